#!/usr/bin/env python3
"""The layer rule of the tree (docs/architecture.md): every #include and every
CMake link, include directory or source points down a layer, never up.

usage: check_layers.py [ROOT]     (default: the tree this script is in)

Each file belongs to a unit: hw/<unit>, host/<unit>, apu_rtl/rom and
apu_rtl/isa are units of their own, any other top folder (firmware, tb, tests, ...) is one unit.
ALLOWED says which units a unit may use besides itself. Checked:
  - `#include "x"` in C/C++ sources, resolved like the build does (includes are
    bare names found through per-target include directories): the including
    file's own folder first, else the one file in the tree whose path ends with
    x (on several, the one in the including unit; else an error). A name no
    tree file has is a system or generated header: generated ones are found
    from the OUTPUT/BYPRODUCTS of add_custom_command (or the arguments of an
    execute_process that generates at configure time) and belong to the unit
    of that CMakeLists.txt; the rest are outside the rule.
  - In every CMakeLists.txt: target_link_libraries (target names mapped to the
    unit whose CMakeLists.txt defines them with add_library/add_executable),
    and the tree paths named in target_include_directories, add_library and
    add_executable (${CMAKE_SOURCE_DIR}/..., ${PROJECT_SOURCE_DIR}/..., and
    variables set to them).
Every offence is printed as "file:line: ..."; the exit status is 1 if there is
any, 0 otherwise.
"""

import os
import re
import sys

HW_BASE = {"hw/platform", "hw/apu", "apu_rtl/rom", "apu_rtl/isa"}
HW_ALL = {"hw/platform", "hw/apu", "hw/apu_tlm", "hw/hdlc", "hw/image_bus", "hw/dc", "hw/fm", "hw/rc", "hw/nc", "hw/mc1"}
RTL = {"apu_rtl", "apu_rtl/rom", "apu_rtl/isa"}
HOST_LIBS = {"host/common", "host/scene", "host/apuasm", "host/imgcmp", "host/refrender", "host/apu_profile"}

# unit -> the units it may use (itself always). From the bottom up.
ALLOWED = {
    # The FP24 ROM generator runs the model's approximation core
    # (hw/apu/fp24_trig.cpp) to find the hard cases, and writes the ROM that the
    # model (fp24_rom.inc) and the RTL include: the one pair that uses each
    # other, through a generated file, not through code.
    "apu_rtl/rom": {"hw/apu"},
    # The instruction-set table: microword fields, op codes and latencies,
    # generated into the core's package and the models' apu_isa.hpp.
    "apu_rtl/isa": set(),
    "hw/platform": set(),
    "hw/apu": {"apu_rtl/rom", "apu_rtl/isa"},
    "apu_rtl": {"apu_rtl/rom", "apu_rtl/isa"},
    # The machine's units: each on the platform table, the APU and the
    # transports it talks through, none on another unit's internals.
    "hw/hdlc": {"hw/platform"},
    "hw/image_bus": {"hw/platform"},
    "hw/dc": {"hw/platform", "hw/image_bus"},
    "hw/fm": {"hw/platform", "hw/image_bus"},
    "hw/rc": HW_BASE | {"hw/hdlc"},
    "hw/nc": HW_BASE | {"hw/hdlc", "hw/image_bus"},
    # The APU as an sc_module for a user's test bench, on the engine it is handed.
    "hw/apu_tlm": HW_BASE,
    # The machine: every unit, wired.
    "hw/mc1": HW_ALL,
    # The RTL engine: the verilated APU core (apu_rtl/) behind the model's
    # ApuEngine interface, with its untraced models and trace signals; the
    # engine of mc1, the Python module and the benches; and the FP24 units'
    # harness (fp24_rtl.*: the verilated units one op a cycle). Not a unit the
    # machine uses: the application hands it to the machine (host/mc1).
    "hw/apu_rtl_engine": HW_BASE | RTL,
    # Plain data and tools that know no machine.
    "host/common": set(),  # output files written whole or not at all; command lines; JSON; shard reports
    "host/scene": {"host/common"},  # JSON (host/common/json.hpp)
    "host/imgcmp": {"host/common"},
    "host/apuasm": HW_BASE | {"host/common"},
    "host/refrender": {"host/common", "host/scene", "host/imgcmp"},
    # The APU's cycle and stall profiles and the files beside a waveform,
    # from ApuEngine's per-cycle records (either engine).
    "host/apu_profile": HW_BASE,
    # Firmware runs on an NC and the RC's side of a frame; it reads scenes.
    "firmware": HW_ALL - {"hw/mc1"} | {"host/scene"},
    # Test benches: the RTL under test, the models, firmware and host libraries.
    "tb": HW_ALL | RTL | {"hw/apu_rtl_engine", "firmware"} | HOST_LIBS,
    # The application: the machine, firmware, both APU engines, reports.
    "host/mc1": HW_ALL | RTL | {"hw/apu_rtl_engine", "firmware"} | HOST_LIBS,
    # Tests, the top-level build, tools and docs may use anything.
    "tests": None,
    # Fuzz harnesses: the libraries they drive, the FP24 vector reader of tb.
    "fuzz": HW_ALL | RTL | {"hw/apu_rtl_engine", "firmware", "tb"} | HOST_LIBS,
    "tools": None,
    # The Python module: the FP24 model and units (the units' harness,
    # hw/apu_rtl_engine/fp24_rtl.*), the APU on both engines, its profile, the
    # assembler, staged output files. No test bench.
    "python": HW_BASE | RTL | {"hw/apu_rtl_engine", "host/apu_profile", "host/apuasm", "host/common"},
    # Consumers of the installed package (they include <mc1/...>, not the tree).
    "examples": None,
    "": None,
}

CXX_EXT = (".c", ".cc", ".cpp", ".h", ".hpp", ".inc", ".ipp")
SKIP_DIRS = {"build", ".git"}
INCLUDE_RE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')
CMAKE_LINK_KEYWORDS = {"PUBLIC", "PRIVATE", "INTERFACE", "LINK_PUBLIC", "LINK_PRIVATE", "LINK_INTERFACE_LIBRARIES"}


def unit_of(rel):
    """The unit of a path relative to the root ('' for top-level files)."""
    parts = rel.split("/")
    if len(parts) == 1:
        return ""
    if parts[0] in ("hw", "host") and len(parts) > 2:
        return parts[0] + "/" + parts[1]
    if parts[0] == "apu_rtl" and len(parts) > 2 and parts[1] in ("rom", "isa"):
        return "apu_rtl/" + parts[1]
    return parts[0]


def may_use(user, used):
    """None when allowed, else the reason it is not."""
    if user == used or used == "":
        return None
    if user not in ALLOWED:
        return "unit %s has no rule in tools/check_layers.py ALLOWED" % (user or "(top)")
    allowed = ALLOWED[user]
    if allowed is None or used in allowed:
        return None
    return "%s must not use %s" % (user or "(top)", used)


def walk(root):
    for d, dirs, files in os.walk(root):
        dirs[:] = sorted(x for x in dirs if x not in SKIP_DIRS and not x.startswith((".", "build-")))
        for f in sorted(files):
            yield os.path.relpath(os.path.join(d, f), root).replace(os.sep, "/")


class Checker:
    def __init__(self, root):
        self.root = root
        self.files = list(walk(root))
        self.fileset = set(self.files)
        self.errors = []
        self.targets = {}    # CMake target -> unit
        self.generated = {}  # generated header name -> unit

    def error(self, rel, line, msg):
        self.errors.append("%s:%d: %s" % (rel, line, msg))

    # ---- #include ----

    def resolve(self, rel, name):
        """The tree file `#include "name"` in `rel` means, or None (outside the tree)."""
        own = os.path.normpath(os.path.join(os.path.dirname(rel), name)).replace(os.sep, "/")
        if own in self.fileset:
            return own
        hits = [f for f in self.files if f == name or f.endswith("/" + name)]
        if len(hits) > 1:
            same = [f for f in hits if unit_of(f) == unit_of(rel)]
            if len(same) == 1:
                return same[0]
            raise LookupError("ambiguous include \"%s\": %s" % (name, ", ".join(hits)))
        return hits[0] if hits else None

    def check_includes(self, rel):
        with open(os.path.join(self.root, rel), encoding="utf-8", errors="replace") as f:
            for n, text in enumerate(f, 1):
                m = INCLUDE_RE.match(text)
                if not m:
                    continue
                name = m.group(1)
                try:
                    target = self.resolve(rel, name)
                except LookupError as e:
                    self.error(rel, n, str(e))
                    continue
                used = unit_of(target) if target else self.generated.get(os.path.basename(name))
                if used is None:
                    continue
                why = may_use(unit_of(rel), used)
                if why:
                    self.error(rel, n, '#include "%s" (%s): %s' % (name, target or "generated", why))

    # ---- CMake ----

    def cmake_commands(self, rel):
        """(command, [(token, line)]) for every command call of a CMakeLists.txt."""
        text = open(os.path.join(self.root, rel), encoding="utf-8", errors="replace").read()
        out, i, line, n = [], 0, 1, len(text)
        while i < n:
            c = text[i]
            if c == "\n":
                line += 1
                i += 1
            elif c == "#":
                while i < n and text[i] != "\n":
                    i += 1
            elif c.isalpha() or c == "_":
                m = re.match(r"[A-Za-z_][A-Za-z0-9_]*", text[i:])
                j = i + m.end()
                while j < n and text[j] in " \t":
                    j += 1
                if j < n and text[j] == "(":
                    args, i, line = self.cmake_args(text, j + 1, line)
                    out.append((m.group(0).lower(), args))
                else:
                    i = j
            else:
                i += 1
        return out

    @staticmethod
    def cmake_args(text, i, line):
        args, tok, tok_line, depth, n = [], "", line, 0, len(text)

        def flush():
            nonlocal tok
            if tok:
                args.append((tok, tok_line))
            tok = ""

        while i < n:
            c = text[i]
            if c == '"':
                j = i + 1
                while j < n and text[j] != '"':
                    if text[j] == "\\":
                        j += 1
                    j += 1
                if not tok:
                    tok_line = line
                tok += text[i + 1:j]
                line += text[i:j].count("\n")
                i = j + 1
                continue
            if c == "#" and not tok:
                while i < n and text[i] != "\n":
                    i += 1
                continue
            if c in " \t\r\n":
                flush()
                if c == "\n":
                    line += 1
            elif c == "(":
                depth += 1
                tok += c
            elif c == ")":
                if depth == 0:
                    flush()
                    return args, i + 1, line
                depth -= 1
                tok += c
            else:
                if not tok:
                    tok_line = line
                tok += c
            i += 1
        flush()
        return args, i, line

    def tree_path(self, rel, token, variables):
        """The unit a CMake path token names inside the tree, or None."""
        def expand(m):
            v = m.group(1)
            if v in ("CMAKE_SOURCE_DIR", "PROJECT_SOURCE_DIR"):
                return "@ROOT@"
            if v == "CMAKE_CURRENT_SOURCE_DIR":
                return "@ROOT@/" + os.path.dirname(rel)
            return variables.get(v, m.group(0))
        t = token
        for _ in range(8):  # variables set to other variables
            t, before = re.sub(r"\$\{(\w+)\}", expand, t), t
            if t == before:
                break
        if not t.startswith("@ROOT@"):
            if "$" in t or t.startswith("-") or t.isupper():  # unknown variable, option, keyword
                return None
            t = "@ROOT@/" + os.path.dirname(rel) + "/" + t  # relative to this CMakeLists.txt
        p = os.path.normpath(t.replace("@ROOT@", "").lstrip("/")).replace(os.sep, "/")
        return unit_of(p + "/x") if os.path.isdir(os.path.join(self.root, p)) else unit_of(p)

    def cmake_files(self):
        return [f for f in self.files if os.path.basename(f) == "CMakeLists.txt"]

    def collect_targets(self):
        for rel in self.cmake_files():
            for cmd, args in self.cmake_commands(rel):
                if cmd in ("add_library", "add_executable") and args and "$" not in args[0][0]:
                    self.targets[args[0][0]] = unit_of(rel)
                if cmd in ("add_custom_command", "execute_process"):
                    for tok, _ in args:
                        if tok.endswith((".h", ".hpp", ".inc")) and "$<" not in tok:
                            self.generated[os.path.basename(tok)] = unit_of(rel)

    def check_cmake(self, rel):
        variables = {}
        for cmd, args in self.cmake_commands(rel):
            if cmd == "set" and len(args) >= 2:
                variables[args[0][0]] = " ".join(a for a, _ in args[1:])
            if not args:
                continue
            owner = self.targets.get(args[0][0], unit_of(rel))
            if cmd == "target_link_libraries":
                for tok, line in args[1:]:
                    if tok in CMAKE_LINK_KEYWORDS or tok not in self.targets:
                        continue
                    why = may_use(owner, self.targets[tok])
                    if why:
                        self.error(rel, line, "%s links %s: %s" % (args[0][0], tok, why))
            elif cmd in ("target_include_directories", "add_library", "add_executable", "target_sources"):
                for tok, line in args[1:]:
                    used = self.tree_path(rel, tok, variables)
                    why = used is not None and may_use(owner, used)
                    if why:
                        self.error(rel, line, "%s %s uses %s: %s" % (cmd, args[0][0], tok, why))

    def run(self):
        self.collect_targets()
        for rel in self.files:
            if rel.endswith(CXX_EXT):
                self.check_includes(rel)
            elif os.path.basename(rel) == "CMakeLists.txt":
                self.check_cmake(rel)
        return self.errors


def main(argv):
    root = argv[1] if len(argv) > 1 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    errors = Checker(root).run()
    for e in errors:
        print(e)
    if errors:
        print("check_layers: %d dependencies point up a layer (docs/architecture.md)" % len(errors))
        return 1
    print("check_layers: every include and link points down")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
