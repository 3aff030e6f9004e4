#!/usr/bin/env python3
"""Formal proofs of the APU RTL: Yosys 0.23 + yosys-smtbmc + z3 (docs/apu-rtl.md
"Formal proofs").

    tools/formal.py [options] PROOF...
    tools/formal.py --list            the proofs, one a line: name, labels, what it proves
    tools/formal.py --ctest-list      name;labels;timeout lines for tb/formal/CMakeLists.txt

Each proof reads the RTL it needs (apu_rtl/*.sv, the generated package
apu_pkg.sv) and, for the harness proofs, a harness of tb/formal/ with
`read_verilog -formal`, runs `prep -top`, writes an SMT-LIB2 model
(`write_smt2 -wires`) and runs yosys-smtbmc with z3:
  - a bounded model check from the initial state (`-t DEPTH`, `--presat`:
    the assumptions are checked satisfiable first, so a proof cannot pass on
    contradicting assumptions);
  - temporal induction (`-i -t K`) where the proof's table entry says it
    closes; where it does not, the output says to which depth BMC checked it.
A failing check prints the assertion that failed and the counterexample
trace (--dump-vcd) path, and the run exits 1.

Proof kinds:
  - harness proofs (fp24_round, fp24_mul, fp24_add, apu_interlock): the
    harness states the properties against a record of its own; the RTL's
    embedded assertions (apu_assert.svh) are removed there (`chformal
    -remove` on every module but the harness) so that each proof checks
    what it names; they have proofs of their own:
  - asserts_<module>: every apu_rtl/<module>.sv that uses APU_ASSERT*, read
    with -formal (FORMAL defined, apu_assert.svh makes each rule a clocked
    immediate assert), top = the module with its parameters set from the
    package where it has them, rst_n low in the first cycle (an smtc
    constraint), every other input free in every cycle;
  - negative checks (*_mutant): a proof run on a copy of the RTL with a
    planted bug (--mutate); it passes when the proof finds the
    counterexample, so the machinery itself is tested.

Options:
  --generated DIR    the build's generated files (apu_pkg.sv); default build/generated
  --work DIR         where models, logs and traces go; default build/formal
  --mutate FILE:LINE:OLD:NEW   plant a bug: in a scratch copy of FILE, replace
                     OLD by NEW on line LINE (LINE empty: the one line holding
                     OLD); repeatable; implies the proof is expected to hold
                     unless --expect-fail
  --expect-fail      succeed only if some check finds a counterexample
  --depth N / --k K  override the BMC depth / induction k
  --no-induction     BMC only
Python standard library only.
"""
import os
import re
import signal
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RTL = os.path.join(ROOT, "apu_rtl")
HARNESS = os.path.join(ROOT, "tb", "formal")

# ---- the proofs -------------------------------------------------------------
# rtl: apu_rtl modules read (file stems); harness: tb/formal file; top; bmc:
# depth; ind: induction k (None: not expected to close, BMC only); probes:
# (harness wire, flattened design wire) pairs connected after `flatten`;
# cut: cell types whose outputs become free values (an over-approximation:
# a property that holds with them free holds with them); memory_map: the
# design's memories as registers (z3 with SMT arrays got nowhere on the F
# register file); params: the top's parameters (a proof's params replace
# its base's, whole); labels; timeout (s).
# apu_interlock's tag pipes and busy vectors, probed for the induction invariants
INTERLOCK_PROBES = ([(f"p_{u}_{r}", f"dut.u_{u}_tags.{r}") for u in ("mul", "add", "fu") for r in ("v", "d", "kind")]
                    + [(f"p_{u}_ge", f"dut.{u}_ge") for u in ("mul", "add", "fu")])
PROOFS = {
    "fp24_round": dict(
        what="fp24_round against the rounding rule of docs/fp24.md (nearest-even at 17 bits, OF, UF after rounding, NX), "
             "input contract exp != +255",
        rtl=["fp24_round"], harness="fp24_round_formal.sv", top="fp24_round_formal",
        bmc=1, ind=1, labels="formal", timeout=120),
    "fp24_mul": dict(
        what="fp24_mul: out_valid exactly LAT_MUL cycles after in_valid, special values (NaN, 0*inf, inf, signed zero, DAZ) "
             "of the op issued LAT_MUL cycles earlier, out_next_result, fp24_round's input contract",
        rtl=["fp24_classify", "fp24_round", "fp24_result_stage", "fp24_mul"], harness="fp24_mul_formal.sv",
        top="fp24_mul_formal", bmc=5, ind=4, cut=["$mul"],
        probes=[("rnd_exp", "dut.rnd_exp"), ("rnd_en", "dut.u_s2.u_round.en")],
        labels="formal", timeout=300),
    "fp24_add": dict(
        what="fp24_add: out_valid exactly LAT_ADD cycles after in_valid, ADD/SUB special values (NaN, inf-inf, inf, signed "
             "and exact zero sums, x+0, DAZ), NEG/ABS, CMP and FIX on NaN, fp24_round's input contract",
        rtl=["fp24_classify", "fp24_round", "fp24_result_stage", "fp24_add"], harness="fp24_add_formal.sv",
        top="fp24_add_formal", bmc=4, ind=4,
        probes=[("rnd_exp", "dut.rnd_exp"), ("rnd_en", "dut.u_s2.u_round.en")],
        labels="formal", timeout=600),
    "apu_interlock": dict(
        what="apu_interlock + apu_tagpipe at the package's latencies: RAW exactly when a source is written by an op in "
             "flight, WAW by the header's rule, completion and next-cycle tags, cmp_in_flight, pipes_busy",
        rtl=["apu_tagpipe", "apu_interlock"], harness="apu_interlock_formal.sv", top="apu_interlock_formal",
        probes=INTERLOCK_PROBES, params={"ADDR_W": 3}, bmc=3, ind=2, labels="formal,long", timeout=14400),
    "apu_interlock_tags": dict(
        what="apu_interlock + apu_tagpipe at the package's latencies, all 64 registers: completion and next-cycle tags "
             "(the tag issued L cycles earlier), cmp_in_flight, pipes_busy (the hazards: apu_interlock)",
        base="apu_interlock", params={}, defines=["NO_HAZARDS"], bmc=3, ind=2, labels="formal", timeout=600),
    "apu_interlock_one": dict(
        what="apu_interlock's hazards at all 64 registers, one register chosen freely (anyconst): RAW and WAW per "
             "slot and unit for the slots that name it, that register's bit of every busy vector (the induction "
             "invariant), raw_*/waw_* as the ORs of the per-unit signals; the tags and completions as apu_interlock",
        base="apu_interlock", params={}, defines=["ONE_REG"],
        probes=INTERLOCK_PROBES + [(f"p_{s}_{u}", f"dut.{s}_{u}") for s in ("src", "dst") for u in ("mul", "add", "fu")],
        bmc=3, ind=2, labels="formal,long", timeout=14400),
    "apu_interlock_one_small": dict(
        what="apu_interlock_one at 8 registers (ADDR_W 3)",
        base="apu_interlock_one", params={"ADDR_W": 3}, bmc=5, labels="formal", timeout=600),
    "apu_regfile_f": dict(
        what="apu_regfile as the F registers (7 read ports; 6 write ports, all write-first) at 8 registers of 2 bits "
             "(a register's logic is the same for each, and the file only moves words), for every register: a "
             "disabled read port returns 0, a read returns the word the highest write-first port writes to it this "
             "cycle, else the last word written (the highest port of a cycle winning), 0 after a reset",
        rtl=["apu_regfile"], harness="apu_regfile_formal.sv", top="apu_regfile_formal",
        params={"DATA_W": 2, "ADDR_W": 3}, bmc=3, ind=1, memory_map=True, labels="formal", timeout=600),
    "apu_regfile_a": dict(
        what="apu_regfile as the A registers (4 read ports, 2 write ports written at the clock, A0 = 0) at 16 "
             "registers of 2 bits: as apu_regfile_f, and register 0 reads 0 whatever is written to it",
        base="apu_regfile_f", params={"DATA_W": 2, "ADDR_W": 4, "N_RD": 4, "N_WR": 2, "N_WR_FIRST": 0, "ZERO_REG": 1}),
    "apu_regfile_f_full": dict(
        what="apu_regfile_f at the F file's size, 64 x 24",
        base="apu_regfile_f", params={}, bmc=2, labels="formal,long", timeout=14400),
    "apu_regfile_a_full": dict(
        what="apu_regfile_a at the A file's size, 16 x 16",
        base="apu_regfile_a", params={"DATA_W": 16, "ADDR_W": 4, "N_RD": 4, "N_WR": 2, "N_WR_FIRST": 0, "ZERO_REG": 1},
        bmc=2, labels="formal,long", timeout=14400),
    # negative checks: the machinery finds a planted bug
    "fp24_round_mutant": dict(
        what="fp24_round with ties away from zero planted: the proof must fail",
        base="fp24_round", expect_fail=True,
        mutate=[("apu_rtl/fp24_round.sv", None, "round_up = guard & (sticky | frac[0]);", "round_up = guard;")],
        labels="formal", timeout=120),
    "apu_regfile_mutant": dict(
        what="apu_regfile with the last write-first port left out of the bypass: the proof must fail",
        base="apu_regfile_f", expect_fail=True, no_induction=True,
        mutate=[("apu_rtl/apu_regfile.sv", None, "wf < N_WR_FIRST;", "wf + 1 < N_WR_FIRST;")],
        labels="formal", timeout=300),
    "apu_regfile_zero_mutant": dict(
        what="apu_regfile whose register 0 takes writes in a ZERO_REG file (the A file's A0): the proof must fail",
        base="apu_regfile_a", expect_fail=True, no_induction=True,
        mutate=[("apu_rtl/apu_regfile.sv", None, "!(ZERO_REG && wr_addr", "!(1'b0 && wr_addr")],
        labels="formal", timeout=300),
    "apu_interlock_one_mutant": dict(
        what="apu_interlock whose function unit's busy vectors move down an entry one register off (a wrong stride): "
             "apu_interlock_one_small must fail",
        base="apu_interlock_one_small", expect_fail=True, no_induction=True, bmc=5,
        mutate=[("apu_rtl/apu_interlock.sv", None, "fu_ge <= (fu_ge >> N_REG) | fu_new;",
                 "fu_ge <= (fu_ge >> (N_REG - 1)) | fu_new;")],
        labels="formal", timeout=300),
    "apu_interlock_mutant": dict(
        what="apu_interlock with the function unit's tag pipe one stage too long for RECIP/SQRT (a wrong latency): the proof must fail",
        base="apu_interlock_tags", expect_fail=True, no_induction=True, bmc=6,
        mutate=[("apu_rtl/apu_interlock.sv", None, ".LAT0(LAT_FUNC), .LAT1(LAT_TRIG)", ".LAT0(LAT_FUNC + 1), .LAT1(LAT_TRIG)")],
        labels="formal", timeout=300),
}

# Embedded assertions (asserts_<module>): depth and k per module where the
# default does not suit; params from the package (name -> apu_pkg name).
ASSERT_DEFAULT = dict(bmc=4, ind=4, labels="formal", timeout=600)
ASSERT_TABLE = {
    # IlkIssueLandsLast: apu_core's obligation (it issues only with waw clear)
    "apu_interlock": dict(pkg_params={"LAT_MUL": "LAT_MUL", "LAT_ADD": "LAT_ADD", "LAT_FUNC": "LAT_FUNC",
                                      "LAT_TRIG": "LAT_TRIG"}, bmc=12, ind=11, labels="formal,long", timeout=14400,
                          input_rules=["IlkIssueLandsLast"]),
    # rules about a module's inputs (its caller's obligations) are assumed
    # where the module is the top and proved in its parent (apu_core, long)
    "apu_callstack": dict(input_rules=["CallStackPushNotFull", "CallStackPopNotEmpty", "CallStackPushOrPop"]),
    # a module whose inputs come from its parent: its rules proved there
    # (the same models as asserts_fp24_mul / asserts_fp24_add, which read
    # fp24_result_stage and so prove its rules too: this test only under long)
    "fp24_result_stage": dict(context=["fp24_mul", "fp24_add"], labels="formal,long", timeout=14400),
    # a 64 x 24 register file: its memory as registers (memory_map)
    "apu_regfile": dict(bmc=3, ind=None, memory_map=True, labels="formal,long", timeout=14400),
    "apu_tagpipe": dict(context=["apu_interlock"], pkg_params={"LAT_MUL": "LAT_MUL", "LAT_ADD": "LAT_ADD",
                                                                "LAT_FUNC": "LAT_FUNC", "LAT_TRIG": "LAT_TRIG"},
                        bmc=12, ind=11, labels="formal,long", timeout=14400),
    "apu_core": dict(bmc=4, ind=None, labels="formal,long", timeout=14400),
    "fp24_func": dict(bmc=6, ind=None, labels="formal,long", timeout=14400),
    # induction closes at k=6 (2.7 s): in the default suite
    "fp24_func_rsq": dict(bmc=6, ind=6, labels="formal", timeout=600),
    "fp24_func_trig": dict(bmc=12, ind=None, labels="formal,long", timeout=14400),
}
ASSERT_RE = re.compile(r"`APU_ASSERT")


def rtl_modules():
    """apu_rtl/*.sv stems (one module a file, named as the file)."""
    return sorted(f[:-3] for f in os.listdir(RTL) if f.endswith(".sv"))


def assert_modules():
    out = []
    for m in rtl_modules():
        with open(os.path.join(RTL, m + ".sv"), encoding="utf-8") as f:
            if ASSERT_RE.search(f.read()):
                out.append(m)
    return out


def deps(module):
    """The apu_rtl modules `module` instantiates and the packages it names,
    itself last (read order)."""
    known = set(rtl_modules())
    order, seen = [], set()

    def visit(m):
        if m in seen:
            return
        seen.add(m)
        with open(os.path.join(RTL, m + ".sv"), encoding="utf-8") as f:
            text = re.sub(r"//[^\n]*", "", f.read())
        # The packages it names (pkg::X) and the modules it instantiates.
        used = re.findall(r"\b(\w+)::", text) + re.findall(r"^\s*(\w+)\s*(?:#\s*\(|\w+\s*\()", text, re.M)
        for name in used:
            if name in known and name != m:
                visit(name)
        order.append(m)

    visit(module)
    return order


def proof_table():
    table = {}
    def resolve(p):
        q = resolve(PROOFS[p["base"]]) if "base" in p else {}
        q.update(p)
        return q
    for name, p in PROOFS.items():
        table[name] = resolve(p)
    for m in assert_modules():
        q = dict(ASSERT_DEFAULT)
        q.update(ASSERT_TABLE.get(m, {}))
        q.update(what=f"the assertions embedded in apu_rtl/{m}.sv (APU_ASSERT*)", rtl=deps(m), top=m, embedded=True)
        table["asserts_" + m] = q
    return table


# ---- running ----------------------------------------------------------------
def rule_lines(path, rules):
    """Source lines of the APU_ASSERT* invocations of `rules` in `path` (an
    invocation may span lines; Yosys names its assert by one of them)."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    out = []
    for rule in rules:
        hits = [i for i, l in enumerate(lines) if re.search(r"`APU_ASSERT\w*\(\s*" + rule + r"\s*,", l)]
        if len(hits) != 1:
            sys.exit(f"formal: rule {rule} is on {len(hits)} lines of {path}, not 1")
        i, depth = hits[0], 0
        while True:
            out.append(i + 1)
            depth += lines[i].count("(") - lines[i].count(")")
            if depth <= 0 or i + 1 >= len(lines):
                break
            i += 1
    return out


def pkg_params(pkg_path):
    vals = {}
    with open(pkg_path, encoding="utf-8") as f:
        for m in re.finditer(r"localparam\s+int\s+(\w+)\s*=\s*(\d+)\s*;", f.read()):
            vals[m.group(1)] = int(m.group(2))
    return vals


def apply_mutations(mutations, work):
    """Scratch copies of the mutated files: {original path: copy path}."""
    copies = {}
    for path, line, old, new in mutations:
        src = path if os.path.isabs(path) else os.path.join(ROOT, path)
        with open(copies.get(src, src), encoding="utf-8") as f:
            lines = f.read().split("\n")
        if line is None:
            hits = [i for i, l in enumerate(lines) if old in l]
            if len(hits) != 1:
                sys.exit(f"formal: --mutate: '{old}' is on {len(hits)} lines of {path}, not 1")
            idx = hits[0]
        else:
            idx = line - 1
            if not 0 <= idx < len(lines) or old not in lines[idx]:
                sys.exit(f"formal: --mutate: '{old}' is not on line {line} of {path}")
        lines[idx] = lines[idx].replace(old, new, 1)
        mdir = os.path.join(work, "mutant")
        os.makedirs(mdir, exist_ok=True)
        dst = os.path.join(mdir, os.path.basename(src))
        with open(dst, "w", encoding="utf-8") as f:
            f.write("\n".join(lines))
        print(f"formal: planted in {os.path.relpath(src, ROOT)}:{idx + 1}: '{old}' -> '{new}'")
        copies[src] = dst
    return copies


def descendants(root):
    """Ids of every process below `root` (from /proc)."""
    children = {}
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                with open(f"/proc/{d}/stat", encoding="utf-8") as f:
                    ppid = int(f.read().rsplit(")", 1)[1].split()[1])
            except (OSError, ValueError, IndexError):
                continue
            children.setdefault(ppid, []).append(int(d))
    out, todo = [], [root]
    while todo:
        for c in children.get(todo.pop(), []):
            out.append(c)
            todo.append(c)
    return out


def run(cmd, log, timeout):
    t0 = time.monotonic()
    with open(log, "w", encoding="utf-8") as f:
        # its own process group: a timeout ends the solver yosys-smtbmc started too
        proc = subprocess.Popen(cmd, stdout=f, stderr=subprocess.STDOUT, cwd=os.path.dirname(log),
                                start_new_session=True)
        try:
            rc = proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            # yosys-smtbmc runs the solver in a process group of its own: end
            # every descendant by its id, then the group
            for pid in descendants(proc.pid):
                try:
                    os.kill(pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
            rc = None
    return rc, time.monotonic() - t0


def smtbmc_result(log):
    with open(log, encoding="utf-8", errors="replace") as f:
        text = f.read()
    status = re.findall(r"Status: (\w+)", text)
    failed = re.findall(r"(Assert failed in .*|Assumptions are unsatisfiable!.*)", text)
    return (status[-1] if status else None), failed


def prove(name, p, args):
    if p.get("context"):
        ok = True
        for ctx in p["context"]:
            # the parent's own input rules (its caller's obligations) are
            # assumed there too
            q = dict(p, top=ctx, rtl=deps(ctx), context=None,
                     input_rules=ASSERT_TABLE.get(ctx, {}).get("input_rules", []),
                     what=p["what"] + f", in its parent {ctx} (its inputs are the parent's)")
            ok = prove(f"{name}.{ctx}", q, args) and ok
        return ok
    work = os.path.join(args.work, name)
    os.makedirs(work, exist_ok=True)
    pkg = os.path.join(args.generated, "apu_pkg.sv")
    if not os.path.exists(pkg):
        sys.exit(f"formal: {pkg} missing (configure the build: it generates apu_pkg.sv)")
    mutations = list(p.get("mutate", [])) + args.mutate
    copies = apply_mutations(mutations, work) if mutations else {}
    expect_fail = p.get("expect_fail", False) or args.expect_fail

    def src(path):
        return copies.get(path, path)

    files = [pkg] + [src(os.path.join(RTL, m + ".sv")) for m in p["rtl"]]
    if "harness" in p:
        files.append(os.path.join(HARNESS, p["harness"]))
    top = p["top"]
    incdirs = [RTL, args.generated]
    defs = " ".join("-D" + d for d in p.get("defines", []))
    ys = [f"read_verilog -formal -sv {defs} {' '.join('-I' + d for d in incdirs)} {' '.join(files)}"]
    params = pkg_params(pkg)
    for par, pname in p.get("pkg_params", {}).items():
        ys.append(f"chparam -set {par} {params[pname]} {top}")
    for par, val in p.get("params", {}).items():
        ys.append(f"chparam -set {par} {val} {top}")
    ys.append(f"prep -top {top}")
    if p.get("memory_map"):
        # memories as registers: z3 did not get past BMC step 2 of a 64 x 24
        # register file in 10 minutes with its SMT arrays
        ys.append("memory_map")
        ys.append("opt_clean")
    if p.get("input_rules"):
        path = src(os.path.join(RTL, top + ".sv"))
        sel = " ".join(f"a:src={path}:{n}.*" for n in rule_lines(path, p["input_rules"]))
        ys.append(f"chformal -assert2assume {sel}")
        print(f"formal {name}: assumed (input rules): {', '.join(p['input_rules'])}")
    if not p.get("embedded"):
        # the RTL's own assertions have their own proofs (asserts_*)
        ys.append(f"chformal -remove * {top} %d")
        ys.append("opt_clean")
    if p.get("probes") or p.get("cut"):
        ys.append("flatten")
        for wire, target in p.get("probes", []):
            ys.append(f"connect -set {wire} {target}")
        for cell in p.get("cut", []):
            ys.append(f"delete t:{cell}")
        ys.append("setundef -undriven -anyseq")
        ys.append("opt_clean")
    ys.append("async2sync")
    ys.append("write_smt2 -wires model.smt2")
    with open(os.path.join(work, "model.ys"), "w", encoding="utf-8") as f:
        f.write("\n".join(ys) + "\n")
    rc, t_ys = run(["yosys", "-q", "-l", "yosys.log", "-s", "model.ys"], os.path.join(work, "yosys.out"), 600)
    if rc != 0:
        print(f"formal {name}: yosys failed (rc {rc}); log {os.path.join(work, 'yosys.log')}")
        with open(os.path.join(work, "yosys.out"), encoding="utf-8", errors="replace") as f:
            print(f.read()[-3000:])
        return False
    smtc = []
    if p.get("embedded"):
        with open(os.path.join(work, "yosys.log"), encoding="utf-8", errors="replace") as f:
            pass
        smtc = ["--smtc", "reset.smtc"]
        with open(os.path.join(work, "reset.smtc"), "w", encoding="utf-8") as f:
            f.write("# rst_n low in the first cycle (the valid bits have no initial value)\ninitial\nassume (not [rst_n])\n")
    depth = args.depth or p["bmc"]
    k = args.k or p.get("ind")
    print(f"formal {name}: {p['what']}")
    print(f"formal {name}: model built in {t_ys:.1f} s ({work}/model.smt2)")
    found_cex = False
    ok = True
    # BMC
    vcd = os.path.join(work, "bmc.vcd")
    cmd = ["yosys-smtbmc", "-s", "z3", "--unroll", "--noprogress", "--presat", "-t", str(depth), "--dump-vcd", vcd] + smtc + ["model.smt2"]
    rc, t = run(cmd, os.path.join(work, "bmc.log"), args.timeout)
    status, failed = smtbmc_result(os.path.join(work, "bmc.log"))
    if rc is None:
        print(f"formal {name}: BMC depth {depth}: TIMEOUT after {t:.1f} s (log {work}/bmc.log)")
        ok = False
    elif status == "PASSED":
        print(f"formal {name}: BMC depth {depth}: passed ({t:.1f} s)")
    else:
        found_cex = status == "FAILED" and any(x.startswith("Assert failed") for x in failed)
        for x in failed:
            print(f"formal {name}: BMC: {x}")
        what = f"counterexample {vcd}" if found_cex else f"log {work}/bmc.log"
        print(f"formal {name}: BMC depth {depth}: FAILED ({t:.1f} s); {what}")
        ok = False
    # induction
    if ok and k and not (args.no_induction or p.get("no_induction")):
        vcd = os.path.join(work, "induction.vcd")
        cmd = ["yosys-smtbmc", "-s", "z3", "--unroll", "--noprogress", "-i", "-t", str(k), "--dump-vcd", vcd] + smtc + ["model.smt2"]
        rc, t = run(cmd, os.path.join(work, "induction.log"), args.timeout)
        status, failed = smtbmc_result(os.path.join(work, "induction.log"))
        if rc is not None and status == "PASSED":
            print(f"formal {name}: induction k={k}: closed ({t:.1f} s): PROVED for every depth")
        else:
            why = "timeout" if rc is None else "did not close"
            print(f"formal {name}: induction k={k}: {why} ({t:.1f} s; induction trace {vcd}, log {work}/induction.log)")
            ok = False
    elif ok:
        print(f"formal {name}: no induction (does not close): checked by BMC to depth {depth} only")
    if expect_fail:
        if found_cex:
            print(f"formal {name}: the planted bug was found, as expected")
            return True
        print(f"formal {name}: the planted bug was NOT found")
        return False
    return ok


def main(argv):
    sys.stdout.reconfigure(line_buffering=True)
    import argparse
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("proofs", nargs="*")
    ap.add_argument("--generated", default=os.path.join(ROOT, "build", "generated"))
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "formal"))
    ap.add_argument("--mutate", action="append", default=[])
    ap.add_argument("--expect-fail", action="store_true")
    ap.add_argument("--depth", type=int)
    ap.add_argument("--k", type=int)
    ap.add_argument("--no-induction", action="store_true")
    ap.add_argument("--timeout", type=float, default=3600, help="per solver run, seconds")
    ap.add_argument("--list", action="store_true")
    ap.add_argument("--ctest-list", action="store_true")
    args = ap.parse_args(argv)
    muts = []
    for m in args.mutate:
        parts = m.split(":", 3)
        if len(parts) != 4:
            ap.error(f"--mutate {m}: want FILE:LINE:OLD:NEW")
        muts.append((parts[0], int(parts[1]) if parts[1] else None, parts[2], parts[3]))
    args.mutate = muts
    args.generated = os.path.abspath(args.generated)
    args.work = os.path.abspath(args.work)
    table = proof_table()
    if args.list or args.ctest_list:
        for name, p in table.items():
            if args.ctest_list:
                print(f"{name}|{p['labels']}|{p['timeout']}")
            else:
                print(f"{name:24} {p['labels']:12} {p['what']}")
        return 0
    if not args.proofs:
        ap.error("name a proof (--list)")
    ok = True
    for name in args.proofs:
        if name not in table:
            ap.error(f"no proof {name} (--list)")
        t0 = time.monotonic()
        r = prove(name, table[name], args)
        print(f"formal {name}: {'PASS' if r else 'FAIL'} in {time.monotonic() - t0:.1f} s")
        ok = ok and r
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
