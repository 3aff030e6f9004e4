#!/usr/bin/env python3
"""Golden frames (docs/renderer.md "Golden frames"): frames the product makes,
locked bit for bit.

tests/golden/frames.txt lists the frames, one a line:

    NAME  GOLDEN  mc1 ARGUMENTS...

GOLDEN is `-` for a frame with its own golden file, tests/golden/NAME.txt, or
the NAME of the frame whose golden it must equal (the RTL engine's frame is
the ISS's). A golden file holds `key value` lines: the SHA-256 of the PNG the
frame's `mc1` command writes, then every simulated time and count of its
statistics JSON (`--stats`), flattened (`nc.3.busy_ps`); left out are the
host's figures (`host.*`), the fractions derived from the times (floats such
as `*_share`, `*utilization*`, `simulated_time_s`) and what names the run
rather than its result (`scene`, `engine`, `rtl_nodes`).

    golden_frames.py frame NAME --mc1 BIN --source SRC --work DIR [--bless]
        runs the frame and compares it with its golden: each differing field
        named with both values (exit 1); --bless (or MC1_BLESS_FRAMES=1 in the
        environment) writes the golden instead (a frame whose golden is
        another's is compared even then).
    golden_frames.py consistent --source SRC
        the goldens agree with each other and the list: one file per frame
        with its own golden, no file without a frame, and the same PNG for
        every frame of one scene at one size (the frame does not depend on
        the number of NCs or the engine).
"""
import argparse
import hashlib
import json
import os
import shlex
import subprocess
import sys

MANIFEST = "tests/golden/frames.txt"
SKIP_TOP = {"host", "scene", "engine", "rtl_nodes"}


def read_manifest(source):
    frames = {}
    with open(os.path.join(source, MANIFEST)) as f:
        for number, line in enumerate(f, 1):
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            words = shlex.split(line)
            if len(words) < 3:
                sys.exit(f"{MANIFEST}:{number}: expected NAME GOLDEN ARGUMENTS...")
            name, golden, args = words[0], words[1], words[2:]
            if name in frames:
                sys.exit(f"{MANIFEST}:{number}: frame {name} listed twice")
            frames[name] = {"golden": name if golden == "-" else golden, "args": args, "line": number}
    for name, fr in frames.items():
        g = frames.get(fr["golden"])
        if g is None or g["golden"] != fr["golden"]:
            sys.exit(f"{MANIFEST}:{fr['line']}: {name}'s golden {fr['golden']} is not a frame with a golden of its own")
    return frames


def flatten(value, prefix, out):
    if isinstance(value, dict):
        for k, v in value.items():
            if not prefix and k in SKIP_TOP:
                continue
            flatten(v, f"{prefix}.{k}" if prefix else k, out)
    elif isinstance(value, list):
        out[f"{prefix}.count"] = str(len(value))
        for i, v in enumerate(value):
            flatten(v, f"{prefix}.{i}", out)
    elif isinstance(value, float):
        return  # a fraction of the times, derived from them
    elif isinstance(value, bool):
        out[prefix] = "true" if value else "false"
    else:
        out[prefix] = str(value)


def run_frame(name, frame, mc1, source, work):
    os.makedirs(work, exist_ok=True)
    png = os.path.join(work, name + ".png")
    stats = os.path.join(work, name + ".json")
    for f in (png, stats):
        if os.path.exists(f):
            os.remove(f)
    args = [os.path.join(source, a) if a.startswith("scenes/") else a for a in frame["args"]]
    cmd = [mc1] + args + ["--quiet", "--out", png, "--stats", stats]
    print("$ " + " ".join(shlex.quote(c) for c in cmd), flush=True)
    rc = subprocess.run(cmd).returncode
    if rc != 0:
        sys.exit(f"{name}: mc1 exit status {rc}")
    with open(png, "rb") as f:
        fields = {"png_sha256": hashlib.sha256(f.read()).hexdigest()}
    with open(stats) as f:
        flatten(json.load(f), "", fields)
    return fields


def read_golden(path):
    fields = {}
    with open(path) as f:
        for line in f:
            line = line.rstrip("\n")
            if line and not line.startswith("#"):
                key, _, value = line.partition(" ")
                fields[key] = value
    return fields


def write_golden(path, name, frame, fields):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(f"# {name}: mc1 {' '.join(frame['args'])}\n")
        f.write("# written by tools/bless-frames.sh; compared bit for bit by ctest -L golden\n")
        for k, v in fields.items():
            f.write(f"{k} {v}\n")
    os.replace(tmp, path)


def compare(name, golden_name, want, got):
    bad = []
    for k in want:
        if k not in got:
            bad.append(f"{k}: golden {want[k]}, missing from the frame")
        elif got[k] != want[k]:
            bad.append(f"{k}: golden {want[k]}, got {got[k]}")
    bad += [f"{k}: not in the golden, got {got[k]}" for k in got if k not in want]
    if not bad:
        print(f"{name}: PNG and {len(want) - 1} statistics equal to golden {golden_name}")
        return 0
    print(f"{name}: {len(bad)} field(s) differ from golden tests/golden/{golden_name}.txt:", file=sys.stderr)
    for b in bad[:60]:
        print(f"  {name}: {b}", file=sys.stderr)
    if len(bad) > 60:
        print(f"  ... and {len(bad) - 60} more", file=sys.stderr)
    print("(a change meant to move them: tools/bless-frames.sh, and say why in the commit)", file=sys.stderr)
    return 1


def cmd_frame(a):
    frames = read_manifest(a.source)
    if a.name not in frames:
        sys.exit(f"{a.name}: not a frame of {MANIFEST}")
    frame = frames[a.name]
    got = run_frame(a.name, frame, a.mc1, a.source, a.work)
    golden_path = os.path.join(a.source, "tests/golden", frame["golden"] + ".txt")
    bless = a.bless or os.environ.get("MC1_BLESS_FRAMES") == "1"
    if bless and frame["golden"] == a.name:
        write_golden(golden_path, a.name, frame, got)
        print(f"{a.name}: blessed {golden_path}")
        return 0
    if not os.path.exists(golden_path):
        sys.exit(f"{a.name}: no golden {golden_path} (tools/bless-frames.sh writes it)")
    return compare(a.name, frame["golden"], read_golden(golden_path), got)


def image_key(args):
    """Frames of one scene (or the self-test) at one size make one image."""
    size = args[args.index("--size") + 1] if "--size" in args else "default"
    return (args[0], args[1] if args[0] == "render" else "", size)


def cmd_consistent(a):
    frames = read_manifest(a.source)
    folder = os.path.join(a.source, "tests/golden")
    bad = []
    own = {n for n, f in frames.items() if f["golden"] == n}
    files = {f[:-4] for f in os.listdir(folder) if f.endswith(".txt") and f != "frames.txt"}
    bad += [f"tests/golden/{n}.txt missing (tools/bless-frames.sh)" for n in sorted(own - files)]
    bad += [f"tests/golden/{n}.txt is no frame's golden ({MANIFEST})" for n in sorted(files - own)]
    images = {}
    for n in sorted(own & files):
        sha = read_golden(os.path.join(folder, n + ".txt")).get("png_sha256")
        images.setdefault(image_key(frames[n]["args"]), []).append((n, sha))
    for key, members in images.items():
        if len({sha for _, sha in members}) > 1:
            bad.append(f"{' '.join(x for x in key if x)}: the PNG differs between frames: " +
                       ", ".join(f"{n} {sha}" for n, sha in members))
    for b in bad:
        print(b, file=sys.stderr)
    if not bad:
        print(f"{len(own)} goldens for {len(frames)} frames; {len(images)} images, each the same PNG for every "
              "node count and engine")
    return 1 if bad else 0


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    f = sub.add_parser("frame")
    f.add_argument("name")
    f.add_argument("--mc1", required=True)
    f.add_argument("--source", required=True)
    f.add_argument("--work", required=True)
    f.add_argument("--bless", action="store_true")
    c = sub.add_parser("consistent")
    c.add_argument("--source", required=True)
    a = p.parse_args()
    return cmd_frame(a) if a.command == "frame" else cmd_consistent(a)


if __name__ == "__main__":
    sys.exit(main())
