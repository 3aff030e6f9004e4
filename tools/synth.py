#!/usr/bin/env python3
"""Open-flow synthesis report of the APU RTL (docs/apu-rtl.md "Synthesis").

    synth.py [--quick] [--units U,U,...] [--no-ice40] [--check-form quick|full]
             [--require-check] [--ice40-units U,...] [--rtl DIR --out DIR] BUILD_DIR

Reads the same sources Verilator does (apu_rtl/*.sv and BUILD_DIR/generated/
apu_pkg.sv, fp24_rom.svh) with Debian's Yosys 0.23 and, per unit:
  - checks: hierarchy, proc, `check -assert`, no latch;
  - the unit's gate-level netlist, written by tools/netlist.py (the one
    netlist writer: BUILD_DIR/netlist/U.v and .json), and its check
    (docs/apu-rtl.md "Gate-level checks"): a netlist without a passing
    check record gets its check run first (--check-form, default quick);
    a check that fails, or with --require-check one that was not run,
    exits 1 naming the unit, and no figure of that unit is reported;
  - from that checked netlist, generic `synth` (memories kept as memories): cells, flip-flops, inferred
    memories, and per pipeline stage the cells, flip-flops and logic depth in
    gate levels (tools/synth_depth.py), cross-checked with `ltp -noff`; the
    deepest path into every register, and for apu_core those paths by
    pipeline stage (the issue cycle, each unit's own stages);
  - `synth_ice40` (tools/netlist.py --flow ice40, its netlist checked the
    same way on a thinned quick set) and, where the result fits an HX8K,
    nextpnr-ice40 Fmax.
Writes BUILD_DIR/reports/synth.txt and synth.json (work files in
BUILD_DIR/reports/synth/), each unit with the check its netlists passed.
--ice40-units: the units that get the iCE40 step (default all; fp24_func's
synth_ice40 alone takes a quarter of an hour).
--rtl DIR --out DIR: a copy of apu_rtl/ instead, everything written into
DIR (tb/netlist/netlist_planted_bug.cmake: a planted bug must stop the
report).
--quick runs the checks only (the default test suite's form) and writes
nothing but the work files.
Exit 0; 1 when a check fails (an error, a latch, a problem `check` found);
2 on a usage error or a missing tool.
"""
import json
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import netlist  # noqa: E402
import synth_depth  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RTL = os.path.join(ROOT, "apu_rtl")
UNITS = ["fp24_mul", "fp24_add", "fp24_func", "apu_core"]
# iCE40HX8K (ct256 package): 7680 logic cells, 32 x 4 kbit block RAM.
HX8K = {"name": "iCE40HX8K-CT256", "nextpnr": ["--hx8k", "--package", "ct256"],
        "luts": 7680, "ffs": 7680, "bram": 32, "bram_bits": 32 * 4096}
LATCH_TYPES = "t:$dlatch t:$adlatch t:$dlatchsr t:$_DLATCH_* t:$_DLATCHSR_*"


class CheckFailed(Exception):
    pass


def sources(gen, rtl=None):
    """Packages first, then the rest (tools/netlist.py's sources())."""
    return netlist.sources(gen, rtl)


def yosys(script, log, what):
    """Runs a Yosys script; a failure raises CheckFailed naming the log."""
    with open(log, "w") as f:
        rc = subprocess.run(["yosys", "-q", "-l", log + ".full", "-p", script],
                            stdout=f, stderr=subprocess.STDOUT).returncode
    if rc != 0:
        with open(log) as f:
            tail = f.read().strip().splitlines()[-5:]
        raise CheckFailed(f"{what}: yosys failed (log {log}.full):\n  " + "\n  ".join(tail))
    with open(log + ".full") as f:
        return f.read()


def read_cmd(gen, top):
    return netlist.read_cmd(gen, top)


def check_unit(gen, top, work):
    """Elaborates, runs proc and check: returns the number of latches (must be 0)."""
    log = yosys(f"{read_cmd(gen, top)}; proc; flatten; opt_clean; check -assert;"
                f" tee -o {work}/{top}.latches.txt select -count {LATCH_TYPES}",
                f"{work}/{top}.check.log", f"{top}: read/proc/check")
    with open(f"{work}/{top}.latches.txt") as f:
        m = re.search(r"(\d+) objects", f.read())
    latches = int(m.group(1)) if m else -1
    inferred = len(re.findall(r"^Latch inferred", log, re.M))
    if latches != 0 or inferred != 0:
        raise CheckFailed(f"{top}: {max(latches, inferred)} latch(es) (log {work}/{top}.check.log.full)")
    return 0


def int_param(v):
    return int(v, 2) if isinstance(v, str) else int(v)


def checked(build, top, flow, form, run_checks, log):
    """The unit's netlist (tools/netlist.py write) and the record of the
    check it passed; CheckFailed when the check fails, or is missing and
    `run_checks` is off: no figures of that netlist."""
    name = netlist.flow_name(top, flow)
    try:
        # the netlist's lock held: no other writer replaces it until its
        # files are copied, the check's sha256 the copy's
        with netlist.holding(build, top, flow):
            net = netlist.write(build, top, log, flow)
            rec = netlist.passing_record(build, top, net["sha256"], flow)
            if rec is None:
                if not run_checks:
                    raise CheckFailed(f"{name}: its netlist {net['v']} (sha256 {net['sha256'][:16]}) has no "
                                      f"passing check: no figures (tools/netlist.py check --units {top}"
                                      f"{' --flow ' + flow if flow != 'generic' else ''} {build})")
                log(f"synth: {name}: no passing check of this netlist: running its {form} check")
                rec = netlist.check(build, top, form, jobs=2, log=log, flow=flow)
            work = os.path.join(build, "reports", "synth") if netlist.OUT_DIR is None else netlist.OUT_DIR
            copies = {}
            for k in ("v", "json", "log"):
                copies[k] = os.path.join(work, os.path.basename(net[k]) + ".checked")
                shutil.copyfile(net[k], copies[k])
            sha = netlist.sha256_file(copies["v"])
            if rec.get("netlist_sha256") != sha:
                raise CheckFailed(f"{name}: the checked netlist's sha256 {rec.get('netlist_sha256')} is not "
                                  f"{net['v']}'s {sha}")
            net = dict(net, sha256=sha, json=copies["json"], log=copies["log"])
    except netlist.Failed as e:
        raise CheckFailed(f"{name}: netlist check failed, no figures of it reported:\n{e}")
    except netlist.Usage as e:
        raise CheckFailed(f"{name}: netlist check could not run, no figures of it reported: {e}")
    summary = {k: rec.get(k) for k in ("form", "date", "against", "sets", "vectors", "programs", "seconds")
               if rec.get(k) is not None}
    return net, {"netlist": os.path.relpath(net["v"], build), "sha256": net["sha256"],
                 "check": summary, "passed": netlist.describe(rec)}


def generic(gen, top, work, net):
    """Generic synthesis, memories kept: counts and stages of the gate
    netlist `net` (tools/netlist.py's generic flow: synth's own script,
    `fine:` without memory_map, so a memory stays one $mem_v2 cell,
    reported with its bits, instead of becoming flip-flops)."""
    with open(net["log"]) as f:
        log = f.read()
    with open(net["json"]) as f:
        mod = json.load(f)["modules"][top]
    memories, n_ff, n_cells = [], 0, 0
    for name, c in mod["cells"].items():
        t = c["type"]
        if t.startswith("$mem"):
            p = c["parameters"]
            width, size = int_param(p["WIDTH"]), int_param(p["SIZE"])
            memories.append({"name": memory_name(c, name), "width": width, "words": size, "bits": width * size,
                             "read_ports": int_param(p["RD_PORTS"]), "write_ports": int_param(p["WR_PORTS"]),
                             "sync_read": int_param(p["RD_CLK_ENABLE"]) != 0})
            continue
        n_cells += 1
        if synth_depth.is_ff(t):
            n_ff += len(c["connections"].get("Q", [1]))
    net_ = synth_depth.Netlist(mod)
    stages = synth_depth.analyse(mod, net_)
    ltp_count = synth_depth.analyse(mod, net_, read_tree=False)["ltp"]
    m = re.search(r"Longest topological path in \S+ \(length=(\d+)\)", log)
    # Two counts of one quantity (an asynchronous read as one level, as ltp
    # counts it): a disagreement is a bug in synth_depth.py.
    if m is None or int(m.group(1)) != ltp_count:
        raise CheckFailed(f"{top}: depth {ltp_count} but `ltp -noff` says "
                          f"{m.group(1) if m else 'nothing'} (log {net['log']})")
    paths = synth_depth.paths(mod, net_)
    return {"cells": n_cells, "flip_flops": n_ff, "memories": memories,
            "memory_bits": sum(x["bits"] for x in memories),
            "stages": stages["stages"], "loop": stages["loop"], "to_outputs": stages["outputs"],
            "depth": stages["ltp"], "ltp_noff": int(m.group(1)) if m else None,
            "paths": paths, "stages_by_name": stages_by_name(paths) if top == "apu_core" else None}


# The FP units' instances in apu_core: a path from one of their registers to
# another of the same instance is that unit's own stage; every other path is
# the cycle of the word (docs/apu-rtl.md "One cycle").
UNIT_INSTANCES = ("u_mul", "u_add", "u_func")


# The core's D/I registers: a path into them is the decode stage (the word on
# the program memory's output, the F register read with its write-first
# bypass and the units' results of the next cycle, the LD bypass's select),
# docs/apu-rtl.md "One cycle".
DECODE_REGISTERS = ("i_word_q", "opnd_q", "byp_ld_q")


def stage_of(path):
    """The pipeline stage a register-to-register path belongs to: "decode"
    (into the D/I registers), "issue" (the word's cycle in I: interlock, the
    late bypass, a unit's stage-1 logic, the sequencer up to the program
    memory's address, the writes) or a unit's own stage, "u_add s2" (named
    by the register it ends in)."""
    to, src = path["to"], path["from"]
    top = to.split(".", 1)[0]
    if re.sub(r"\[.*$", "", top) in DECODE_REGISTERS:
        return "decode"
    if top not in UNIT_INSTANCES or not src.startswith(top + "."):
        return "issue"
    inst, leaf = to.rsplit(".", 1)
    m = re.match(r"s(\d+)_", leaf)
    if m and m.group(1) == "1":
        return "issue"  # stage 1 latches the issue cycle's operands (a unit's own result by the bypass)
    return f"{inst} s{m.group(1)}" if m else f"{inst} {leaf}"


def stages_by_name(paths):
    """Per stage_of() class: the deepest path, and the registers it ends in
    with their own deepest paths (deepest first), in the order decode, issue, then
    the units' stages."""
    out = {}
    for p in paths:  # deepest first
        e = out.setdefault(stage_of(p), {"stage": stage_of(p), "depth": p["depth"], "path": p, "ends": []})
        e["ends"].append({"to": p["to"], "depth": p["depth"], "from": p["from"]})

    def key(e):
        if e["stage"] in ("decode", "issue"):
            return (0, e["stage"], 0)
        inst, _, st = e["stage"].partition(" ")
        return (1, inst, int(st[1:]) if re.fullmatch(r"s\d+", st) else 99)
    return sorted(out.values(), key=key)


def memory_name(cell, name):
    """A memory's source name (synth_depth.memory_name of its MEMID)."""
    return synth_depth.memory_name(cell["parameters"].get("MEMID", name))


def ice40(build, top, work, report, form, run_checks, log):
    """synth_ice40 (tools/netlist.py --flow ice40, checked), then
    nextpnr-ice40 on an HX8K when the netlist fits it."""
    if report["memory_bits"] > HX8K["bram_bits"] or any(not m["sync_read"] for m in report["memories"]):
        big = report["memory_bits"] > HX8K["bram_bits"]
        why = (f"{report['memory_bits']} memory bits, the HX8K has {HX8K['bram_bits']} of block RAM"
               if big else "an asynchronously read memory cannot be block RAM")
        return {"part": HX8K["name"], "fits": False, "reason": why}
    ice, chk = checked(build, top, "ice40", form, run_checks, log)
    net = ice["json"]
    with open(net) as f:
        cells = json.load(f)["modules"][top]["cells"].values()
    count = {}
    for c in cells:
        count[c["type"]] = count.get(c["type"], 0) + 1
    luts = count.get("SB_LUT4", 0)
    ffs = sum(n for t, n in count.items() if t.startswith("SB_DFF"))
    bram = count.get("SB_RAM40_4K", 0)
    res = {"part": HX8K["name"], "luts": luts, "flip_flops": ffs, "carries": count.get("SB_CARRY", 0),
           "bram": bram, "netlist": chk}
    if luts > HX8K["luts"] or ffs > HX8K["ffs"] or bram > HX8K["bram"]:
        res.update(fits=False, reason=f"{luts} LUTs, {ffs} FFs, {bram} BRAMs; the HX8K has "
                                      f"{HX8K['luts']} logic cells and {HX8K['bram']} BRAMs")
        return res
    log = f"{work}/{top}.nextpnr.log"
    with open(log, "w") as f:
        rc = subprocess.run(["nextpnr-ice40", *HX8K["nextpnr"], "--json", net, "--seed", "1",
                             "--freq", "1"], stdout=f, stderr=subprocess.STDOUT).returncode
    with open(log) as f:
        text = f.read()
    fmax = re.findall(r"Max frequency for clock\s+'[^']*':\s+([\d.]+) MHz", text)
    if rc != 0 or not fmax:
        raise CheckFailed(f"{top}: nextpnr-ice40 failed or gave no Fmax (exit {rc}, log {log})")
    else:
        # the last figure is the one after routing
        lc = re.search(r"ICESTORM_LC:\s+(\d+)/", text)
        res.update(fits=True, fmax_mhz=float(fmax[-1]), logic_cells=int(lc.group(1)) if lc else None)
    return res


def text_report(units):
    out = ["APU RTL, open-flow synthesis (tools/synth.sh; method: docs/apu-rtl.md \"Synthesis\")",
           "Yosys 0.23 generic `synth -flatten`, memories kept; depth = gate levels, every gate one level,",
           "an asynchronous memory read its mux tree (log2 words; `ltp -noff` counts it as one level).",
           "Every figure is of a netlist that passed its gate-level check (tools/netlist.py, simulated in",
           "Icarus Verilog 11; docs/apu-rtl.md \"Gate-level checks\"):", ""]
    for name, u in units.items():
        for chk in (u.get("netlist"), (u.get("ice40") or {}).get("netlist")):
            if chk:
                out.append(f"  {chk['netlist']} (sha256 {chk['sha256'][:16]}): {chk['passed']}")
    out.append("")
    out.append(f"{'unit':<10} {'stage':<8} {'cells':>8} {'FFs':>7} {'depth':>6}")
    for name, u in units.items():
        g = u["generic"]
        out.append(f"{name:<10} {'all':<8} {g['cells']:>8} {g['flip_flops']:>7} {g['depth']:>6}"
                   f"   (ltp -noff {g['ltp_noff']}; latches {u['latches']})")
        for s in g["stages"]:
            out.append(f"{'':<10} {'s' + str(s['rank']):<8} {s['cells']:>8} {s['flip_flops']:>7} {s['depth']:>6}")
        if g["loop"]:
            l_ = g["loop"]
            out.append(f"{'':<10} {'loop':<8} {l_['cells']:>8} {l_['flip_flops']:>7} {l_['depth']:>6}"
                       "   (registers that feed themselves)")
        if g["to_outputs"]:
            out.append(f"{'':<10} {'outputs':<8} {'':>8} {'':>7} {g['to_outputs']:>6}")
        if g.get("stages_by_name"):
            out.append(f"{'':<10} by stage: deepest register-to-register path (stage: depth, path)")
            for e in g["stages_by_name"]:
                p = e["path"]
                way = " > ".join([p["from"]] + [f"{n} ({lv})" for n, lv in p["through"]] + [p["to"]])
                out.append(f"{'':<12}{e['stage']:<22} {e['depth']:>3}  {way}")
                if e["stage"] in ("decode", "issue"):
                    for end in e["ends"][1:8]:
                        out.append(f"{'':<12}{'':<22} {end['depth']:>3}  ... > {end['to']} (from {end['from']})")
        for m in g["memories"]:
            out.append(f"{'':<10} memory {m['name']}: {m['words']} x {m['width']} = {m['bits']} bits, "
                       f"{m['read_ports']} read ({'sync' if m['sync_read'] else 'async'}), "
                       f"{m['write_ports']} write")
    out += ["", f"iCE40 ({HX8K['name']}, nextpnr-ice40 --hx8k --package ct256 --seed 1)"]
    for name, u in units.items():
        i = u.get("ice40")
        if i is None:
            continue
        if i.get("fits"):
            out.append(f"{name:<10} {i['luts']:>6} LUTs {i['flip_flops']:>6} FFs {i['bram']:>3} BRAM"
                       f" {i['logic_cells']:>6} LCs   Fmax {i['fmax_mhz']:.1f} MHz")
        else:
            size = f"{i['luts']:>6} LUTs {i['flip_flops']:>6} FFs {i['bram']:>3} BRAM   " if "luts" in i else ""
            out.append(f"{name:<10} {size}does not fit: {i['reason']}")
    return "\n".join(out) + "\n"


def main(argv):
    args = argv[1:]
    quick = "--quick" in args
    do_ice40 = "--no-ice40" not in args
    run_checks = "--require-check" not in args
    units = UNITS
    rest = []
    form = "quick"
    ice40_units = UNITS
    scratch = {}
    i = 0
    while i < len(args):
        a = args[i]
        if a == "--units" and i + 1 < len(args):
            units = args[i + 1].split(",")
            i += 1
        elif a == "--ice40-units" and i + 1 < len(args):
            ice40_units = args[i + 1].split(",")
            i += 1
        elif a == "--check-form" and i + 1 < len(args):
            form = args[i + 1]
            i += 1
        elif a in ("--rtl", "--out") and i + 1 < len(args):
            scratch[a] = args[i + 1]
            i += 1
        elif a not in ("--quick", "--no-ice40", "--require-check"):
            rest.append(a)
        i += 1
    if len(rest) != 1 or any(u not in UNITS for u in units) or form not in netlist.FORMS or len(scratch) == 1:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        print(f"synth.py: units are {','.join(UNITS)}", file=sys.stderr)
        return 2
    build = os.path.abspath(rest[0])
    gen = os.path.join(build, "generated")
    for f in ("apu_pkg.sv", "fp24_rom.svh"):
        if not os.path.exists(os.path.join(gen, f)):
            print(f"synth.py: {gen}/{f} is missing: configure and build {build} first", file=sys.stderr)
            return 2
    tools = ["yosys"] + (["nextpnr-ice40", "iverilog", "vvp"] if not quick else [])
    for t in tools:
        if shutil.which(t) is None:
            print(f"synth.py: {t} not found (tools/setup.sh installs it)", file=sys.stderr)
            return 2
    reports = os.path.join(build, "reports")
    if scratch:
        # a copy of apu_rtl/ (tb/netlist's planted bug): its netlists, records
        # and reports in the --out directory, the build's left alone
        netlist.use_rtl(scratch["--rtl"], scratch["--out"])
        reports = os.path.join(scratch["--out"], "reports")
    work = os.path.join(reports, "synth")
    os.makedirs(work, exist_ok=True)
    result = {}
    try:
        for u in units:
            r = {"latches": check_unit(gen, u, work)}
            print(f"synth: {u}: read, proc, check: ok, 0 latches", flush=True)
            if not quick:
                net, r["netlist"] = checked(build, u, "generic", form, run_checks, netlist.say)
                print(f"synth: {u}: netlist {r['netlist']['netlist']}: {r['netlist']['passed']}", flush=True)
                r["generic"] = generic(gen, u, work, net)
                g = r["generic"]
                print(f"synth: {u}: {g['cells']} cells, {g['flip_flops']} FFs, depth {g['depth']}", flush=True)
                if do_ice40 and u in ice40_units:
                    r["ice40"] = ice40(build, u, work, g, form, run_checks, netlist.say)
                    fm = r["ice40"].get("fmax_mhz")
                    print(f"synth: {u}: iCE40 " + (f"Fmax {fm:.1f} MHz" if fm else "does not fit"), flush=True)
            result[u] = r
    except CheckFailed as e:
        print(f"synth: FAILED: {e}", file=sys.stderr)
        return 1
    if quick:
        return 0
    with open(os.path.join(reports, "synth.json"), "w") as f:
        json.dump({"tool": "yosys 0.23", "units": result}, f, indent=1)
    with open(os.path.join(reports, "synth.txt"), "w") as f:
        f.write(text_report(result))
    print(f"synth: wrote {reports}/synth.txt and synth.json")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
