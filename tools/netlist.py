#!/usr/bin/env python3
"""Gate-level netlists of the APU RTL and their checks (docs/apu-rtl.md
"Gate-level checks").

    netlist.py write [--units U,...] BUILD_DIR
    netlist.py check [--units U,...] [--form quick|full] [--jobs N] BUILD_DIR
    netlist.py status [--units U,...] BUILD_DIR
    --flow ice40 (write, check, status): the FP24 units' synth_ice40
    netlists instead (BUILD_DIR/netlist/U.ice40.v, Yosys's iCE40 cell
    models; the quick sets thinned, the iCE40 cells simulating slowly)
    further options: --rtl DIR --out DIR (a copy of apu_rtl/, its netlists
    and records in DIR instead of BUILD_DIR/netlist: tb/netlist's test that
    the check catches a planted bug)

write: the one netlist writer of the project. Yosys 0.23 reads the sources
Verilator reads (sources() below: BUILD_DIR/generated/apu_pkg.sv, then
apu_rtl/*.sv, with apu_rtl/ and BUILD_DIR/generated/ on the include path),
runs generic `synth -flatten -top U` (its own script up to `fine`, then
techmap and `abc -fast`: AND, NAND, OR, NOR, XOR, XNOR, ANDNOT, ORNOT, MUX,
NOT gates and flip-flops; inferred memories stay memories) and writes
  BUILD_DIR/netlist/U.v     `write_verilog -noattr`: plain gates as `assign`s,
                            flip-flops as `always` blocks, memories as arrays
  BUILD_DIR/netlist/U.json  `write_json` of the same netlist (tools/synth.py
                            takes its figures from it)
  BUILD_DIR/netlist/U.log   Yosys's log (`ltp -noff` included)
  BUILD_DIR/netlist/U.stamp.json  what the netlist was made from (a hash of
                            every source, the script and Yosys's version)
A netlist whose stamp matches its sources is reused, not synthesized again.
Units: fp24_mul, fp24_add, fp24_func, fp24_units (the three side by side)
and apu_core.

check: each unit's netlist simulated in Icarus Verilog 11 against the C++
model (`fp24-run --engine model`) or, for apu_core, the ISS (`apu-run
--engine iss`); tb/netlist/ has the benches. The FP24 units run
tb/fp24_icarus_tb.sv with the netlist in place of the RTL (the other units
of fp24_units idle stubs) on the vector sets of netlist_vectors.py: known
(tb/vectors/fp24_known.vec), structured, boundary and random. apu_core's
netlist runs under the icarus engine (tb/apu/apu_icarus_lockstep_tb.sv
compiled with it) in lockstep with the ISS, `apu-cosim --engines
iss,icarus`, every cycle compared: the hand-timed kernels of
tb/apu_icarus.cmake and random programs (quick 6, full 400, seed 38). A
mismatch is listed with its op, operands, both results and flags, and
counted; a divergence as apu-cosim reports it. Each
check leaves BUILD_DIR/netlist/U.FORM.check.json (passed or not, the
netlist's sha256, the sets, their vectors or programs, the time);
tools/synth.py reports figures only for a netlist with a passing record.

status: prints each unit's latest check records.

Exit 0; 1 when a check fails (or Yosys or a simulation fails); 2 on a
usage error or a missing tool or build.
"""
import contextlib
import datetime
import fcntl
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RTL = os.path.join(ROOT, "apu_rtl")
TB = os.path.join(ROOT, "tb")
NETLIST_TB = os.path.join(TB, "netlist")
sys.path.insert(0, NETLIST_TB)

FP_UNITS = ["fp24_mul", "fp24_add", "fp24_func"]
UNITS = FP_UNITS + ["fp24_units", "apu_core"]
FORMS = ("quick", "full")
OUT_DIR = None  # BUILD_DIR/netlist unless use_rtl() says otherwise


def say(msg):
    print(msg, flush=True)


class Failed(Exception):
    """A failed synthesis, simulation or check: exit 1."""


class Usage(Exception):
    """A missing tool, build or option: exit 2."""


def sources(gen, rtl=None):
    """Packages first (Yosys resolves pkg::name at read time), then the rest:
    the generated apu_pkg.sv and the .sv files of `rtl` (apu_rtl/)."""
    rtl = rtl or RTL
    pkgs = [os.path.join(gen, "apu_pkg.sv")]
    rest = []
    for f in sorted(os.listdir(rtl)):
        if f.endswith(".sv"):
            (pkgs if f.endswith("_pkg.sv") else rest).append(os.path.join(rtl, f))
    return pkgs + rest


def read_cmd(gen, top):
    """Yosys's read of the sources Verilator reads, `top` elaborated."""
    return f"read_verilog -sv -I{gen} -I{RTL} {' '.join(sources(gen))}; hierarchy -check -top {top}"


def generic_script(gen, top, out):
    """The generic flow (docs/apu-rtl.md "Synthesis" step 2): synth's own
    script up to `fine` without memory_map, gates by `abc -fast`; the
    netlist written as Verilog and JSON from the one run."""
    return (f"{read_cmd(gen, top)}; synth -flatten -top {top} -run coarse:fine;"
            f" opt -fast -full; opt -full; techmap; opt -fast; abc -fast; opt -fast;"
            f" hierarchy -check; check -assert; write_json {out}.json;"
            f" write_verilog -noattr {out}.v; ltp -noff")


def ice40_script(gen, top, out):
    """synth_ice40 (tools/synth.py's iCE40 figures and nextpnr's input):
    SB_LUT4, SB_CARRY, SB_DFF*, SB_RAM40_4K cells, simulated with Yosys's
    ice40/cells_sim.v."""
    return (f"{read_cmd(gen, top)}; synth_ice40 -top {top} -json {out}.json;"
            f" write_verilog -noattr {out}.v")


FLOWS = {"generic": generic_script, "ice40": ice40_script}
ICE40_CELLS = "/usr/share/yosys/ice40/cells_sim.v"


def flow_name(top, flow):
    """The file name of a netlist: U (generic) or U.ice40."""
    return top if flow == "generic" else f"{top}.{flow}"


def yosys_version():
    r = subprocess.run(["yosys", "-V"], capture_output=True, text=True)
    return r.stdout.strip()


def sha256_file(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def input_files(gen):
    """Every file the read may touch: the sources, the include files of
    apu_rtl/ and the generated directory."""
    files = list(sources(gen))
    for d in (RTL, gen):
        for f in sorted(os.listdir(d)):
            if f.endswith((".svh", ".vh")):
                files.append(os.path.join(d, f))
    return files


def stamp_of(gen, top, flow="generic"):
    h = hashlib.sha256()
    h.update(yosys_version().encode())
    h.update(FLOWS[flow]("GEN", top, "OUT").encode())
    for f in input_files(gen):
        h.update(os.path.basename(f).encode())
        with open(f, "rb") as fh:
            h.update(hashlib.sha256(fh.read()).digest())
    return h.hexdigest()


_HELD = set()


@contextlib.contextmanager
def locked(path):
    """An exclusive lock on `path` (a netlist and its records, while one
    process writes or checks them); taken again by its holder, a no-op."""
    if path in _HELD:
        yield
        return
    with open(path, "a") as f:
        fcntl.flock(f, fcntl.LOCK_EX)
        _HELD.add(path)
        try:
            yield
        finally:
            _HELD.discard(path)
            fcntl.flock(f, fcntl.LOCK_UN)


def holding(build, top, flow="generic"):
    """The lock of a netlist: held, no other process replaces it (a writer
    whose sources changed) while it is checked or measured."""
    return locked(os.path.join(build_paths(build)[2], flow_name(top, flow) + ".lock"))


def build_paths(build):
    build = os.path.abspath(build)
    gen = os.path.join(build, "generated")
    for f in ("apu_pkg.sv", "fp24_rom.svh"):
        if not os.path.exists(os.path.join(gen, f)):
            raise Usage(f"{gen}/{f} is missing: configure and build {build} first")
    out = netlist_dir(build)
    os.makedirs(out, exist_ok=True)
    return build, gen, out


def netlist_dir(build):
    return OUT_DIR or os.path.join(os.path.abspath(build), "netlist")


def use_rtl(rtl, out):
    """Netlists of another copy of apu_rtl/ (`rtl`), written into `out`
    (a scratch copy with a planted bug: the check must fail)."""
    global RTL, OUT_DIR
    RTL, OUT_DIR = os.path.abspath(rtl), os.path.abspath(out)


def write(build, top, log=say, flow="generic"):
    """The netlist of `top` (see the module doc): returns {"v", "json",
    "log", "sha256", "stamp", "reused", "seconds"}; raises Failed when Yosys
    fails."""
    if top not in UNITS:
        raise Usage(f"unknown unit {top} (units: {','.join(UNITS)})")
    if shutil.which("yosys") is None:
        raise Usage("yosys not found (tools/setup.sh installs it)")
    build, gen, outdir = build_paths(build)
    name = flow_name(top, flow)
    base = os.path.join(outdir, name)
    stamp = stamp_of(gen, top, flow)
    with locked(base + ".lock"):
        try:
            with open(base + ".stamp.json") as f:
                old = json.load(f)
        except (OSError, ValueError):
            old = {}
        if (old.get("stamp") == stamp and all(os.path.exists(base + e) for e in (".v", ".json", ".log"))
                and old.get("sha256") == sha256_file(base + ".v")):
            return {"v": base + ".v", "json": base + ".json", "log": base + ".log", "sha256": old["sha256"],
                    "stamp": stamp, "reused": True, "seconds": old.get("seconds")}
        for e in (".v", ".json", ".log", ".stamp.json"):
            with contextlib.suppress(FileNotFoundError):
                os.remove(base + e)
        tmp = base + ".tmp"
        t0 = time.monotonic()
        log(f"netlist: {name}: synthesizing (" + ("yosys synth -flatten, abc -fast)" if flow == "generic"
                                                  else "yosys synth_ice40)"))
        with open(base + ".yosys.out", "w") as f:
            rc = subprocess.run(["yosys", "-q", "-l", tmp + ".log", "-p", FLOWS[flow](gen, top, tmp)],
                                stdout=f, stderr=subprocess.STDOUT).returncode
        seconds = round(time.monotonic() - t0, 1)
        if rc != 0 or not all(os.path.exists(tmp + e) for e in (".v", ".json")):
            with open(base + ".yosys.out") as f:
                tail = f.read().strip().splitlines()[-5:]
            raise Failed(f"{name}: yosys failed (exit {rc}, log {tmp}.log):\n  " + "\n  ".join(tail))
        for e in (".json", ".log", ".v"):
            os.replace(tmp + e, base + e)
        sha = sha256_file(base + ".v")
        with open(base + ".stamp.json", "w") as f:
            json.dump({"unit": top, "flow": flow, "stamp": stamp, "sha256": sha, "yosys": yosys_version(),
                       "script": FLOWS[flow]("BUILD/generated", top, "BUILD/netlist/" + name),
                       "seconds": seconds}, f, indent=1)
        log(f"netlist: {name}: {base}.v written in {seconds} s")
        return {"v": base + ".v", "json": base + ".json", "log": base + ".log", "sha256": sha,
                "stamp": stamp, "reused": False, "seconds": seconds}


# ---- check records ----

def record_path(build, top, form, flow="generic"):
    return os.path.join(netlist_dir(build), f"{flow_name(top, flow)}.{form}.check.json")


def save_record(build, top, form, rec, flow="generic"):
    path = record_path(build, top, form, flow)
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(rec, f, indent=1)
    os.replace(tmp, path)


def passing_record(build, top, sha, flow="generic"):
    """The passing check record of the netlist with this sha256, the full
    form preferred; None when there is none."""
    for form in FORMS[::-1]:
        try:
            with open(record_path(build, top, form, flow)) as f:
                rec = json.load(f)
        except (OSError, ValueError):
            continue
        if rec.get("passed") and rec.get("netlist_sha256") == sha:
            return rec
    return None


def describe(rec):
    """One line: which check a netlist passed."""
    if rec.get("programs") is not None:
        progs = ", ".join(f"{p['name']} ({p['cycles']} cycles)" for p in rec["programs"])
        what = f"in lockstep with the ISS, every cycle: {progs}"
    else:
        sets = ", ".join(f"{s['name']} {s['vectors']}" for s in rec["sets"])
        what = f"{rec['vectors']} vectors against the model ({sets})"
    return (f"{rec['form']} check {'passed' if rec['passed'] else 'FAILED'} on {rec['date']}: "
            f"{what}; {rec['seconds']} s")


# ---- tools ----

def tool(name, path=None):
    p = path or shutil.which(name)
    if p is None or not os.path.exists(p):
        raise Usage(f"{name} not found" + ("" if path else " (tools/setup.sh installs it)"))
    return p


def run(cmd, what, **kw):
    r = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if r.returncode != 0:
        raise Failed(f"{what}: exit {r.returncode}\n{r.stdout[-2000:]}{r.stderr[-2000:]}")
    return r


def iverilog(out, top, files, gen, what):
    run([tool("iverilog"), "-g2012", f"-I{gen}", "-s", top, "-o", out] + files, f"iverilog ({what})")


# ---- the FP24 units ----

def stub(build, gen, unit, outdir):
    """An idle `unit` with the RTL's ports, every output 0: fp24_units'
    other units while one unit's netlist is checked."""
    path = os.path.join(outdir, f"stub_{unit}.v")
    stamp = stamp_of(gen, unit)
    with locked(path + ".lock"):
        try:
            with open(path + ".stamp") as f:
                if f.read() == stamp and os.path.exists(path):
                    return path
        except OSError:
            pass
        r = subprocess.run(["yosys", "-q", "-p", f"{read_cmd(gen, unit)}; proc; flatten; delete c:*;"
                            f" setundef -undriven -zero; opt_clean -purge; write_verilog -noattr {path}.tmp"],
                           capture_output=True, text=True)
        if r.returncode != 0:
            raise Failed(f"stub of {unit}: yosys failed\n{r.stdout[-1500:]}{r.stderr[-1500:]}")
        os.replace(path + ".tmp", path)
        with open(path + ".stamp", "w") as f:
            f.write(stamp)
    return path


def fp_vvp(build, gen, unit, net, work, flow="generic"):
    """tb/fp24_icarus_tb.sv on fp24_units with `unit`'s netlist (net: its
    .v), the other units idle stubs; fp24_units' own netlist alone. An
    iCE40 netlist with Yosys's models of its cells."""
    vvp = os.path.join(work, f"{unit}.check.vvp")
    files = [os.path.join(gen, "apu_pkg.sv"), os.path.join(TB, "fp24_icarus_tb.sv")]
    if unit == "fp24_units":
        files.append(net)
    else:
        files += [os.path.join(RTL, "fp24_units.sv"), net]
        files += [stub(build, gen, u, netlist_dir(build)) for u in FP_UNITS if u != unit]
    defs = []
    if flow == "ice40":
        if not os.path.exists(ICE40_CELLS):
            raise Usage(f"{ICE40_CELLS} not found (Debian's yosys installs it)")
        # cells_sim.v's port defaults (`input X = 1'b1`) are beyond Icarus 11
        files.append(ICE40_CELLS)
        defs = ["-DNO_ICE40_DEFAULT_ASSIGNMENTS"]
    run([tool("iverilog"), "-g2012", *defs, f"-I{gen}", "-s", "fp24_icarus_tb", "-o", vvp] + files,
        f"iverilog ({flow_name(unit, flow)} netlist)")
    return vvp


def run_vectors(vvp, vec_lines, work, jobs):
    """The bench on the vectors, split into `jobs` parallel runs: the
    `result flags` lines in order."""
    n = len(vec_lines)
    jobs = max(1, min(jobs, n // 200 + 1))
    chunks = [vec_lines[i * n // jobs:(i + 1) * n // jobs] for i in range(jobs)]
    procs = []
    for i, c in enumerate(chunks):
        vin, vout = os.path.join(work, f"chunk{i}.vec"), os.path.join(work, f"chunk{i}.out")
        with open(vin, "w") as f:
            f.write("\n".join(c) + "\n")
        procs.append((subprocess.Popen([tool("vvp"), "-n", vvp, f"+vectors={vin}", f"+results={vout}"],
                                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True), vout, len(c)))
    out = []
    for p, vout, count in procs:
        text, _ = p.communicate()
        if p.returncode != 0 or re.search(r"FATAL|ERROR", text) or not os.path.exists(vout):
            raise Failed(f"vvp {os.path.basename(vvp)} failed (exit {p.returncode}):\n{text[-2000:]}")
        with open(vout) as f:
            lines = f.read().split()
        got = [f"{lines[i]} {lines[i + 1]}" for i in range(0, len(lines), 2)]
        if len(got) != count:
            raise Failed(f"vvp {os.path.basename(vvp)}: {len(got)} results for {count} vectors")
        out += got
    return out


def model_results(fp24_run, vec_lines):
    r = subprocess.run([fp24_run, "--engine", "model"], input="\n".join(vec_lines) + "\n",
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise Failed(f"fp24-run --engine model: exit {r.returncode}\n{r.stderr[-2000:]}")
    return [" ".join(l.split()) for l in r.stdout.splitlines() if l.strip()]


# The iCE40 netlists simulate some 15 times slower (cells_sim.v's models):
# their check runs the quick sets thinned to this many vectors (the known
# ones whole).
ICE40_VECTORS = {"fp24_mul": 3000, "fp24_add": 3000, "fp24_func": 150}


def thin(sets, limit):
    total = sum(len(v) for n, v in sets if n != "known")
    if total <= limit:
        return sets
    step = total / limit
    return [(n, v if n == "known" else [v[int(i * step)] for i in range(int(len(v) / step))]) for n, v in sets]


def check_fp(build, unit, form, jobs, log, flow="generic"):
    import netlist_vectors  # tb/netlist/netlist_vectors.py
    build, gen, outdir = build_paths(build)
    fp24_run = tool("fp24-run", os.path.join(build, "bin", "fp24-run"))
    t0 = time.monotonic()
    net = write(build, unit, log, flow)
    ops = None if unit == "fp24_units" else netlist_vectors.UNIT_OPS[unit]
    sets = netlist_vectors.sets(form, ops, os.path.join(TB, "vectors", "fp24_known.vec"))
    if flow == "ice40":
        sets = thin(sets, ICE40_VECTORS[unit])
    vectors = [v for _, vs in sets for v in vs]
    with tempfile.TemporaryDirectory(dir=outdir) as work:
        vvp = fp_vvp(build, gen, unit, net["v"], work, flow)
        t1 = time.monotonic()
        got = run_vectors(vvp, vectors, work, jobs)
        sim_s = time.monotonic() - t1
    want = model_results(fp24_run, vectors)
    if len(want) != len(vectors):
        raise Failed(f"fp24-run --engine model: {len(want)} results for {len(vectors)} vectors")
    wrong, by_set, i = [], [], 0
    for name, vs in sets:
        bad = 0
        for v in vs:
            if got[i] != want[i]:
                bad += 1
                wrong.append((name, v, got[i], want[i]))
            i += 1
        by_set.append({"name": name, "vectors": len(vs), "mismatches": bad})
    by_op = {}
    for _, v, _, _ in wrong:
        by_op[v.split()[0]] = by_op.get(v.split()[0], 0) + 1
    rec = {"unit": unit, "flow": flow, "form": form, "netlist": net["v"], "netlist_sha256": net["sha256"],
           "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
           "against": "fp24-run --engine model", "sets": by_set, "vectors": len(vectors),
           "mismatches": len(wrong), "mismatches_by_op": by_op,
           "first_mismatches": [{"set": s, "vector": v, "netlist": g, "model": w} for s, v, g, w in wrong[:20]],
           "passed": not wrong, "sim_seconds": round(sim_s, 1), "seconds": round(time.monotonic() - t0, 1)}
    save_record(build, unit, form, rec, flow)
    name = flow_name(unit, flow)
    sets_txt = ", ".join(f"{s['name']} {s['vectors']}" for s in by_set)
    if wrong:
        lines = [f"{name} netlist: {len(wrong)} of {len(vectors)} vectors differ from the model "
                 f"(by op: {', '.join(f'{k} {n}' for k, n in sorted(by_op.items()))}; sets: "
                 + ", ".join(f"{s['name']} {s['mismatches']}/{s['vectors']}" for s in by_set) + ")",
                 "  first ones (vector: netlist result flags / model result flags):"]
        lines += [f"  [{s}] {v}: netlist {g} / model {w}" for s, v, g, w in wrong[:20]]
        raise Failed("\n".join(lines))
    log(f"netlist: {name}: {form} check passed: {len(vectors)} vectors ({sets_txt}) agree with the model, "
        f"{rec['seconds']} s ({round(sim_s, 1)} s in Icarus)")
    return rec


# ---- apu_core ----

# tb/apu_icarus.cmake's kernels: r_xform's camera batch and xform4 on one
# block of two vertices, each with the end of the stream after it.
KERNEL_DATA = {
    "camera.hex": "@0 000001 000000\n@b 414000 000000 000000\n"
                  "@10 000000 000000 000000 000000 3f0000 000000 44e000 000060 000040 381df4\n",
    "end.hex": "@0 000000\n",
    "xform4.hex": "@0 000002\n@10 400000 000000 000000 3f0000\n000000 400000 000000 400000\n"
                  "000000 000000 400000 000000\n000000 000000 000000 3f0000\n"
                  "@20 3f0000 400000 408000 3f0000\nbf0000 000000 3f0000 3f0000\n",
}
KERNELS = [("r_xform.apu", ["camera.hex", "end.hex"]), ("xform4.apu", ["xform4.hex", "end.hex"])]
# Random programs of apu-cosim (apu_random.hpp) in lockstep: (seed, count).
RANDOM_PROGRAMS = {"quick": (38, 6), "full": (38, 400)}
LOCKSTEP_TB = os.path.join(TB, "apu", "apu_icarus_lockstep_tb.sv")


def core_vvp(build, gen, net, outdir):
    """tb/apu/apu_icarus_lockstep_tb.sv (the icarus engine's bench) compiled
    with the netlist (tb/apu_icarus.cmake, APU_NETLIST); kept beside the
    netlist while neither changes."""
    vvp = os.path.join(outdir, "apu_core.lockstep.vvp")
    h = hashlib.sha256()
    for f in (net["v"], LOCKSTEP_TB, os.path.join(TB, "apu_icarus.cmake"), os.path.join(gen, "apu_pkg.sv")):
        h.update(hashlib.sha256(open(f, "rb").read()).digest())
    stamp = h.hexdigest()
    with locked(vvp + ".lock"):
        try:
            with open(vvp + ".stamp") as f:
                if f.read() == stamp and os.path.exists(vvp):
                    return vvp
        except OSError:
            pass
        run([tool("cmake"), f"-DIVERILOG={tool('iverilog')}", f"-DSOURCE_DIR={ROOT}", f"-DGENERATED={gen}",
             f"-DOUTPUT={vvp}", f"-DCORE={net['v']}", "-DDEFINES=APU_NETLIST", "-P",
             os.path.join(TB, "apu_icarus.cmake")], "iverilog of the lockstep bench with the apu_core netlist")
        with open(vvp + ".stamp", "w") as f:
            f.write(stamp)
    return vvp


def cosim(apu_cosim, vvp, args, what):
    """apu-cosim ARGS --engines iss,icarus on the netlist's bench: the cycles
    both agree on; a divergence raises Failed with apu-cosim's report."""
    r = subprocess.run([apu_cosim, *args, "--engines", "iss,icarus", "--icarus-vvp", vvp],
                       capture_output=True, text=True)
    m = re.search(r"iss and icarus agree on (\d+) cycles", r.stdout)
    if r.returncode != 0 or not m:
        raise Failed(f"apu_core netlist, {what}: apu-cosim --engines iss,icarus (exit {r.returncode}):\n"
                     f"{r.stdout[-3000:]}{r.stderr[-1500:]}")
    return int(m.group(1)), r.stdout


def check_core(build, form, jobs, log):
    build, gen, outdir = build_paths(build)
    apu_cosim = tool("apu-cosim", os.path.join(build, "bin", "apu-cosim"))
    if "icarus" not in subprocess.run([apu_cosim, "--help"], capture_output=True, text=True).stdout:
        raise Usage(f"{apu_cosim} has no icarus engine: build it (target apu-cosim)")
    t0 = time.monotonic()
    net = write(build, "apu_core", log)
    vvp = core_vvp(build, gen, net, outdir)
    progs = []
    with tempfile.TemporaryDirectory(dir=outdir) as work:
        for name, text in KERNEL_DATA.items():
            with open(os.path.join(work, name), "w") as f:
                f.write(text)
        for kernel, data in KERNELS:
            t1 = time.monotonic()
            args = [os.path.join(ROOT, "firmware", "kernels", kernel)]
            for d in data:
                args += ["--data", os.path.join(work, d)]
            cycles, out = cosim(apu_cosim, vvp, args, kernel)
            if "; halted" not in out:
                raise Failed(f"apu_core netlist, {kernel}: did not halt:\n{out[-2000:]}")
            progs.append({"name": kernel, "kind": "hand-timed kernel (tb/apu_icarus.cmake)", "cycles": cycles,
                          "seconds": round(time.monotonic() - t1, 1)})
            log(f"netlist: apu_core: {kernel}: the netlist and the ISS agree on every one of {cycles} cycles")
    seed, count = RANDOM_PROGRAMS[form]
    t1 = time.monotonic()
    shards = max(1, min(jobs, count))
    procs = []
    for k in range(shards):
        first, n = k * count // shards, (k + 1) * count // shards - k * count // shards
        args = [apu_cosim, "--random", str(n), "--seed", str(seed), "--first", str(first),
                "--engines", "iss,icarus", "--icarus-vvp", vvp]
        procs.append((subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True),
                      first, n))
    total, failures = 0, []
    for p, first, n in procs:
        out, err = p.communicate()
        m = re.search(r"iss and icarus agree on (\d+) cycles", out)
        if p.returncode != 0 or not m:
            failures.append(f"cases {first}..{first + n - 1} (exit {p.returncode}):\n{out[-3000:]}{err[-1000:]}")
        else:
            total += int(m.group(1))
    if failures:
        raise Failed(f"apu_core netlist: random programs of seed {seed} in lockstep with the ISS: "
                     + "\n".join(failures))
    progs.append({"name": f"apu-cosim --random {count} --seed {seed}", "kind": "random programs",
                  "programs": count, "cycles": total, "seconds": round(time.monotonic() - t1, 1)})
    log(f"netlist: apu_core: {count} random programs (seed {seed}): the netlist and the ISS agree on every one "
        f"of {total} cycles ({time.monotonic() - t1:.1f} s)")
    rec = {"unit": "apu_core", "form": form, "netlist": net["v"], "netlist_sha256": net["sha256"],
           "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
           "against": "the ISS, every cycle (apu-cosim --engines iss,icarus, the icarus engine on the netlist)",
           "programs": progs, "passed": True, "seconds": round(time.monotonic() - t0, 1)}
    save_record(build, "apu_core", form, rec)
    return rec


def check(build, unit, form="quick", jobs=1, log=say, flow="generic"):
    """Runs the check of `unit`'s netlist (flow generic, or ice40 for the
    FP24 units); returns its record (passed), or raises Failed after saving
    a failing record."""
    if unit not in UNITS:
        raise Usage(f"unknown unit {unit} (units: {','.join(UNITS)})")
    if form not in FORMS:
        raise Usage(f"unknown form {form} (quick, full)")
    if flow not in FLOWS or (flow == "ice40" and unit not in FP_UNITS):
        raise Usage(f"no {flow} check of {unit} (ice40: the FP24 units)")
    started = time.time()
    try:
        with holding(build, unit, flow):
            if unit == "apu_core":
                return check_core(build, form, jobs, log)
            return check_fp(build, unit, form, jobs, log, flow)
    except Failed as e:
        path = record_path(build, unit, form, flow)
        if not os.path.exists(path) or os.path.getmtime(path) < started:
            # a failure before the comparison: the record says so
            save_record(build, unit, form, {"unit": unit, "flow": flow, "form": form, "passed": False,
                                            "netlist_sha256": None, "error": str(e)[:4000],
                                            "date": datetime.datetime.now(datetime.timezone.utc).strftime(
                                                "%Y-%m-%d %H:%M UTC")}, flow)
        raise


def main(argv):
    args = argv[1:]
    if not args or args[0] not in ("write", "check", "status"):
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    cmd, args = args[0], args[1:]
    units, form, jobs, rest, rtl, out, flow = None, "quick", 1, [], None, None, "generic"
    i = 0
    while i < len(args):
        a = args[i]
        if a in ("--units", "--form", "--jobs", "--rtl", "--out", "--flow") and i + 1 < len(args):
            v = args[i + 1]
            if a == "--flow":
                flow = v
            elif a == "--rtl":
                rtl = v
            elif a == "--out":
                out = v
            elif a == "--units":
                units = v.split(",")
            elif a == "--form":
                form = v
            else:
                if not v.isdigit() or not 1 <= int(v) <= 64:
                    print("netlist.py: --jobs takes 1..64", file=sys.stderr)
                    return 2
                jobs = int(v)
            i += 2
            continue
        rest.append(a)
        i += 1
    if len(rest) != 1 or form not in FORMS or (rtl is None) != (out is None) or flow not in FLOWS:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    build = rest[0]
    if rtl is not None:
        if not os.path.isdir(rtl):
            print(f"netlist.py: --rtl {rtl}: not a directory", file=sys.stderr)
            return 2
        use_rtl(rtl, out)
    units = units or (UNITS if cmd == "write" else FP_UNITS + ["apu_core"])
    failed = []
    try:
        for u in units:
            if u not in UNITS:
                raise Usage(f"unknown unit {u} (units: {','.join(UNITS)})")
        for u in units:
            if cmd == "write":
                write(build, u, flow=flow)
            elif cmd == "check":
                try:
                    check(build, u, form, jobs, flow=flow)
                except Failed as e:  # the other units are still checked
                    print(f"netlist.py: FAILED: {e}", file=sys.stderr, flush=True)
                    failed.append(u)
            else:
                for f in FORMS:
                    try:
                        with open(record_path(build, u, f, flow)) as fh:
                            rec = json.load(fh)
                    except (OSError, ValueError):
                        print(f"{flow_name(u, flow)}: no {f} check")
                        continue
                    print(f"{flow_name(u, flow)}: " + (describe(rec) if "sets" in rec or "programs" in rec else
                                      f"{f} check FAILED on {rec.get('date')}: {rec.get('error', '')[:300]}"))
    except Usage as e:
        print(f"netlist.py: {e}", file=sys.stderr)
        return 2
    except Failed as e:
        print(f"netlist.py: FAILED: {e}", file=sys.stderr)
        return 1
    if failed:
        print(f"netlist.py: the {form} check failed for {', '.join(failed)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
