#!/usr/bin/env python3
"""Random FP24 vectors for the second-simulator test (docs/fp24-verification.md).

    fp24_icarus_vectors.py COUNT SEED > vectors

COUNT vectors of every op in fp24-run's format (`op a [b]`, hex), the ops
interleaved so that every unit sees back-to-back issues. One operand in four
comes from the edges of the format: +-0 and denormal encodings (DAZ), the
smallest and largest normals, +-inf, NaNs, 1 and its neighbours, and the
exponents next to them; FLOAT's operand is a 16-bit integer, its edges 0,
+-1, 0x7fff, 0x8000. The same COUNT and SEED give the same file.
Exit 0; 2 on a usage error.
"""
import random
import sys

OPS2 = ["add", "sub", "mul", "cmp"]
OPS1 = ["recip", "sqrt", "sin", "cos", "float", "fix", "neg", "abs"]
EDGE_EXP = [0x00, 0x01, 0x02, 0x3e, 0x3f, 0x40, 0x41, 0x4e, 0x4f, 0x50, 0x7d, 0x7e, 0x7f]
EDGE_FRAC = [0x0000, 0x0001, 0x7fff, 0x8000, 0xfffe, 0xffff]
EDGE_INT = [0x0000, 0x0001, 0xffff, 0x7fff, 0x8000, 0x8001, 0xfffe]


def operand(rng, op):
    if op == "float":
        return rng.choice(EDGE_INT) if rng.random() < 0.25 else rng.getrandbits(16)
    if rng.random() < 0.25:
        sign = rng.getrandbits(1)
        exp = rng.choice(EDGE_EXP)
        frac = rng.choice(EDGE_FRAC) if rng.random() < 0.5 else rng.getrandbits(16)
        return sign << 23 | exp << 16 | frac
    return rng.getrandbits(24)


def main(argv):
    if len(argv) != 3 or not argv[1].isdigit() or not argv[2].isdigit():
        print("usage: fp24_icarus_vectors.py COUNT SEED", file=sys.stderr)
        return 2
    count, rng = int(argv[1]), random.Random(int(argv[2]))
    out = []
    for _ in range(count):
        for op in OPS2 + OPS1:
            a = operand(rng, op)
            if op in OPS2:
                out.append(f"{op} {a:06x} {operand(rng, op):06x}")
            else:
                out.append(f"{op} {a:04x}" if op == "float" else f"{op} {a:06x}")
    sys.stdout.write("\n".join(out) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
