#!/usr/bin/env python3
"""tools/rtl_equiv.py on the adder: the working tree's fp24_add against a
copy of itself is proven equivalent, and against a copy whose stage 2
computes in every cycle (where the tree's assigns a don't care without an
op: docs/fp24-rtl.md "Idle stages"); against copies with one change each (a
sticky bit no longer jammed into the sum, CMP no longer equating -0 and +0) it is
not, and the report names the unproven state.

    rtl_equiv_test.py BUILD_DIR
"""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.join(HERE, "..", "tools", "rtl_equiv.py")
RTL = os.path.join(HERE, "..", "apu_rtl")
BUILD = None


def run_against(edit=None):
    """rtl_equiv.py fp24_add against a copy of apu_rtl/, `edit` (old, new) applied to fp24_add.sv."""
    with tempfile.TemporaryDirectory() as gold:
        for f in os.listdir(RTL):
            if f.endswith((".sv", ".svh")):
                shutil.copy(os.path.join(RTL, f), gold)
        if edit:
            path = os.path.join(gold, "fp24_add.sv")
            text = open(path).read()
            assert edit[0] in text, edit[0]
            open(path, "w").write(text.replace(edit[0], edit[1], 1))
        p = subprocess.run([sys.executable, TOOL, "--gold-dir", gold, BUILD, "fp24_add"],
                           capture_output=True, text=True)
        return p.returncode, p.stdout + p.stderr


class RtlEquiv(unittest.TestCase):
    def test_same_design_is_proven(self):
        rc, out = run_against()
        self.assertEqual(rc, 0, out)
        self.assertIn("fp24_add: equivalent to", out)

    def test_dont_care_against_always_computed_is_proven(self):
        rc, out = run_against(("if (s1_valid && !s1_direct) begin", "if (1'b1) begin"))
        self.assertEqual(rc, 0, out)
        self.assertIn("fp24_add: equivalent to", out)

    def test_sticky_not_jammed_is_found(self):
        rc, out = run_against(("small_al[0] | sticky}", "small_al[0]}"))
        self.assertEqual(rc, 1, out)
        self.assertIn("NOT proven equivalent", out)
        self.assertIn("s1_sum", out)  # the register the sticky bit reaches

    def test_cmp_of_zeros_change_is_found(self):
        rc, out = run_against(("cmp_eq = mag_eq && ((a_sign == b_sign) || (a_mag == '0));",
                               "cmp_eq = mag_eq && (a_sign == b_sign);"))
        self.assertEqual(rc, 1, out)
        self.assertIn("NOT proven equivalent", out)


if __name__ == "__main__":
    BUILD = sys.argv.pop(1)
    unittest.main()
