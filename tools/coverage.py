#!/usr/bin/env python3
"""Coverage of the APU: code coverage of the verilated RTL and functional
coverage of the core and the FP24 units (docs/fp24-verification.md "Coverage").

usage:
  coverage.py run [--build DIR] [--quick]   configure DIR (default build-cov/)
        with -DMC1_RTL_COVERAGE=ON, build what the regressions need, run them
        with MC1_COVERAGE_DAT set, merge the data (verilator_coverage), write
        DIR/reports/coverage.info, coverage-html/ (genhtml), coverage.json and
        coverage.txt (a line per module), then check the goals (exit 1 if one
        is missed). tools/test.sh --coverage runs this.
  coverage.py goals --report FILE.json      check the goals on a report
  coverage.py close-check --cosim EXE --waivers FILE --work DIR
        a short --close-coverage run of apu-cosim: every core bin hit or waived
  coverage.py summary --dat FILE.dat... --functional F.json --waivers FILE --out DIR
        only the merge and the reports, from data already written

The goals: every functional bin hit or waived with a reason (tb/coverage/
waivers.txt); RTL (apu_rtl/*.sv) line >= 98 %, branch >= 95 %, toggle >= 90 %
(toggles outside the bits waived as constant in the waiver file, lines
"toggle:MODULE.SIGNAL[BITS] REASON": shell wildcards in MODULE.SIGNAL, BITS
a list of N, A-B and A-B/S, every S-th bit from A; a waived bit that toggles
is reported and misses the goal). Exit status: 0 goals met, 1 a goal missed or a
step failed, 2 usage error.
"""

import argparse
import fnmatch
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WAIVERS = os.path.join(ROOT, "tb", "coverage", "waivers.txt")
GOALS = {"line": 98.0, "branch": 95.0, "toggle": 90.0}
TARGETS = ["fp24-regress", "fp24_round_test", "apu-cosim", "apu_hand_timed_test", "mc1"]


def fail(msg, code=1):
    print(f"coverage: {msg}", file=sys.stderr)
    sys.exit(code)


def read_waivers(path):
    """[(pattern, reason, line)] of the waiver file; a line without a reason is an error."""
    out = []
    with open(path) as f:
        for n, line in enumerate(f, 1):
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            parts = line.split(None, 1)
            if len(parts) < 2:
                fail(f"{path}:{n}: waiver of {parts[0]} gives no reason", 2)
            out.append((parts[0], parts[1], n))
    return out


def waived(waivers, name):
    return next((w for w in waivers if fnmatch.fnmatchcase(name, w[0])), None)


# ---- Verilator coverage data -------------------------------------------------

def parse_key(key):
    """Verilator's point key: \\001name\\002value pairs."""
    fields = {}
    for part in key.split("\x01"):
        if "\x02" in part:
            k, v = part.split("\x02", 1)
            fields[k] = v
    return fields


def read_dat(paths):
    """Merged points: (kind, file, line, column/comment) -> [count, module, comment]."""
    points = {}
    for path in paths:
        with open(path, errors="replace") as f:
            for line in f:
                if not line.startswith("C '"):
                    continue
                end = line.rfind("' ")
                fields = parse_key(line[3:end])
                count = int(line[end + 2:])
                page = fields.get("page", "")
                kind = page.split("/", 1)[0].replace("v_", "")
                module = page.split("/", 1)[1] if "/" in page else "?"
                ident = (kind, fields.get("f", "?"), fields.get("l", "0"), fields.get("n", ""), fields.get("o", ""))
                p = points.setdefault(ident, [0, module, fields.get("o", ""), fields.get("f", "?")])
                p[0] += count
    return points


def is_rtl(path):
    """The RTL under test: apu_rtl/*.sv (not the engine's wrappers and stand-ins)."""
    return os.path.dirname(os.path.abspath(path)) == os.path.join(ROOT, "apu_rtl")


def bit_set(spec):
    """The bits of a toggle waiver's [BITS]: "1,3", "0-10", "1-31/2"."""
    bits = set()
    for item in spec.split(","):
        rng, _, step = item.partition("/")
        first, _, last = rng.partition("-")
        bits.update(range(int(first), int(last or first) + 1, int(step or 1)))
    return bits


def toggle_waived(toggle_waivers, module, comment):
    """Whether toggle point `comment` (SIGNAL[BIT]) of `module` is waived."""
    name, _, bit = comment.partition("[")
    for pattern, _reason, _n in toggle_waivers:
        m = re.fullmatch(r"(.*)\[([0-9,/-]+)\]", pattern)
        if not m:
            if fnmatch.fnmatchcase(f"{module}.{comment}", pattern):
                return True
        elif fnmatch.fnmatchcase(f"{module}.{name}", m.group(1)) and bit.rstrip("]").isdigit() \
                and int(bit.rstrip("]")) in bit_set(m.group(2)):
            return True
    return False


def code_figures(points, toggle_waivers, toggled_waived=None):
    """Per module and for the RTL as a whole: {kind: [hit, total]}; waived toggles
    left out (a waived one that toggled is added to `toggled_waived`)."""
    modules, rtl, waived_bits = {}, {"line": [0, 0], "branch": [0, 0], "toggle": [0, 0]}, 0
    for (kind, path, _line, _col, comment), (count, module, _c, _f) in points.items():
        if kind not in rtl:
            continue
        if kind == "toggle" and toggle_waived(toggle_waivers, module, comment):
            waived_bits += 1
            if count and toggled_waived is not None:
                toggled_waived.append(f"{module}.{comment}")
            continue
        m = modules.setdefault((module, os.path.relpath(path, ROOT)), {"line": [0, 0], "branch": [0, 0],
                                                                         "toggle": [0, 0]})
        m[kind][1] += 1
        m[kind][0] += count > 0
        if is_rtl(path):
            rtl[kind][1] += 1
            rtl[kind][0] += count > 0
    return modules, rtl, waived_bits


def pct(hit_total):
    hit, total = hit_total
    return round(100.0 * hit / total, 2) if total else 100.0


def functional_figures(bins, waivers):
    n = len(bins)
    hit = sum(1 for c in bins.values() if c)
    w = sum(1 for name, c in bins.items() if not c and waived(waivers, name))
    return {"bins": n, "hit": hit, "waived": w}


def merge_bins(paths):
    bins = {}
    for p in paths:
        with open(p) as f:
            for name, c in json.load(f)["bins"].items():
                bins[name] = bins.get(name, 0) + c
    return bins


def write_reports(out, dats, functional_jsons, waivers_path):
    """coverage.info, coverage-html/, coverage.json, coverage.txt in out/."""
    os.makedirs(out, exist_ok=True)
    merged = os.path.join(out, "coverage.dat")
    subprocess.run(["verilator_coverage", "--write", merged] + dats, check=True, stdout=subprocess.DEVNULL)
    info = os.path.join(out, "coverage.info")
    subprocess.run(["verilator_coverage", "--write-info", info, merged], check=True, stdout=subprocess.DEVNULL)
    html = os.path.join(out, "coverage-html")
    if shutil.which("genhtml"):
        shutil.rmtree(html, ignore_errors=True)
        subprocess.run(["genhtml", "--quiet", "--branch-coverage", "--output-directory", html, info], check=True)
    else:
        print("coverage: genhtml not found (tools/setup.sh installs lcov): no HTML report", file=sys.stderr)
    all_waivers = read_waivers(waivers_path)
    toggle_waivers = [(p[len("toggle:"):], r, n) for p, r, n in all_waivers if p.startswith("toggle:")]
    bin_waivers = [w for w in all_waivers if not w[0].startswith("toggle:")]
    toggled_waived = []
    modules, rtl, waived_bits = code_figures(read_dat([merged]), toggle_waivers, toggled_waived)
    bins = merge_bins(functional_jsons)
    report = {"rtl": {k: pct(v) for k, v in rtl.items()},
              "functional": functional_figures(bins, bin_waivers),
              "rtl_points": {k: {"hit": v[0], "total": v[1]} for k, v in rtl.items()},
              "toggle_bits_waived": waived_bits,
              "modules": {f"{m} ({p})": {k: pct(v) for k, v in fig.items()} for (m, p), fig in sorted(modules.items())},
              "functional_empty": sorted(n for n, c in bins.items() if not c and not waived(bin_waivers, n)),
              "functional_waived_but_hit": sorted(n for n, c in bins.items() if c and waived(bin_waivers, n)),
              "toggle_waived_but_toggled": sorted(toggled_waived)}
    with open(os.path.join(out, "coverage.json.tmp"), "w") as f:
        json.dump(report, f, indent=1)
    os.replace(os.path.join(out, "coverage.json.tmp"), os.path.join(out, "coverage.json"))
    write_text(os.path.join(out, "coverage.txt"), report, modules)
    with open(os.path.join(out, "functional.json"), "w") as f:
        json.dump({"bins": bins}, f, indent=1)
    return report


def write_text(path, report, modules):
    lines = ["Code coverage of the verilated models, per module (points hit / points, %):",
             f"{'module (file)':58} {'line':>16} {'branch':>16} {'toggle':>18}"]
    for (m, p), fig in sorted(modules.items()):
        cells = [f"{v[0]}/{v[1]} {pct(v):6.2f}" if v[1] else "-" for v in (fig['line'], fig['branch'], fig['toggle'])]
        rtl = "" if is_rtl(os.path.join(ROOT, p)) else "  (engine wrapper, not in the RTL figure)"
        lines.append(f"{m + ' (' + p + ')':58} {cells[0]:>16} {cells[1]:>16} {cells[2]:>18}{rtl}")
    r = report["rtl"]
    lines.append(f"RTL (apu_rtl/*.sv): line {r['line']} %, branch {r['branch']} %, toggle {r['toggle']} % "
                 f"({report['toggle_bits_waived']} toggle points waived as constant)")
    f = report["functional"]
    lines.append(f"Functional: {f['bins']} bins, {f['hit']} hit, {f['waived']} waived, "
                 f"{len(report['functional_empty'])} empty and not waived")
    for n in report["functional_empty"]:
        lines.append(f"  empty: {n}")
    for n in report["functional_waived_but_hit"]:
        lines.append(f"  waived but hit: {n}")
    for n in report.get("toggle_waived_but_toggled", []):
        lines.append(f"  toggle waived as constant but toggled: {n}")
    with open(path, "w") as out:
        out.write("\n".join(lines) + "\n")


# ---- goals -----------------------------------------------------------------------

def check_goals(report):
    ok = True
    for kind, goal in GOALS.items():
        got = report["rtl"][kind]
        met = got >= goal
        ok &= met
        print(f"coverage goal: RTL {kind} >= {goal} %: {got} % {'met' if met else 'MISSED'}")
    f = report["functional"]
    met = f["hit"] + f["waived"] == f["bins"]
    ok &= met
    print(f"coverage goal: every functional bin hit or waived: {f['bins']} bins, {f['hit']} hit, "
          f"{f['waived']} waived: {'met' if met else 'MISSED'}")
    for n in report.get("functional_empty", [])[:40]:
        print(f"  empty: {n}")
    wrong = report.get("toggle_waived_but_toggled", []) + report.get("functional_waived_but_hit", [])
    for n in wrong[:40]:
        print(f"  waived but hit or toggled: {n}")
    return ok and not wrong


def cmd_goals(args):
    if not os.path.exists(args.report):
        print(f"coverage: {args.report}: no report (tools/test.sh --coverage writes it); the goals: "
              + ", ".join(f"RTL {k} >= {g} %" for k, g in GOALS.items()) + ", every functional bin hit or waived")
        return 1
    with open(args.report) as f:
        return 0 if check_goals(json.load(f)) else 1


def cmd_close_check(args):
    os.makedirs(args.work, exist_ok=True)
    out = os.path.join(args.work, "functional.json")
    cmd = [args.cosim, "--random", str(args.max), "--seed", str(args.seed), "--coverage", out,
           "--waivers", args.waivers, "--close-coverage", str(args.quiet)]
    print(" ".join(cmd))
    rc = subprocess.run(cmd).returncode
    if rc != 0:
        return 1
    with open(out) as f:
        bins = json.load(f)["bins"]
    waivers = [w for w in read_waivers(args.waivers) if not w[0].startswith("toggle:")]
    empty = [n for n, c in bins.items() if n.startswith("core.") and not c and not waived(waivers, n)]
    for n in empty:
        print(f"apu_coverage_close: core bin neither hit nor waived: {n}")
    hit_waived = [n for n, c in bins.items() if c and waived(waivers, n)]
    for n in hit_waived:
        print(f"apu_coverage_close: bin waived as unreachable but hit: {n}")
    core = [n for n in bins if n.startswith("core.")]
    print(f"apu_coverage_close: {len(core)} core bins, {sum(1 for n in core if bins[n])} hit, {len(empty)} empty")
    return 1 if empty or hit_waived else 0


# ---- run -------------------------------------------------------------------------

def sh(cmd, env=None, **kw):
    print("+ " + " ".join(cmd), flush=True)
    t0 = time.time()
    subprocess.run(["nice"] + cmd, check=True, env=env, **kw)
    print(f"  ({time.time() - t0:.0f} s)", flush=True)


def cmd_run(args):
    build = os.path.abspath(args.build)
    sh(["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release", "-DMC1_RTL_COVERAGE=ON"],
       stdout=subprocess.DEVNULL)
    sh(["cmake", "--build", build, "-j2", "--target"] + TARGETS)
    data = os.path.join(build, "coverage")
    shutil.rmtree(data, ignore_errors=True)
    os.makedirs(data)
    reports = os.path.join(build, "reports")
    os.makedirs(reports, exist_ok=True)
    env = dict(os.environ)

    def run(name, cmd, **kw):
        env["MC1_COVERAGE_DAT"] = os.path.join(data, name + "-%p.dat")
        sh(cmd, env=env, **kw)

    bin_dir = os.path.join(build, "bin")
    exe = lambda name: os.path.join(bin_dir, name)
    test_exe = lambda name: os.path.join(bin_dir, name)  # the test programs are in bin/ too
    func = [os.path.join(data, "cosim.json"), os.path.join(data, "close.json")]
    random_pairs = "100000" if not args.quick else "1000"
    run("fp24-regress", [exe("fp24-regress"), "--random", random_pairs, "--threads", "2"]
        + (["--ops", "add,sub,mul,cmp,float,neg,abs,fix"] if args.quick else []), stdout=subprocess.DEVNULL)
    run("fp24-round", [test_exe("fp24_round_test")], stdout=subprocess.DEVNULL)
    run("hand-timed", [test_exe("apu_hand_timed_test")], stdout=subprocess.DEVNULL)
    n = "100" if args.quick else "1000"
    run("cosim", [exe("apu-cosim"), "--random", n, "--seed", "1", "--coverage", func[0], "--waivers", WAIVERS])
    run("close", [exe("apu-cosim"), "--random", "3000", "--seed", "7", "--first", "1000000", "--coverage", func[1],
                  "--waivers", WAIVERS, "--close-coverage", "100" if args.quick else "300"])
    run("render", [exe("mc1"), "render", os.path.join(ROOT, "scenes", "tiny.json"), "--size", "32x24",
                   "--engine", "rtl", "--out", os.path.join(data, "render.png")], stdout=subprocess.DEVNULL)
    dats = sorted(glob.glob(os.path.join(data, "*.dat")))
    if not dats:
        fail(f"no coverage data in {data} (was {build} built with MC1_RTL_COVERAGE=ON?)")
    report = write_reports(reports, dats, func, WAIVERS)
    print(open(os.path.join(reports, "coverage.txt")).read())
    print(f"coverage: {reports}/coverage.json, coverage.txt, coverage.info, coverage-html/index.html")
    return 0 if check_goals(report) else 1


def cmd_summary(args):
    report = write_reports(args.out, args.dat, args.functional, args.waivers)
    print(open(os.path.join(args.out, "coverage.txt")).read())
    return 0 if check_goals(report) else 1


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run", help="build build-cov/, run the regressions, report, check the goals")
    r.add_argument("--build", default=os.path.join(ROOT, "build-cov"))
    r.add_argument("--quick", action="store_true", help="fewer vectors and programs (a smoke run)")
    g = sub.add_parser("goals", help="check the goals on a coverage.json")
    g.add_argument("--report", required=True)
    c = sub.add_parser("close-check", help="a short --close-coverage run: every core bin hit or waived")
    c.add_argument("--cosim", required=True)
    c.add_argument("--waivers", required=True)
    c.add_argument("--work", required=True)
    c.add_argument("--max", type=int, default=1500)
    c.add_argument("--quiet", type=int, default=150)
    c.add_argument("--seed", type=int, default=11)
    s = sub.add_parser("summary", help="merge and report data already written")
    s.add_argument("--dat", nargs="+", required=True)
    s.add_argument("--functional", nargs="+", required=True)
    s.add_argument("--waivers", default=WAIVERS)
    s.add_argument("--out", required=True)
    args = p.parse_args()
    return {"run": cmd_run, "goals": cmd_goals, "close-check": cmd_close_check, "summary": cmd_summary}[args.cmd](args)


if __name__ == "__main__":
    sys.exit(main())
