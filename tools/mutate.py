#!/usr/bin/env python3
"""Mutation score: apply listed one-line mutants to a scratch copy of HEAD.

The list (tools/mutants.txt) holds one mutant per block:

    mutant FILE:LINE
    old: exact text on that line
    new: replacement text
    tests: ctest -R regex expected to kill it
    why: short reason
    equivalent: REASON        (optional: kept, not run, not scored)

The copy is `git archive HEAD` under WORKDIR/src, configured and built once
(Release) in WORKDIR/src/build; a later run at a newer HEAD updates the
files that changed (git diff) and rebuilds incrementally. For each mutant: check the old text is on
its line (else the list is stale: refuse), apply, rebuild `all`, run
`ctest -R TESTS -LE long` (and with --full the default suite), record killed
(build failed, or which tests failed) or survived, restore the file. Nothing
is written under the repository this script lives in.

Exit status: 0 only if every non-equivalent mutant run was killed.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tarfile
import io
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
KEYS = ("old", "new", "tests", "why", "equivalent")


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def parse_block(header, lines, where):
    m = re.fullmatch(r"mutant (\S+):(\d+)", header)
    if not m:
        raise SystemExit(f"{where}: expected 'mutant FILE:LINE', got {header!r}")
    mut = {"file": m.group(1), "line": int(m.group(2))}
    for ln in lines:
        key, sep, val = ln.partition(":")
        if not sep or key not in KEYS:
            raise SystemExit(f"{where}: unknown field in {ln!r}")
        mut[key] = val[1:] if val.startswith(" ") else val
    for key in ("old", "new", "why"):
        if key not in mut:
            raise SystemExit(f"{where}: mutant without '{key}:'")
    if "tests" not in mut and "equivalent" not in mut:
        raise SystemExit(f"{where}: mutant without 'tests:' or 'equivalent:'")
    return mut


def parse_list(path):
    mutants, block, start = [], [], 0
    with open(path, encoding="utf-8") as f:
        rows = f.read().split("\n") + [""]
    for n, row in enumerate(rows, 1):
        if row.startswith("#"):
            continue
        if row.strip():
            start = start or n
            block.append(row)
        elif block:
            mut = parse_block(block[0], block[1:], f"{path}:{start}")
            mut["id"] = len(mutants) + 1
            mutants.append(mut)
            block, start = [], 0
    return mutants


def run(cmd, cwd, logpath, timeout=None):
    with open(logpath, "w") as out:
        try:
            return subprocess.run(cmd, cwd=cwd, stdout=out, stderr=subprocess.STDOUT,
                                  timeout=timeout).returncode
        except subprocess.TimeoutExpired:
            return -1


def head_commit():
    return subprocess.check_output(["git", "-C", REPO, "rev-parse", "HEAD"], text=True).strip()


def original(commit, path):
    return subprocess.check_output(["git", "-C", REPO, "show", f"{commit}:{path}"])


def sync_copy(src, old, commit):
    """Brings a copy of commit `old` to `commit` file by file (the build stays)."""
    names = subprocess.check_output(["git", "-C", REPO, "diff", "--name-only", old, commit], text=True).split()
    log(f"mutate: updating the copy from {old[:10]} to {commit[:10]}: {len(names)} files")
    for name in names:
        path = os.path.join(src, name)
        try:
            data = original(commit, name)
        except subprocess.CalledProcessError:  # removed at commit
            if os.path.exists(path):
                os.remove(path)
            continue
        os.makedirs(os.path.dirname(path), exist_ok=True)
        write(src, name, data)


def make_copy(workdir, commit):
    src = os.path.join(workdir, "src")
    stamp = os.path.join(workdir, "commit")
    old = open(stamp).read().strip() if os.path.exists(stamp) else ""
    if old == commit:
        return src
    if old and os.path.isdir(src):
        sync_copy(src, old, commit)
        with open(stamp, "w") as f:
            f.write(commit + "\n")
        return src
    log(f"mutate: copying {commit[:10]} to {src}")
    subprocess.run(["rm", "-rf", src], check=True)
    os.makedirs(src)
    data = subprocess.check_output(["git", "-C", REPO, "archive", commit])
    tarfile.open(fileobj=io.BytesIO(data)).extractall(src)
    with open(stamp, "w") as f:
        f.write(commit + "\n")
    return src


def build(src, logpath):
    if not os.path.exists(os.path.join(src, "build", "CMakeCache.txt")):
        cfg = ["cmake", "-S", src, "-B", os.path.join(src, "build"), "-DCMAKE_BUILD_TYPE=Release"]
        if run(cfg, src, logpath) != 0:
            return False
    return run(["cmake", "--build", "build", "-j2"], src, logpath) == 0


def failed_tests(logpath):
    text = open(logpath, errors="replace").read()
    tail = text.split("The following tests FAILED:")[-1] if "FAILED:" in text else ""
    names = re.findall(r"^\s*\d+ - (\S+)", tail, re.M)
    if "No tests were found" in text:
        names.append("(no tests matched)")
    return names


def ctest(src, args, logpath):
    cmd = ["ctest", "--test-dir", "build", "--timeout", "600", "-j2", "--output-on-failure"] + args
    rc = run(cmd, src, logpath)
    return rc, failed_tests(logpath)


def apply(src, mut, text):
    rows = text.split(b"\n")
    i = mut["line"] - 1
    old, new = mut["old"].encode(), mut["new"].encode()
    if i >= len(rows) or old not in rows[i]:
        raise SystemExit(f"mutant {mut['id']}: {mut['file']}:{mut['line']} does not hold "
                         f"{mut['old']!r}: the list is stale")
    rows[i] = rows[i].replace(old, new, 1)
    write(src, mut["file"], b"\n".join(rows))


def write(src, path, data):
    with open(os.path.join(src, path), "wb") as f:
        f.write(data)


def verdict(src, mut, full, logdir):
    base = os.path.join(logdir, f"m{mut['id']:03d}")
    if not build(src, base + ".build.log"):
        return "killed", "build failed"
    rc, failed = ctest(src, ["-R", mut["tests"], "-LE", "long"], base + ".test.log")
    if "(no tests matched)" in failed:
        return "error", f"no test matches {mut['tests']!r}"
    if rc != 0:
        return "killed", "failed: " + " ".join(failed[:8]) + (" ..." if len(failed) > 8 else "")
    if full:
        rc, failed = ctest(src, ["-LE", "long"], base + ".full.log")
        if rc != 0:
            return "killed", "full suite failed: " + " ".join(failed[:8])
    return "survived", f"{mut['tests']} passed"


def run_one(src, commit, mut, full, logdir):
    text = original(commit, mut["file"])
    apply(src, mut, text)
    t0 = time.time()
    try:
        status, detail = verdict(src, mut, full, logdir)
    finally:
        write(src, mut["file"], text)
    return status, detail, time.time() - t0


def where(mut):
    return f"{mut['file']}:{mut['line']}"


def print_table(results):
    print(f"{'id':>3}  {'status':10} {'secs':>5}  {'where':44} detail")
    for r in results:
        print(f"{r['id']:>3}  {r['status']:10} {r.get('seconds', 0):5.0f}  {r['where']:44} {r['detail']}")


def score(results):
    run_ = [r for r in results if r["status"] in ("killed", "survived", "error")]
    killed = sum(r["status"] == "killed" for r in run_)
    equiv = sum(r["status"] == "equivalent" for r in results)
    return {"killed": killed, "run": len(run_), "equivalent": equiv, "listed": len(results),
            "survived": [r["id"] for r in run_ if r["status"] != "killed"]}


def list_only(mutants):
    for m in mutants:
        tag = f"equivalent: {m['equivalent']}" if "equivalent" in m else f"tests: {m['tests']}"
        print(f"{m['id']:>3}  {where(m):44} {m['old']!r} -> {m['new']!r}  ({tag})")


def select(mutants, only):
    if not only:
        return mutants
    ids = {int(x) for x in only.split(",") if x}
    return [m for m in mutants if m["id"] in ids]


def check_fresh(mutants, commit):
    for m in mutants:
        row = original(commit, m["file"]).split(b"\n")[m["line"] - 1:m["line"]]
        if not row or m["old"].encode() not in row[0]:
            raise SystemExit(f"mutant {m['id']}: {where(m)} does not hold {m['old']!r}: the list is stale")


def check_lines(mutants):
    """--check: the list against the checkout's files (test mutants_list_current),
    so that a change that moves a listed line says so in the default suite."""
    stale = []
    for m in mutants:
        with open(os.path.join(REPO, m["file"]), "rb") as f:
            lines = f.read().split(b"\n")
        if m["line"] > len(lines) or m["old"].encode() not in lines[m["line"] - 1]:
            found = [str(i + 1) for i, x in enumerate(lines) if m["old"].encode() in x]
            stale.append(f"mutant {m['id']}: {where(m)} does not hold {m['old']!r}"
                         + (f" (it is on line {', '.join(found)})" if found else " (not in the file)"))
    for line in stale:
        print(line, file=sys.stderr)
    print(f"mutate: {len(mutants)} mutants, {len(stale)} stale")
    return 1 if stale else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--list-file", default=os.path.join(REPO, "tools", "mutants.txt"))
    ap.add_argument("--workdir", default="/tmp/mc1-mutate")
    ap.add_argument("--only", help="comma-separated mutant ids")
    ap.add_argument("--list", action="store_true", help="print the mutants and exit")
    ap.add_argument("--check", action="store_true",
                    help="check that every mutant's old text is on its line of the checkout, and exit")
    ap.add_argument("--full", action="store_true", help="also run the default suite")
    ap.add_argument("--json", help="write a JSON report here")
    a = ap.parse_args()
    mutants = select(parse_list(a.list_file), a.only)
    if a.list:
        return list_only(mutants)
    if a.check:
        return check_lines(mutants)
    commit = head_commit()
    check_fresh(mutants, commit)
    results = campaign(mutants, commit, a)
    return report(results, a.json)


def campaign(mutants, commit, a):
    src = make_copy(os.path.abspath(a.workdir), commit)
    logdir = os.path.join(os.path.abspath(a.workdir), "logs")
    os.makedirs(logdir, exist_ok=True)
    for m in mutants:  # an interrupted run may have left one applied
        write(src, m["file"], original(commit, m["file"]))
    t0 = time.time()
    if not build(src, os.path.join(logdir, "base.build.log")):
        raise SystemExit(f"mutate: the unmutated copy does not build: {logdir}/base.build.log")
    log(f"mutate: base build {time.time() - t0:.0f} s")
    baseline(src, mutants, logdir)
    results = []
    for k, m in enumerate(mutants, 1):
        results.append(one_result(src, commit, m, a.full, logdir, f"{k} of {len(mutants)}"))
        if a.json:  # a partial report survives an interrupted run
            write_json(a.json, results)
    return results


def baseline(src, mutants, logdir):
    """The unmutated copy must pass every test a mutant is to be killed by."""
    regex = "|".join(sorted({m["tests"] for m in mutants if "equivalent" not in m}))
    if not regex:
        return
    t0 = time.time()
    rc, failed = ctest(src, ["-R", regex, "-LE", "long"], os.path.join(logdir, "base.test.log"))
    if rc != 0:
        raise SystemExit(f"mutate: the unmutated copy fails {' '.join(failed)}: {logdir}/base.test.log")
    log(f"mutate: baseline tests pass in {time.time() - t0:.0f} s")


def one_result(src, commit, m, full, logdir, progress):
    r = {"id": m["id"], "where": where(m), "old": m["old"], "new": m["new"],
         "tests": m.get("tests", ""), "why": m["why"]}
    if "equivalent" in m:
        r.update(status="equivalent", detail=m["equivalent"])
        return r
    status, detail, secs = run_one(src, commit, m, full, logdir)
    r.update(status=status, detail=detail, seconds=round(secs, 1))
    log(f"mutate: mutant {m['id']} ({progress}) {where(m)} {status} in {secs:.0f} s: {detail}")
    return r


def write_json(path, results):
    with open(path, "w") as f:
        json.dump({"score": score(results), "mutants": results}, f, indent=1)


def report(results, json_path):
    print_table(results)
    s = score(results)
    print(f"\nscore: {s['killed']} killed of {s['run']} run "
          f"({s['equivalent']} equivalent, not run); survived: {s['survived'] or 'none'}")
    if json_path:
        write_json(json_path, results)
    return 0 if s["killed"] == s["run"] else 1


if __name__ == "__main__":
    sys.exit(main() or 0)
