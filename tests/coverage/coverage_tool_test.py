#!/usr/bin/env python3
"""tools/coverage.py's own rules, without a coverage build (default suite):
toggle waivers by bit list (N, A-B, A-B/S) leave those bits out of the
figure and a waived bit that toggled misses the goal; every toggle waiver of
tb/coverage/waivers.txt parses; the goals read a report.
  coverage_tool_test.py SOURCE_DIR"""
import io
import os
import sys
import contextlib

SRC = sys.argv[1]
sys.path.insert(0, os.path.join(SRC, "tools"))
import coverage as cov  # noqa: E402


def fail(msg):
    print(f"coverage_tool_test: {msg}", file=sys.stderr)
    sys.exit(1)


if cov.bit_set("1-7/2,8,10-11") != {1, 3, 5, 7, 8, 10, 11}:
    fail(f"bit_set: {cov.bit_set('1-7/2,8,10-11')}")
waivers = [("m.z[1-31/2]", "odd", 1), ("m.n*[0-2]", "pad", 2), ("m.flag", "whole", 3)]
for comment, want in [("z[3]", True), ("z[4]", False), ("n16[2]", True), ("n16[3]", False), ("flag", True),
                      ("zz[3]", False)]:
    if cov.toggle_waived(waivers, "m", comment) != want:
        fail(f"toggle_waived(m.{comment}) is not {want}")
# Points: (kind, file, line, column, comment) -> [count, module, comment, file].
rtl = os.path.join(SRC, "apu_rtl", "x.sv")
points = {("toggle", rtl, "1", "", f"z[{b}]"): [1 if b % 2 == 0 else 0, "m", "", rtl] for b in range(8)}
points[("toggle", rtl, "1", "", "z[9]")] = [1, "m", "", rtl]  # waived as constant, but toggled
toggled = []
_, figures, waived = cov.code_figures(points, waivers, toggled)
if figures["toggle"] != [4, 4] or waived != 5 or toggled != ["m.z[9]"]:
    fail(f"code_figures: {figures['toggle']}, {waived} waived, toggled {toggled}")
report = {"rtl": {"line": 100.0, "branch": 100.0, "toggle": 100.0}, "functional": {"bins": 2, "hit": 1, "waived": 1},
          "toggle_waived_but_toggled": toggled}
with contextlib.redirect_stdout(io.StringIO()) as out:
    ok = cov.check_goals(report)
if ok or "waived but hit or toggled: m.z[9]" not in out.getvalue():
    fail(f"a waived bit that toggled does not miss the goals:\n{out.getvalue()}")
report["toggle_waived_but_toggled"] = []
with contextlib.redirect_stdout(io.StringIO()):
    if not cov.check_goals(report):
        fail("goals met are reported missed")
for pattern, _reason, line in cov.read_waivers(os.path.join(SRC, "tb", "coverage", "waivers.txt")):
    if pattern.startswith("toggle:") and "[" in pattern:
        spec = pattern[pattern.index("[") + 1:-1]
        try:
            cov.bit_set(spec)
        except ValueError:
            fail(f"waivers.txt:{line}: '{spec}' is not a bit list")
print("coverage_tool_test: ok")
