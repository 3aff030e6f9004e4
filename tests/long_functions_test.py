#!/usr/bin/env python3
"""tools/long_functions.py on small fake trees: a function over the limit fails
the check, named by file:line and its name, unless the allow-list gives it a
reason; braces in comments and literals, initializer lists and data do not
confuse it; a source file over its limit fails; a stale or malformed
allow-list entry fails."""

import os
import subprocess
import sys
import tempfile
import unittest

CHECKER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools", "long_functions.py")


def body(n, indent="  "):
    """n - 2 statement lines: a body of n lines with its two braces."""
    return "".join("%sx += %d;\n" % (indent, i) for i in range(n - 2))


def check(files, *args):
    with tempfile.TemporaryDirectory() as root:
        for rel, text in files.items():
            path = os.path.join(root, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w") as f:
                f.write(text)
        p = subprocess.run([sys.executable, CHECKER, root] + list(args), capture_output=True, text=True)
        return p.returncode, p.stdout


class LongFunctions(unittest.TestCase):
    def test_the_limit_itself_passes_one_more_line_fails(self):
        rc, out = check({"hw/a/a.cpp": "int x;\nvoid f() {\n" + body(70) + "}\n"})
        self.assertEqual(rc, 0, out)
        self.assertIn("no function over 70 lines, no file over 700", out)
        rc, out = check({"hw/a/a.cpp": "int x;\n\nvoid f() {\n" + body(71) + "}\n"})
        self.assertEqual(rc, 1, out)
        self.assertIn("hw/a/a.cpp:3: f: 71 lines (limit 70)", out)

    def test_the_limit_is_an_option(self):
        rc, out = check({"firmware/a.cpp": "void f() {\n" + body(12) + "}\n"}, "--limit", "10")
        self.assertEqual(rc, 1, out)
        self.assertIn("firmware/a.cpp:1: f: 12 lines (limit 10)", out)

    def test_only_the_machine_firmware_host_and_benches_are_searched(self):
        long_fn = "void f() {\n" + body(80) + "}\n"
        rc, out = check({"tests/a_test.cpp": long_fn, "tools/x.cpp": long_fn, "hw/a/a.sv": long_fn})
        self.assertEqual(rc, 0, out)
        for d in ("hw/a/", "firmware/", "host/a/", "tb/"):
            rc, out = check({d + "x.hpp": long_fn})
            self.assertEqual(rc, 1, d + ": " + out)

    def test_methods_are_named_by_their_classes_not_namespaces(self):
        src = ("namespace mc1::x {\nclass Box {\n public:\n  int get() const {\n" + body(72, "    ") + "  }\n};\n"
               "struct Box::Inner {\n  void run();\n};\n"
               "void Box::Inner::run() {\n" + body(75) + "}\n}  // namespace mc1::x\n")
        rc, out = check({"host/x/box.hpp": src})
        self.assertEqual(rc, 1, out)
        self.assertIn("host/x/box.hpp:4: Box::get: 72 lines", out)
        self.assertIn(": Box::Inner::run: 75 lines", out)

    def test_braces_in_comments_and_literals_are_not_code(self):
        noise = ('  const char* s = "{{{ \\" {";\n  char c = \'{\';  // {\n  /* } } */\n'
                 '  auto r = R"x(} } })x";\n  int big = 1\'000\'000;\n')
        src = "void f() {\n" + noise + body(60) + "}\nvoid g() {\n" + body(71) + "}\n"
        rc, out = check({"tb/a.cpp": src})
        self.assertEqual(rc, 1, out)
        self.assertIn("tb/a.cpp:%d: g: 71 lines" % (1 + 5 + 59 + 1), out)
        self.assertNotIn(": f:", out)

    def test_a_constructor_with_braced_initializers_is_one_function(self):
        src = "Foo::Foo(int a)\n    : a_{a}, b_(a), v_{1, 2} {\n" + body(71) + "}\n"
        rc, out = check({"hw/a/foo.cpp": src})
        self.assertEqual(rc, 1, out)
        self.assertIn("hw/a/foo.cpp:1: Foo::Foo: 71 lines", out)

    def test_data_and_control_flow_are_not_functions(self):
        table = "const int t[] = {\n" + "".join("  %d,\n" % i for i in range(90)) + "};\n"
        enum = "enum class E {\n" + "".join("  e%d,\n" % i for i in range(90)) + "};\n"
        struct = "struct S {\n" + "".join("  int m%d;\n" % i for i in range(90)) + "};\n"
        rc, out = check({"hw/a/t.hpp": table + enum + struct})
        self.assertEqual(rc, 0, out)

    def test_lambdas_count_with_their_function_and_alone_at_namespace_scope(self):
        inner = "void f() {\n  auto l = [&](int y) {\n" + body(40, "    ") + "  };\n" + body(35) + "}\n"
        rc, out = check({"host/a/l.cpp": inner})
        self.assertEqual(rc, 1, out)
        self.assertIn("host/a/l.cpp:1: f: 75 lines", out)
        top = "namespace {\nconst auto g = [](int y) {\n" + body(71) + "};\n}\n"
        rc, out = check({"host/a/l.cpp": top})
        self.assertEqual(rc, 1, out)
        self.assertIn("host/a/l.cpp:2: lambda@2: 71 lines", out)

    def test_an_allowed_function_passes_a_stale_or_bad_entry_fails(self):
        files = {"hw/a/a.cpp": "void f() {\n" + body(80) + "}\n",
                 "tools/long_functions.allow": "# why\nhw/a/a.cpp  f  the reason\n"}
        rc, out = check(files)
        self.assertEqual(rc, 0, out)
        self.assertIn("but the 1 allowed", out)
        files["tools/long_functions.allow"] += "hw/a/a.cpp  g  gone\n"
        rc, out = check(files)
        self.assertEqual(rc, 1, out)
        self.assertIn("tools/long_functions.allow:3: stale: hw/a/a.cpp g", out)
        files["tools/long_functions.allow"] = "hw/a/a.cpp  f\n"
        rc, out = check(files)
        self.assertEqual(rc, 1, out)
        self.assertIn("long_functions.allow:1: an entry is", out)

    def test_a_long_source_file_fails_unless_allowed(self):
        big = "".join("int v%d = %d;\n" % (i, i) for i in range(701))
        rc, out = check({"host/a/big.cpp": big[:-len("int v700 = 700;\n")], "tb/big.cpp": big})
        self.assertEqual(rc, 0, out)
        rc, out = check({"firmware/kernels/k.apu": big})
        self.assertEqual(rc, 1, out)
        self.assertIn("firmware/kernels/k.apu: 701 lines (file limit 700)", out)
        rc, out = check({"hw/a/big.hpp": big, "tools/long_functions.allow": "hw/a/big.hpp (file) a reason\n"})
        self.assertEqual(rc, 0, out)
        rc, out = check({"hw/a/big.hpp": big[:100], "tools/long_functions.allow": "hw/a/big.hpp (file) a reason\n"})
        self.assertEqual(rc, 1, out)
        self.assertIn("stale: hw/a/big.hpp (file) is no file over 700 lines", out)


if __name__ == "__main__":
    unittest.main()
