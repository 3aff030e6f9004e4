#!/usr/bin/env python3
"""mc1 sweep's answers end to end (docs/platform.md "Sweeps"): a small grid
with a 1-NC point run with --csv and --plot; the CSV's columns and values
(the 1-NC point's speedup and efficiency 1, efficiency = speedup / NCs,
n/a where the grid has no 1-NC point, every frame's hash equal); the merge of
the run's report writes the same table, and of a report whose point claims
another image names the points of each image (exit 1); the SVG opened in headless
Chromium: its DOM has a line per series in each panel and a bar per point,
and its screenshot is not blank. Also --out-dir missing refused before point
0 (exit 2, nothing written).
  sweep_report_test.py MC1 SCENE WORK_DIR [CHROMIUM]"""
import csv
import os
import shutil
import subprocess
import sys


sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "testlib"))
import mc1_testlib as lib  # noqa: E402
lib.setup("sweep_report_test")
fail, run, png_pixels = lib.fail, lib.run, lib.png_pixels


def check_csv(path, grid_has_one_nc=True):
    rows = list(csv.DictReader(open(path)))
    want = ["point", "scene", "frame", "width", "height", "nodes", "schedule", "block", "frame_ms", "speedup",
            "efficiency", "apu_utilization", "critical_block", "critical_block_ms", "critical_share", "critical_path",
            "host_seconds", "complete", "image_fnv1a", "share_download", "share_idle"]
    missing = [c for c in want if c not in rows[0]]
    if missing:
        fail(f"{path}: no column {missing}")
    for r in rows:
        if not grid_has_one_nc:
            if r["speedup"] != "n/a" or r["efficiency"] != "n/a":
                fail(f"{path}: point {r['point']}: a speedup without a 1-NC point")
            continue
        s, e, n = float(r["speedup"]), float(r["efficiency"]), int(r["nodes"])
        if n == 1 and (s != 1.0 or e != 1.0):
            fail(f"{path}: point {r['point']}: 1 NC has speedup {s}, efficiency {e}")
        if abs(e - s / n) > 1e-5 * max(1, s):
            fail(f"{path}: point {r['point']}: efficiency {e} is not speedup {s} / {n} NCs")
        one = [x for x in rows if x["nodes"] == "1" and x["schedule"] == r["schedule"] and x["block"] == r["block"]]
        if abs(s - float(one[0]["frame_ms"]) / float(r["frame_ms"])) > 1e-5 * s:
            fail(f"{path}: point {r['point']}: speedup {s} is not T(1 NC) / T")
        shares = sum(float(v) for k, v in r.items() if k.startswith("share_"))
        # Each share is written with 6 significant digits (off by 5e-7 at
        # most, all below 1): the sum is 1 to within that times their number.
        if abs(shares - 1) > 5e-7 * sum(1 for k in r if k.startswith("share_")):
            fail(f"{path}: point {r['point']}: the steps' shares add up to {shares}")
        if not 0 < float(r["critical_share"]) <= 1 or r["complete"] != "yes":
            fail(f"{path}: point {r['point']}: critical share {r['critical_share']}, complete {r['complete']}")
    if len({r["image_fnv1a"] for r in rows}) != 1:
        fail(f"{path}: the points' frames differ")
    return rows


def check_svg(svg, chromium, work, series, points):
    dom = run([chromium, "--headless", "--no-sandbox", "--disable-gpu", "--dump-dom", "file://" + svg]).stdout
    lines, bars = dom.count('class="series"'), dom.count('class="step-bar"')
    if lines != 3 * series:
        fail(f"{svg}: the DOM has {lines} series lines, wanted {3 * series}")
    if bars < points:
        fail(f"{svg}: the DOM has {bars} step bars for {points} points")
    shot = os.path.join(work, "sweep.png")
    run([chromium, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars", "--window-size=1140,700",
         "--screenshot=" + shot, "file://" + svg])
    w, h, bpp, rows = png_pixels(shot)
    colours = set()
    for y in range(0, h, 3):
        for x in range(0, w, 3):
            colours.add(rows[y][x * bpp:x * bpp + 3])
    white = sum(1 for y in range(0, h, 3) for x in range(0, w, 3) if rows[y][x * bpp:x * bpp + 3] == b"\xff\xff\xff")
    if len(colours) < 8 or white > 0.97 * (h // 3 + 1) * (w // 3 + 1):
        fail(f"{shot}: blank ({len(colours)} colours, {white} white samples)")
    print(f"sweep_report_test: {svg} rendered by Chromium: {len(colours)} colours in {w}x{h}")


def main():
    mc1, scene, work = sys.argv[1:4]
    chromium = sys.argv[4] if len(sys.argv) > 4 and sys.argv[4] else shutil.which("chromium")
    if not chromium:
        fail("no chromium (tools/setup.sh installs it)")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(os.path.join(work, "pts"))
    grid = ["--scene", scene, "--size", "32x24", "--nodes", "1,2,4", "--schedules", "lpt,static", "--blocks", "8",
            "--threads", "1"]
    out = run([mc1, "sweep", *grid, "--out-dir", os.path.join(work, "pts"), "--json", os.path.join(work, "s.json"),
               "--csv", os.path.join(work, "s.csv"), "--plot", os.path.join(work, "s.svg")]).stdout
    if "every frame equal across its points (6 points)" not in out:
        fail("no line on the frames compared:\n" + out)
    rows = check_csv(os.path.join(work, "s.csv"))
    if len(rows) != 6:
        fail(f"s.csv: {len(rows)} points, not 6")
    run([mc1, "sweep", "--merge", os.path.join(work, "s.json"), "--quiet", "--json", os.path.join(work, "m.json"),
         "--csv", os.path.join(work, "m.csv")])
    strip = lambda p: [l.split(",")[:16] + l.split(",")[17:] for l in open(p)]  # all but host_seconds
    if strip(os.path.join(work, "s.csv")) != strip(os.path.join(work, "m.csv")):
        fail("the merge's table differs from the run's")
    check_svg(os.path.join(work, "s.svg"), chromium, work, series=2, points=6)
    # A report whose point 2 claims another image: the merge names the points of each image, exit 1.
    text = open(os.path.join(work, "s.json")).read()
    image = rows[2]["image_fnv1a"]
    lines = text.split("\n")
    at = next(i for i, l in enumerate(lines) if '"index": 2,' in l)
    lines[at] = lines[at].replace(image, "0123456789abcdef")
    open(os.path.join(work, "bad.json"), "w").write("\n".join(lines))
    p = run([mc1, "sweep", "--merge", os.path.join(work, "bad.json"), "--json", os.path.join(work, "bad-m.json")], 1)
    want = (f"frames differ: tiny.json frame 0: points 0, 1, 3, 4, 5 give image {image}, "
            "point 2 gives image 0123456789abcdef")
    if want not in p.stderr:
        fail("the merge of a report with a differing frame did not say which points:\n" + p.stdout + p.stderr)
    # No 1-NC point: n/a, said.
    out = run([mc1, "sweep", *grid[:5], "2,4", *grid[6:], "--out-dir", os.path.join(work, "pts"),
               "--csv", os.path.join(work, "n.csv")]).stdout
    check_csv(os.path.join(work, "n.csv"), grid_has_one_nc=False)
    if "speedup and efficiency n/a: no 1-NC point" not in out:
        fail("no line saying the speedups are n/a:\n" + out)
    # --out-dir missing: refused before point 0, nothing written.
    p = run([mc1, "sweep", *grid, "--out-dir", os.path.join(work, "none"), "--csv", os.path.join(work, "x.csv")], 2)
    if "point 0" in p.stdout or os.path.exists(os.path.join(work, "x.csv")) or "--out-dir" not in p.stderr:
        fail("a missing --out-dir was not refused before point 0:\n" + p.stdout + p.stderr)
    print("sweep_report_test: passed")


main()
