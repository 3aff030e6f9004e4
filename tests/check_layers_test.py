#!/usr/bin/env python3
"""tools/check_layers.py on small fake trees: an include or a link that points
up a layer fails the check and is named by file:line; a tree that only points
down passes."""

import os
import subprocess
import sys
import tempfile
import unittest

CHECKER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools", "check_layers.py")


def make_tree(root, files):
    for rel, text in files.items():
        path = os.path.join(root, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            f.write(text)


def check(files):
    with tempfile.TemporaryDirectory() as root:
        make_tree(root, files)
        p = subprocess.run([sys.executable, CHECKER, root], capture_output=True, text=True)
        return p.returncode, p.stdout


BASE = {
    "hw/apu/microword.hpp": "#pragma once\n",
    "hw/apu/CMakeLists.txt": "add_library(apu_core STATIC iss.cpp)\n",
    "hw/apu/iss.cpp": '#include "microword.hpp"\n#include <vector>\n',
    "host/scene/scene.hpp": "#pragma once\n",
    "host/scene/CMakeLists.txt": "add_library(mc1_scene STATIC scene.cpp)\n",
    "firmware/fw.cpp": '#include "microword.hpp"\n#include "scene.hpp"\n',
    "firmware/CMakeLists.txt": "add_library(mc1_fw STATIC fw.cpp)\ntarget_link_libraries(mc1_fw PUBLIC\n  apu_core mc1_scene)\n",
}


class CheckLayers(unittest.TestCase):
    def assert_fails(self, changes, *expected, absent=()):
        """BASE with `changes` fails the check, printing every `expected` line part."""
        files = dict(BASE)
        files.update(changes)
        rc, out = check(files)
        self.assertEqual(rc, 1, out)
        for e in expected:
            self.assertIn(e, out)
        for a in absent:
            self.assertNotIn(a, out)

    def test_a_tree_that_points_down_passes(self):
        rc, out = check(BASE)
        self.assertEqual(rc, 0, out)
        self.assertIn("every include and link points down", out)

    def test_an_upward_include_is_named_by_file_and_line(self):
        self.assert_fails({"hw/apu/iss.cpp": '#include "microword.hpp"\n\n#include "scene.hpp"\n'},
                          'hw/apu/iss.cpp:3: #include "scene.hpp" (host/scene/scene.hpp): '
                          "hw/apu must not use host/scene",
                          "1 dependencies point up")

    def test_an_upward_link_is_named_by_file_and_line(self):
        self.assert_fails({"hw/apu/CMakeLists.txt": "add_library(apu_core STATIC iss.cpp)\n# a comment\n"
                                                    "target_link_libraries(apu_core PRIVATE\n  mc1_fw)\n"},
                          "hw/apu/CMakeLists.txt:4: apu_core links mc1_fw: hw/apu must not use firmware")

    def test_a_source_dir_path_into_a_higher_layer_is_named(self):
        self.assert_fails({"hw/apu/CMakeLists.txt": "set(TB ${CMAKE_SOURCE_DIR}/tb)\n"
                                                    "add_library(apu_core STATIC iss.cpp)\n"
                                                    "target_include_directories(apu_core PUBLIC ${TB})\n",
                           "tb/x.hpp": "#pragma once\n"},
                          "hw/apu/CMakeLists.txt:3: target_include_directories apu_core uses ${TB}: "
                          "hw/apu must not use tb")

    def test_the_own_folder_wins_and_an_ambiguous_name_is_an_error(self):
        # firmware/fw.cpp now means its own scene.hpp; hw/apu has none of its own.
        self.assert_fails({"firmware/scene.hpp": "#pragma once\n", "hw/apu/iss.cpp": '#include "scene.hpp"\n'},
                          'hw/apu/iss.cpp:1: ambiguous include "scene.hpp"', absent=["firmware/fw.cpp"])

    def test_a_generated_header_belongs_to_the_unit_that_generates_it(self):
        self.assert_fails({"firmware/CMakeLists.txt": BASE["firmware/CMakeLists.txt"] +
                           "add_custom_command(\n  OUTPUT ${GEN}/layout.hpp\n  COMMAND gen)\n",
                           "hw/apu/iss.cpp": '#include "layout.hpp"\n'},
                          'hw/apu/iss.cpp:1: #include "layout.hpp" (generated): hw/apu must not use firmware')

    def test_the_application_does_not_use_the_test_benches(self):
        # host/mc1 sits above tb in the table but uses none of it: the shard
        # reports it shares with fp24-regress are host/common's.
        self.assert_fails({"tb/shard_report.hpp": "#pragma once\n",
                           "host/mc1/sweep.cpp": '#include "scene.hpp"\n#include "shard_report.hpp"\n'},
                          'host/mc1/sweep.cpp:2: #include "shard_report.hpp" (tb/shard_report.hpp): '
                          "host/mc1 must not use tb")
        rc, out = check(dict(BASE, **{"host/common/shard_report.hpp": "#pragma once\n",
                                      "host/mc1/sweep.cpp": '#include "shard_report.hpp"\n'}))
        self.assertEqual(rc, 0, out)

    def test_a_unit_without_a_rule_is_an_error(self):
        self.assert_fails({"hw/gpu/gpu.cpp": '#include "microword.hpp"\n'},
                          "hw/gpu/gpu.cpp:1:", "unit hw/gpu has no rule")


if __name__ == "__main__":
    unittest.main()
