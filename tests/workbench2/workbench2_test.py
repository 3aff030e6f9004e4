#!/usr/bin/env python3
"""The architect's workbench, part 2 (issue 43 items 3-5), end to end on the
built tools. One part a run:

  counting  one program's cycles are one number in apu-run, its text and JSON
            profiles and apu-cosim (start to the HALT, not the settle cycles;
            docs/apu-tools.md "Counting"); in a frame, the steps' apu_cycles,
            the NCs' and the stall profile's are one sum, and the timing
            tables' kernels are the profile's; fp24-run --check counts a vector
            all engines get wrong as one mismatch, its line naming the engines.
  decoding  apu-run prints CC and FLAGS by name, F registers as FP24, A
            registers unsigned and signed, --read's words in hex and decoded;
            apu-run --trace runs on the RTL core by itself and says so;
            fp24-run --trace writes a save file whose filters name the ops and
            flags (the same filters as docs/fp24-units.gtkw's).
  window    mc1 render --trace on a window the traced NC's APU does not run in
            warns on stderr, naming the window and when that APU runs; a busy
            window does not; the summary, the stats and the Gantt chart's
            title name the traced NC as on the RTL core.
  gantt     a 64-NC chart fits a 1400x900 window: opened in headless Chromium
            at that size, the legend's last box shows its colour.

  workbench2_test.py PART BIN_DIR SOURCE_DIR WORK_DIR [CHROMIUM]"""
import json
import os
import re
import shutil
import subprocess
import sys

PART, BIN, SRC, WORK = sys.argv[1:5]
CHROMIUM = sys.argv[5] if len(sys.argv) > 5 else ""


sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "testlib"))
import mc1_testlib as lib  # noqa: E402
lib.setup(f"workbench2 {PART}", work=WORK, bin_dir=BIN)
fail, run, tool, png_pixel = lib.fail, lib.run, lib.tool, lib.png_pixel


def number(pattern, text, what):
    m = re.search(pattern, text)
    if not m:
        fail(f"{what}: no '{pattern}' in:\n{text}")
    return int(m.group(1))


def write(name, text):
    with open(os.path.join(WORK, name), "w") as f:
        f.write(text)


STALL = "  li a1, 20\nloop:\n  lif f1, 1.5\n  mul f2, f1, f1\n  add f3, f2, f1\n  dbnz a1, loop\n  halt\n"
BLOCK = ("@0  000002\n@10 400000 000000 000000 3f0000\n    000000 400000 000000 400000\n"
         "    000000 000000 400000 000000\n    000000 000000 000000 3f0000\n"
         "@20 3f0000 400000 408000 3f0000\n    bf0000 000000 3f0000 3f0000\n")


def program_counts(args, what):
    """The cycles of one program in apu-run, its profiles and apu-cosim."""
    ran = number(r"halted after (\d+) cycles", run([tool("apu-run")] + args).stdout, what + " apu-run")
    text = number(r"APU profile: (\d+) cycles", run([tool("apu-run"), "--profile"] + args).stdout, what + " --profile")
    run([tool("apu-run"), "--profile-json", "p.json"] + args)
    js = json.load(open(os.path.join(WORK, "p.json")))["totals"]["cycles"]
    cosim = number(r"iss and rtl agree on (\d+) cycles; halted", run([tool("apu-cosim")] + args).stdout,
                   what + " apu-cosim")
    counts = {"apu-run": ran, "--profile": text, "--profile-json": js, "apu-cosim": cosim}
    if len(set(counts.values())) != 1:
        fail(f"{what}: the cycles differ between tools: {counts}")
    return ran


def md_kernels(md):
    """{kernel: APU cycles} of the timing tables' per-kernel table."""
    out = {}
    for line in md.splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) > 4 and re.fullmatch(r"r_\w+|unnamed-\d+", cells[0]):
            out[cells[0]] = int(cells[3])
    return out


def counting():
    write("stall.apu", STALL)
    n = program_counts(["stall.apu"], "stall.apu")
    # 2 fetch cycles, 82 words, 20 RAW stalls, the loop exit's miss.
    if n != 105:
        fail(f"stall.apu: {n} cycles, wanted 105 (start to HALT, docs/apu-tools.md)")
    write("block.txt", BLOCK)
    write("end.txt", "@0 000000\n")
    xform4 = os.path.join(SRC, "firmware/kernels/xform4.apu")
    program_counts([xform4, "--data", "block.txt", "--data", "end.txt"], "xform4 stream")
    scene = os.path.join(SRC, "scenes/tiny.json")
    run([tool("mc1"), "render", scene, "--size", "96x64", "--nodes", "2", "--quiet", "--stats", "s.json",
         "--profile", "p.json", "--profile", "p.md"])
    stats = json.load(open(os.path.join(WORK, "s.json")))
    prof = json.load(open(os.path.join(WORK, "p.json")))
    steps = sum(s["apu_cycles"] for s in stats["steps"])
    ncs = sum(n["apu_cycles"] for n in stats["nc"])
    if not steps == ncs == prof["totals"]["cycles"]:
        fail(f"a frame's APU cycles: steps {steps}, NCs {ncs}, stall profile {prof['totals']['cycles']}: wanted one")
    tables = md_kernels(open(os.path.join(WORK, "p.md")).read())
    by_name = {k["name"]: k["cycles"] for k in prof["kernels"]}
    if not tables or tables != by_name:
        fail(f"per kernel: the timing tables {tables}, the stall profile {by_name}")
    # fp24-run --check: one wrong golden vector is one mismatch on all engines.
    write("one.golden", "add 3f0000 3f0000 400000 00\nmul 408000 408000 420000 00\n")
    p = run([tool("fp24-run"), "--check", "one.golden"], want=1)
    if not re.search(r"^one.golden:2: model, rtl, oracle: mul 408000 408000 \(3, 3\): expected 420000 00 \(8; -\), "
                     r"got 422000 00 \(9; -\)\n", p.stdout, re.M):
        fail("fp24-run --check: not one line naming the three engines:\n" + p.stdout)
    if "one.golden: 2 vectors, 1 mismatch: FAIL" not in p.stdout:
        fail("fp24-run --check: the verdict does not count 1 mismatch:\n" + p.stdout)
    write("two.golden", "add 3f0000 3f0000 3f0000 00\nmul 408000 408000 420000 00\nneg 3f0000 bf0000 00\n")
    p = run([tool("fp24-run"), "--check", "two.golden", "--engine", "model"], want=1)
    if "two.golden: 3 vectors, 2 mismatches: FAIL" not in p.stdout:
        fail("fp24-run --check --engine model: wanted 2 mismatches:\n" + p.stdout)


def decoding():
    write("regs.apu", "  lif f1, 1.5\n  lif f2, -0.25\n  li a1, 20\n  li a2, 0xfffd\n  cmp f1, f2\n"
                      "  recip f3, f0\n  halt\n")
    out = run([tool("apu-run"), "regs.apu"]).stdout
    for want in [r"CC 0x4 \(GT\)  FLAGS 0x08 \(DZ\)", r"F1=0x3f8000 \(1\.5\)", r"F2=0xbd0000 \(-0\.25\)",
                 r"F3=0x7f0000 \(inf\)", r"A1=0x0014 \(20\)", r"A2=0xfffd \(65533, -3\)"]:
        if not re.search(want, out):
            fail(f"apu-run's registers: no '{want}' in:\n{out}")
    write("block.txt", BLOCK)
    write("end.txt", "@0 000000\n")
    xform4 = os.path.join(SRC, "firmware/kernels/xform4.apu")
    out = run([tool("apu-run"), xform4, "--data", "block.txt", "--data", "end.txt", "--read", "0x20:8",
               "--read", "0:2"]).stdout
    for want in [r"\[0x000\] 0x000002 \(int 2\) +0x000000 \(0\)\n",
                 r"\[0x020\] 0x408000 \(3\) +0x418000 \(6\) +0x418000 \(6\) +0x3f0000 \(1\)\n",
                 r"\[0x024\] 0xbf0000 \(-1\) +0x400000 \(2\) +0x400000 \(2\) +0x3f0000 \(1\)\n"]:
        if not re.search(want, out):
            fail(f"apu-run --read: no '{want}' in:\n{out}")
    # --trace with the default engine: the RTL core, said on stderr.
    write("stall.apu", STALL)
    p = run([tool("apu-run"), "stall.apu", "--trace", "s.fst"])
    if "stall.apu on rtl: halted after 105 cycles" not in p.stdout or "running on the RTL core" not in p.stderr:
        fail(f"apu-run --trace without --engine: not on the RTL core, or not said:\n{p.stdout}{p.stderr}")
    for f in ["s.fst", "s.fst.gtkw"]:
        if not os.path.getsize(os.path.join(WORK, f)):
            fail(f"apu-run --trace: {f} missing or empty")
    fp24_trace()


def fp24_trace():
    """fp24-run --trace's save file and filters: ops and flags by name."""
    write("v.txt", "add 3f0000 3f0000\nrecip 000000\nsqrt bf0000\nmul 7e0000 7e0000\n")
    p = subprocess.run([tool("fp24-run"), "--engine", "rtl", "--trace", "u.fst"], stdin=open(os.path.join(WORK, "v.txt")),
                       capture_output=True, text=True, timeout=120, cwd=WORK)
    if p.returncode != 0:
        fail(f"fp24-run --trace: exit {p.returncode}\n{p.stderr}")
    save = open(os.path.join(WORK, "u.fst.gtkw")).read()
    if f'[dumpfile] "{os.path.join(WORK, "u.fst")}"' not in save:
        fail("u.fst.gtkw does not name its waveform")
    refs = re.findall(r"^\^(\d+) (.*)\n(TOP\.\S+)$", save, re.M)
    named = {sig: path for _, path, sig in refs}
    for sig, filt in [("TOP.fp24_units.u_add.in_op[2:0]", "add_op"), ("TOP.fp24_units.u_func.in_op[1:0]", "func_op"),
                      ("TOP.fp24_units.u_mul.out_flags[4:0]", "flags"), ("TOP.fp24_units.u_add.out_flags[4:0]", "flags"),
                      ("TOP.fp24_units.u_func.out_flags[4:0]", "flags"),
                      ("TOP.fp24_units.u_func.out_trig_flags[4:0]", "flags")]:
        want = os.path.join(WORK, f"u.fst.{filt}.txt")
        if named.get(sig) != want:
            fail(f"u.fst.gtkw: {sig} is not shown through {want} (got {named.get(sig)})")
    docs = open(os.path.join(SRC, "docs/fp24-units.gtkw")).read()
    for filt in ["add_op", "func_op", "flags"]:
        got = open(os.path.join(WORK, f"u.fst.{filt}.txt")).read()
        kept = open(os.path.join(SRC, f"docs/fp24-units.{filt}.txt")).read()
        if got != kept:
            fail(f"docs/fp24-units.{filt}.txt is not what fp24-run writes (u.fst.{filt}.txt):\n{got}")
        if f"docs/fp24-units.{filt}.txt" not in docs:
            fail(f"docs/fp24-units.gtkw does not load docs/fp24-units.{filt}.txt")
    flags = open(os.path.join(WORK, "u.fst.flags.txt")).read()
    for line in ["00 -", "01 NX", "11 NV|NX", "1F NV|DZ|OF|UF|NX"]:
        if line + "\n" not in flags:
            fail(f"the flags filter has no '{line}':\n{flags}")
    ops = open(os.path.join(WORK, "u.fst.add_op.txt")).read() + open(os.path.join(WORK, "u.fst.func_op.txt")).read()
    for line in ["0 add", "1 sub", "2 cmp", "3 float", "4 fix", "5 neg", "6 abs", "0 recip", "1 sqrt", "2 sin", "3 cos"]:
        if line + "\n" not in ops:
            fail(f"the op filters have no '{line}':\n{ops}")


def window():
    scene = os.path.join(SRC, "scenes/tiny.json")
    base = [tool("mc1"), "render", scene, "--size", "96x64", "--nodes", "2", "--trace", "w.fst"]
    # 1-2 ms: the scene is still being broadcast; no NC's APU runs yet.
    p = run(base + ["--trace-from", "1ms", "--trace-to", "2ms", "--stats", "w.json", "--gantt", "w.svg"])
    m = re.search(r"warning: --trace: NC 1's APU does not run in the window 1\.000 ms to 2\.000 ms.*\n"
                  r"  NC 1's APU runs from ([0-9.]+) ms to ([0-9.]+) ms \((\d+) runs\); the nearest run: ([0-9.]+) ms",
                  p.stderr)
    if not m:
        fail("an idle trace window: no warning naming the window and the APU's span:\n" + p.stderr)
    if not 2.0 <= float(m.group(1)) <= float(m.group(4)) <= float(m.group(2)):
        fail("the APU's span does not come after the window:\n" + p.stderr)
    if "iss engine, RTL core on NC 1" not in p.stdout:
        fail("the summary does not name the traced NC as on the RTL core:\n" + p.stdout)
    if json.load(open(os.path.join(WORK, "w.json"))).get("rtl_nodes") != [1]:
        fail("the stats do not name NC 1 in rtl_nodes")
    if "2 NCs (iss engine, RTL core on NC 1, lpt)" not in open(os.path.join(WORK, "w.svg")).read():
        fail("the Gantt chart's title does not name NC 1 as on the RTL core")
    start = float(m.group(4))
    p = run(base + ["--trace-from", f"{start}ms", "--trace-to", f"{start + 1}ms"])
    if "warning" in p.stderr:
        fail(f"a window with APU work ({start} ms on) warned:\n{p.stderr}")


def gantt():
    if not CHROMIUM:
        print("workbench2 gantt: no chromium; the screenshot is not checked")
    scene = os.path.join(SRC, "scenes/tiny.json")
    run([tool("mc1"), "render", scene, "--size", "96x64", "--nodes", "64", "--block", "8", "--quiet", "--gantt", "g.svg"])
    svg = open(os.path.join(WORK, "g.svg")).read()
    height = float(re.search(r'<svg [^>]*height="([0-9.]+)"', svg).group(1))
    if height > 900:
        fail(f"the 64-NC chart is {height} px high: it does not fit 900")
    boxes = re.findall(r'<rect x="([0-9.]+)" y="([0-9.]+)" width="12" height="12" fill="(#[0-9a-f]{6})"', svg)
    if len(boxes) < 10:
        fail(f"the legend has {len(boxes)} boxes")
    x, y, colour = boxes[-1]
    if float(y) + 12 > height:
        fail(f"the legend's last box ends at {float(y) + 12}, below the chart's {height}")
    if not CHROMIUM:
        return
    shot = os.path.join(WORK, "g.png")
    subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
                    "--window-size=1400,900", f"--screenshot={shot}", "file://" + os.path.join(WORK, "g.svg")],
                   capture_output=True, timeout=120)
    if not os.path.exists(shot):
        fail("chromium wrote no screenshot")
    want = tuple(int(colour[i:i + 2], 16) for i in (1, 3, 5))
    got = png_pixel(shot, int(float(x)) + 6, int(float(y)) + 6)
    if max(abs(a - b) for a, b in zip(got, want)) > 24:
        fail(f"in a 1400x900 window the legend's last box ({x}, {y}) shows {got}, not its colour {want}")


shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
{"counting": counting, "decoding": decoding, "window": window, "gantt": gantt}[PART]()
print(f"workbench2 {PART}: ok")
