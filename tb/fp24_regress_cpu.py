#!/usr/bin/env python3
"""fp24-regress's "cpu-s" column and "cpu_seconds" are CPU time, not wall time.

Runs fp24-regress with four worker threads pinned to one CPU, so that each
worker waits for the CPU about three quarters of the time, and checks its
--json report: every op's cpu_seconds above zero, and their sum at most the
run's wall_seconds (one CPU cannot give more). Per-job wall time, which the
column used to hold, sums to about four times the wall time here and fails.

  fp24_regress_cpu.py FP24-REGRESS WORK_DIR
Exit status 0 pass, 1 fail, 2 usage.
"""

import json
import os
import subprocess
import sys

THREADS = 4
# The clocks are read a few microseconds apart; the sum of the ops' CPU
# times may exceed the wall time by no more than this.
EPSILON = 0.01


def main(argv):
    if len(argv) != 3:
        sys.stderr.write(__doc__)
        return 2
    program, work = argv[1], argv[2]
    os.makedirs(work, exist_ok=True)
    report = os.path.join(work, "cpu.json")
    cpu = min(os.sched_getaffinity(0))
    # 2 x 4,000,000 pairs in 122 jobs of 65536: all four workers busy till the end.
    cmd = [program, "--ops", "add,mul", "--random", "4000000", "--no-structured",
           "--threads", str(THREADS), "--json", report]
    run = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         preexec_fn=lambda: os.sched_setaffinity(0, {cpu}), timeout=600)
    if run.returncode != 0:
        print("FAIL: %s: exit %d\n%s%s" % (" ".join(cmd), run.returncode, run.stdout, run.stderr))
        return 1
    with open(report) as f:
        r = json.load(f)
    wall = r["wall_seconds"]
    ops = {op["op"]: op["cpu_seconds"] for op in r["ops"]}
    total = sum(ops.values())
    print("one CPU, %d threads: wall %.3f s, cpu %s, sum %.3f s" %
          (THREADS, wall, ", ".join("%s %.3f s" % kv for kv in ops.items()), total))
    failed = False
    for name, seconds in ops.items():
        if not seconds > 0:
            print("FAIL: %s: cpu_seconds %r, not above 0" % (name, seconds))
            failed = True
    if total > wall + EPSILON:
        print("FAIL: the ops' cpu_seconds sum to %.3f s, more than the run's %.3f s of wall time on one CPU"
              " (wall time of waiting workers counted as CPU time?)" % (total, wall))
        failed = True
    # The text report's cpu-s column is the same figure.
    rows = [line.split() for line in run.stdout.splitlines() if line.split()[:1] in (["add"], ["mul"])]
    for row in rows:
        if abs(float(row[7]) - ops[row[0]]) > 0.05 + 1e-9:
            print("FAIL: text report %s cpu-s %s, JSON %.3f" % (row[0], row[7], ops[row[0]]))
            failed = True
    if len(rows) != 2:
        print("FAIL: text report: %d op rows, wanted 2:\n%s" % (len(rows), run.stdout))
        failed = True
    print("FAIL" if failed else "PASS")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
