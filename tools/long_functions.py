#!/usr/bin/env python3
"""Functions short enough to read without scrolling (docs/architecture.md
"Long functions"): lists every C++ function whose body is longer than the
limit, and fails on one that the allow-list does not name with a reason.

usage: long_functions.py [--limit N] [--file-limit N] [--allow FILE] [--all] [ROOT]
  ROOT     the tree (default: the one this script is in); searched: hw/,
           firmware/, host/, tb/ (.cpp, .hpp, .h, .cc)
  --limit  body lines allowed (default 70): from the line of the opening
           brace to the line of the closing one
  --file-limit  lines allowed in a source file of hw/, firmware/, host/
           (default 700; C++ and the APU kernels' .apu and .inc); its
           allow-list name is "(file)"
  --allow  the allow-list (default ROOT/tools/long_functions.allow): one line
           per function kept long, "path  name  reason"; '#' starts a comment
  --all    list every function over the limit, allowed ones too

A function is named as its definition spells it, with the classes it is
defined in ("Mc1System::report", "Iss::step"), without namespaces; a lambda
defined outside a function body is "lambda@LINE". Everything inside a
function body (its lambdas, its local classes) counts as the function's.
Comments, string and character literals (raw strings too) and preprocessor
lines are skipped. Printed: "file:line: name: N lines (limit L)" for each
function over the limit that is not allowed, "file: N lines (file limit L)"
for each such file, and the allow-list entries that name nothing over its
limit ("stale"); the exit status is 1 if there is any.
"""

import argparse
import os
import re
import sys

DIRS = ("hw", "firmware", "host", "tb")
EXTS = (".cpp", ".hpp", ".h", ".cc")
DEFAULT_LIMIT = 70
FILE_DIRS = ("hw", "firmware", "host")
FILE_EXTS = EXTS + (".apu", ".inc")
DEFAULT_FILE_LIMIT = 700
CONTROL = {"if", "for", "while", "switch", "catch", "return", "sizeof", "alignof", "decltype", "noexcept",
           "static_assert"}
CONTAINERS = {"namespace", "class", "struct", "union"}
ACCESS = re.compile(r"(?<![\w:])(?:public|private|protected)\s*:$")


def strip_code(text):
    """`text` with comments, literals and preprocessor lines blanked (newlines kept)."""
    out = []
    i, n = 0, len(text)
    at_line_start = True
    while i < n:
        c = text[i]
        if c == "\n":
            out.append(c)
            i += 1
            at_line_start = True
            continue
        if at_line_start and c in " \t":
            out.append(c)
            i += 1
            continue
        if at_line_start and c == "#":  # a preprocessor line, with its continuations
            while i < n and text[i] != "\n":
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    out.append("\n")
                    i += 2
                    continue
                i += 1
            continue
        at_line_start = False
        if text.startswith("//", i):
            while i < n and text[i] != "\n":
                i += 1
            continue
        if text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
            continue
        m = re.match(r'(?:u8|u|U|L)?R"([^()\\\s]{0,16})\(', text[i:i + 24])
        if m and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            end = text.find(")" + m.group(1) + '"', i + m.end())
            end = n if end < 0 else end + len(m.group(1)) + 2
            out.append('""' + re.sub(r"[^\n]", "", text[i:end]))
            i = end
            continue
        if c in "\"'":
            if c == "'" and re.search(r"(?<![\w.])[0-9][0-9A-Za-z']*$", text[max(0, i - 64):i]):
                i += 1  # a digit separator: 1'000'000
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
            continue
        out.append(c)
        i += 1
    return "".join(out)


def matching(s, i, open_c, close_c):
    """Index of the bracket closing the one at s[i]."""
    depth = 0
    for j in range(i, len(s)):
        if s[j] == open_c:
            depth += 1
        elif s[j] == close_c:
            depth -= 1
            if depth == 0:
                return j
    return -1


def top_level_paren(head):
    """Index of the first '(' of `head` outside <...> and [...], or -1."""
    angle = square = 0
    for i, c in enumerate(head):
        if c == "<":
            angle += 1
        elif c == ">" and angle:
            angle -= 1
        elif c == "[":
            square += 1
        elif c == "]" and square:
            square -= 1
        elif c == "(" and not square:
            return i
    return -1


def classify(head):
    """What a '{' after `head` (the text since the last ; { or }) opens:
    ("container", name), ("function", name), ("lambda", None), ("member-init", None) or ("data", None)."""
    h = " ".join(head.split())
    h = re.sub(r"^(template\s*<[^{;]*?>\s*)+", "", h)
    if not h:
        return ("data", None)
    words = re.findall(r"[A-Za-z_]\w*", h)
    p = top_level_paren(h)
    if words and words[0] in CONTAINERS | {"enum"} or re.match(r"^extern\s*(\"\")?$", h):
        if p < 0 or words[0] == "namespace":
            if words[0] == "enum":
                return ("data", None)
            m = re.match(r"^(?:namespace|class|struct|union)\s+(?:alignas\s*\(.*?\)\s*)?(?:\[\[.*?\]\]\s*)?([\w:]+)", h)
            name = m.group(1) if m and words[0] != "namespace" else ""
            if name == "final":
                name = ""
            return ("container", name)
    if p < 0:
        return ("data", None)
    before = h[:p].rstrip()
    if before.endswith("]"):
        return ("lambda", None)
    m = re.search(r"(operator\s*(?:\(\)|[^\s\w(]+|[\w:<> ]+?)|~?[A-Za-z_][\w]*(?:\s*<[^()]*>)?(?:\s*::\s*~?[A-Za-z_]\w*(?:\s*<[^()]*>)?)*)$",
                  before)
    if not m:
        return ("data", None)
    name = re.sub(r"\s+", "", m.group(1))
    last = name.split("::")[-1]
    if last in CONTROL:
        return ("data", None)
    prefix = before[:m.start()]
    if re.search(r"(?<![=!<>])=(?!=)", prefix) and "operator" not in name:
        return ("data", None)  # an initializer: x = f(...) { ... } is not a definition
    close = matching(h, p, "(", ")")
    if close < 0:
        return ("data", None)
    rest = h[close + 1:]
    init = re.search(r"(?<!:):(?!:)", rest)
    if init:  # a constructor's initializer list: the body follows a complete initializer
        tail = rest[init.end():].rstrip()
        if not tail.endswith((")", "}")):
            return ("member-init", None)
    return ("function", name)


class Function:
    def __init__(self, path, name, line, body_lines):
        self.path, self.name, self.line, self.body_lines = path, name, line, body_lines


def functions_of(path, text):
    """Every function body of one file, as Function."""
    code = strip_code(text)
    line_at = []
    ln = 1
    for c in code:
        line_at.append(ln)
        if c == "\n":
            ln += 1
    found = []

    def head_line(start, end):
        """Line of the first non-blank character of code[start:end]."""
        for k in range(start, end):
            if not code[k].isspace():
                return line_at[k]
        return line_at[end]

    def scope(i, classes, stop):
        """Scan a namespace or class body from i to its closing brace; returns the index after it."""
        head_start = i
        n = len(code)
        while i < n:
            c = code[i]
            if c == ";":
                head_start = i + 1
            elif c == ":" and ACCESS.search(code, head_start, i + 1) and code[i + 1:i + 2] != ":":
                head_start = i + 1  # public: private: protected: end a head too
            elif c == "}":
                if stop:
                    return i + 1
                head_start = i + 1
            elif c == "{":
                kind, name = classify(code[head_start:i])
                end = matching(code, i, "{", "}")
                if end < 0:
                    return n
                if kind == "container":
                    j = scope(i + 1, classes + ([name] if name else []), True)
                    head_start = j
                    i = j
                    continue
                if kind in ("function", "lambda"):
                    full = "::".join(classes + [name]) if kind == "function" else "lambda@%d" % line_at[i]
                    found.append(Function(path, full, head_line(head_start, i),
                                          line_at[end] - line_at[i] + 1))
                    head_start = end + 1
                # data and member initializers stay part of the head that follows
                i = end + 1
                continue
            i += 1
        return n

    scope(0, [], False)
    return found


def tree_functions(root):
    for d in DIRS:
        for base, dirs, files in os.walk(os.path.join(root, d)):
            dirs.sort()
            for f in sorted(files):
                if f.endswith(EXTS):
                    full = os.path.join(base, f)
                    rel = os.path.relpath(full, root).replace(os.sep, "/")
                    with open(full, encoding="utf-8", errors="replace") as fh:
                        yield from functions_of(rel, fh.read())


def long_files(root, limit):
    """(path, lines) of every source file of FILE_DIRS over `limit` lines."""
    for d in FILE_DIRS:
        for base, dirs, files in os.walk(os.path.join(root, d)):
            dirs.sort()
            for f in sorted(files):
                if f.endswith(FILE_EXTS):
                    full = os.path.join(base, f)
                    with open(full, encoding="utf-8", errors="replace") as fh:
                        n = sum(1 for _ in fh)
                    if n > limit:
                        yield os.path.relpath(full, root).replace(os.sep, "/"), n


def read_allow(path):
    """{(path, name): (line, reason)} of the allow-list; errors for malformed lines."""
    allow, errors = {}, []
    if not os.path.exists(path):
        return allow, errors
    with open(path, encoding="utf-8") as f:
        for n, text in enumerate(f, 1):
            text = text.split("#", 1)[0].strip()
            if not text:
                continue
            parts = text.split(None, 2)
            if len(parts) < 3:
                errors.append("%s:%d: an entry is \"path  name  reason\"" % (path, n))
                continue
            allow[(parts[0], parts[1])] = (n, parts[2])
    return allow, errors


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("root", nargs="?", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    ap.add_argument("--limit", type=int, default=DEFAULT_LIMIT)
    ap.add_argument("--file-limit", type=int, default=DEFAULT_FILE_LIMIT)
    ap.add_argument("--allow")
    ap.add_argument("--all", action="store_true")
    args = ap.parse_args(argv)
    root = os.path.normpath(args.root)
    allow_path = args.allow or os.path.join(root, "tools", "long_functions.allow")
    allow, errors = read_allow(allow_path)
    used = set()
    longest = 0
    for fn in tree_functions(root):
        if fn.body_lines <= args.limit:
            continue
        key = (fn.path, fn.name)
        if key in allow:
            used.add(key)
            if args.all:
                print("%s:%d: %s: %d lines (allowed: %s)" % (fn.path, fn.line, fn.name, fn.body_lines, allow[key][1]))
            continue
        longest = max(longest, fn.body_lines)
        errors.append("%s:%d: %s: %d lines (limit %d); split it, or give the reason in %s"
                      % (fn.path, fn.line, fn.name, fn.body_lines, args.limit, os.path.relpath(allow_path, root)))
    for path, n in long_files(root, args.file_limit):
        key = (path, "(file)")
        if key in allow:
            used.add(key)
            if args.all:
                print("%s: %d lines (allowed: %s)" % (path, n, allow[key][1]))
            continue
        errors.append("%s: %d lines (file limit %d); split it along its jobs, or give the reason in %s"
                      % (path, n, args.file_limit, os.path.relpath(allow_path, root)))
    for key, (n, _) in sorted(allow.items(), key=lambda kv: kv[1][0]):
        if key not in used:
            errors.append("%s:%d: stale: %s %s is no %s over %d lines" %
                          (os.path.relpath(allow_path, root), n, key[0], key[1],
                           "file" if key[1] == "(file)" else "function",
                           args.file_limit if key[1] == "(file)" else args.limit))
    for e in errors:
        print(e)
    if errors:
        return 1
    print("long_functions: no function over %d lines, no file over %d, but the %d allowed"
          % (args.limit, args.file_limit, len(used)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
