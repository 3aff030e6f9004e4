#!/usr/bin/env python3
"""Formal equivalence of an APU RTL module against an earlier version of it
(docs/apu-rtl.md "Equivalence"): a refactor of the RTL (for the simulator,
for depth, for area) is proven to change no output in any cycle, instead of
being sampled by vectors.

    rtl_equiv.py [--rev REV | --gold-dir DIR] [--seq N] BUILD_DIR MODULE

The gold design is apu_rtl/*.sv as committed at REV (default HEAD), or the
.sv files of DIR; the gate design is apu_rtl/*.sv of the working tree. Both
read BUILD_DIR/generated/apu_pkg.sv (the ISA table's package: a change of
the table is not a refactor). With Debian's Yosys 0.23: each side is read,
elaborated with MODULE on top, `proc`ed and flattened on its own (so the
two may differ in their submodules), then `equiv_make` pairs their outputs
and state by name, `equiv_simple` and `equiv_induct` (N cycles, default 2)
prove the pairs, and `equiv_status` counts them: all must be proven.
Registers are matched by name: a refactor that renames or retimes state is
beyond this check (it reports the unmatched cells as unproven). An `'x`
the RTL assigns on one branch is a don't care, as synthesis takes it
(`opt_expr -mux_undef` on both sides: the multiplexer keeps its other
input), so a value left open where nothing reads it (docs/fp24-rtl.md
"Idle stages") is proven as the netlist is built.

Exit 0: proven equivalent; 1: not proven (the unproven cells are listed);
2: usage error, a missing tool, or a design that does not read.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from synth import RTL, ROOT, sources  # noqa: E402  (the same files, in the same order, as synthesis reads)


def export_rev(rev, into):
    """apu_rtl/*.sv (and *.svh) as committed at rev, into the directory `into`."""
    listing = subprocess.run(["git", "-C", ROOT, "ls-tree", "--name-only", f"{rev}:apu_rtl"],
                             capture_output=True, text=True)
    if listing.returncode != 0:
        print(f"rtl_equiv: no apu_rtl/ at revision {rev!r}: {listing.stderr.strip()}", file=sys.stderr)
        sys.exit(2)
    for name in listing.stdout.split():
        if name.endswith((".sv", ".svh")):
            blob = subprocess.run(["git", "-C", ROOT, "show", f"{rev}:apu_rtl/{name}"], capture_output=True)
            with open(os.path.join(into, name), "wb") as f:
                f.write(blob.stdout)


def side(name, directory, gen, module):
    """Yosys commands that read one side and stash it as design `name`."""
    files = " ".join(sources(gen, directory))
    return (f"design -reset; read_verilog -sv -I{gen} -I{directory} {files}; "
            f"hierarchy -check -top {module}; proc; flatten; opt_clean; memory -nomap; opt -fast; "
            f"opt_expr -mux_undef; opt_clean; "
            f"rename {module} {name}; design -stash {name}; ")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    where = ap.add_mutually_exclusive_group()
    where.add_argument("--rev", default="HEAD", help="git revision of the gold apu_rtl/ (default HEAD)")
    where.add_argument("--gold-dir", help="a directory of the gold .sv files instead of a revision")
    ap.add_argument("--seq", type=int, default=2, help="cycles of equiv_simple / equiv_induct (default 2)")
    ap.add_argument("build", help="the build directory (its generated/apu_pkg.sv)")
    ap.add_argument("module", help="the module to compare (fp24_add, fp24_mul, apu_regfile, ...)")
    a = ap.parse_args()
    if not shutil.which("yosys"):
        print("rtl_equiv: yosys not found (tools/setup.sh installs it)", file=sys.stderr)
        return 2
    gen = os.path.join(os.path.abspath(a.build), "generated")
    if not os.path.isfile(os.path.join(gen, "apu_pkg.sv")):
        print(f"rtl_equiv: {gen}/apu_pkg.sv not found: configure the build first", file=sys.stderr)
        return 2
    if a.seq < 1:
        print(f"rtl_equiv: --seq must be at least 1, not {a.seq}", file=sys.stderr)
        return 2
    if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", a.module):
        print(f"rtl_equiv: not a module name: {a.module!r}", file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory(prefix="rtl_equiv.") as tmp:
        gold = a.gold_dir
        if gold is None:
            gold = os.path.join(tmp, "gold")
            os.mkdir(gold)
            export_rev(a.rev, gold)
        script = (side("gold", os.path.abspath(gold), gen, a.module) + side("gate", RTL, gen, a.module) +
                  "design -reset; design -copy-from gold -as gold gold; design -copy-from gate -as gate gate; "
                  f"equiv_make gold gate equiv; hierarchy -top equiv; async2sync; "
                  f"equiv_simple -seq {a.seq}; equiv_induct -seq {a.seq}; equiv_status")
        log = os.path.join(tmp, "yosys.log")
        r = subprocess.run(["yosys", "-q", "-l", log, "-p", script], capture_output=True, text=True)
        text = open(log).read() if os.path.exists(log) else ""
        if r.returncode != 0:
            tail = (r.stdout + r.stderr).strip().splitlines()[-5:]
            print(f"rtl_equiv: {a.module}: yosys failed:\n  " + "\n  ".join(tail), file=sys.stderr)
            return 2
    m = re.search(r"Of those cells (\d+) are proven and (\d+) are unproven", text)
    if not m:
        print(f"rtl_equiv: {a.module}: no equiv_status in Yosys's log", file=sys.stderr)
        return 2
    proven, unproven = int(m.group(1)), int(m.group(2))
    gold_name = a.gold_dir or a.rev
    if unproven == 0:
        print(f"rtl_equiv: {a.module}: equivalent to {gold_name} ({proven} cells proven, induction over {a.seq} cycles)")
        return 0
    print(f"rtl_equiv: {a.module}: NOT proven equivalent to {gold_name}: {unproven} of {proven + unproven} cells unproven")
    for line in re.findall(r"^\s*Unproven \$equiv .*$", text, re.M)[:20]:
        print("  " + line.strip())
    return 1


if __name__ == "__main__":
    sys.exit(main())
