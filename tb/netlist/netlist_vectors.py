#!/usr/bin/env python3
"""FP24 vector sets of the gate-level check (docs/apu-rtl.md "Gate-level
checks"; tools/netlist.py runs them on a unit's netlist against the model).

    netlist_vectors.py quick|full [OP,...] > vectors

Four sets, each a list of `op a [b]` lines in fp24-run's format:
  known       tb/vectors/fp24_known.vec (worked out by hand: ties, signed
              zeros, overflow, underflow, tininess after rounding)
  structured  every operand, and for two-operand ops every ordered pair, of
              exponent classes x significand patterns x both signs:
              quick 0 1 2 63 125 126 127 x 0000 0001 ffff 8000 7fff (70
              values, 4900 pairs); full 14 exponents x 12 patterns (336
              values, 112 896 pairs); FLOAT: the integer edges (full: all
              2^16 integers)
  boundary    results on the edges, exact integer arithmetic choosing the
              operands: MUL products whose 34-bit significand product is a
              tie (both parities), just below or above one, all ones (a
              rounding carry), or exact, each put at result exponents 126
              and 127 (overflow by rounding or outright), 1, 0 and -1 (the
              smallest normal, tininess after rounding, underflow) and 63;
              ADD/SUB: the largest finite plus every step from a whole ulp
              to a quarter (the tie rounds to odd-up: overflow), sums and
              differences near 2^-62 (underflow, exact zeros), an alignment
              tie at every shift 1..17 (lost bits exactly half, just below,
              just above, both parities), FIX around +-2^15 and the
              fractions, FLOAT's edges; RECIP and SIN/COS on every power of
              two, SQRT on exact squares and the exponent range
  random      seeded random operands, one in four from the edges (as
              tb/fp24_icarus_vectors.py), ADD/SUB half with b's exponent
              within 24 of a's (alignment, cancellation)
The same form gives the same vectors.
"""
import random
import sys

UNIT_OPS = {"fp24_mul": ["mul"],
            "fp24_add": ["add", "sub", "cmp", "float", "fix", "neg", "abs"],
            "fp24_func": ["recip", "sqrt", "sin", "cos"]}
ALL_OPS = [op for ops in UNIT_OPS.values() for op in ops]
TWO = ("mul", "add", "sub", "cmp")

EXPS = {"quick": [0, 1, 2, 63, 125, 126, 127],
        "full": [0, 1, 2, 3, 31, 62, 63, 64, 65, 95, 124, 125, 126, 127]}
SIGS = {"quick": [0x0000, 0x0001, 0xffff, 0x8000, 0x7fff],
        "full": [0x0000, 0x0001, 0x0002, 0x7fff, 0x8000, 0x8001, 0xfffe, 0xffff, 0x5555, 0xaaaa, 0x4000,
                 0xc000]}
# random vectors per op
RANDOM = {"quick": {"mul": 4000, "add": 1500, "sub": 1500, "cmp": 500, "float": 300, "fix": 500, "neg": 200,
                    "abs": 200, "recip": 100, "sqrt": 100, "sin": 100, "cos": 100},
          "full": {"mul": 100000, "add": 40000, "sub": 40000, "cmp": 10000, "float": 0, "fix": 10000,
                   "neg": 5000, "abs": 5000, "recip": 4000, "sqrt": 4000, "sin": 4000, "cos": 4000}}
EDGE_EXP = [0x00, 0x01, 0x02, 0x3e, 0x3f, 0x40, 0x41, 0x4e, 0x4f, 0x50, 0x7d, 0x7e, 0x7f]
EDGE_FRAC = [0x0000, 0x0001, 0x7fff, 0x8000, 0xfffe, 0xffff]
EDGE_INT = [0x0000, 0x0001, 0xffff, 0x7fff, 0x8000, 0x8001, 0xfffe, 0x4000, 0xc000, 0x00ff, 0xff00]
MAX = 0x7effff  # largest finite


def enc(s, e, f):
    return (s & 1) << 23 | (e & 0x7f) << 16 | (f & 0xffff)


def vec(op, a, b=None):
    if op == "float":
        return f"float {a:04x}"
    return f"{op} {a:06x}" if b is None else f"{op} {a:06x} {b:06x}"


def values(form):
    return [enc(s, e, f) for e in EXPS[form] for f in SIGS[form] for s in (0, 1)]


def structured(form, op):
    vs = values(form)
    if op in TWO:
        return [vec(op, a, b) for a in vs for b in vs]
    if op == "float":
        ints = range(1 << 16) if form == "full" else EDGE_INT
        return [vec(op, i) for i in ints]
    return [vec(op, a) for a in vs]


# ---- MUL on the edges ----

def split(p):
    """A 34-bit significand product: (17-bit significand, remainder, half,
    normalization shift)."""
    if p >> 33:
        return p >> 17, p & 0x1ffff, 0x10000, 1
    return p >> 16, p & 0xffff, 0x8000, 0


def factor(p, limit, rng):
    """Up to `limit` pairs (ma, mb) of 17-bit significands (hidden bit set)
    with ma * mb == p."""
    out = []
    starts = list(range(0x10000, 0x20000))
    for ma in starts:
        if p % ma == 0 and 0x10000 <= p // ma < 0x20000:
            out.append((ma, p // ma))
    rng.shuffle(out)
    return out[:limit]


def mul_pairs(form, rng):
    """Significand pairs whose product is a tie, next to one, all ones
    (rounding carries) or exact."""
    per = 3 if form == "quick" else 12
    pairs = [(0x10000, 0x10000), (0x1ffff, 0x10000), (0x10000, 0x1ffff), (0x1ffff, 0x1ffff)]
    targets = []
    for shift in (0, 1):
        half = 0x8000 << shift
        top = 0x1ffff << (16 + shift)
        for rem in (0, half - 1, half, half + 1):
            targets.append(top + rem)  # all ones: exact, below / at / above the tie (carry out)
        for sig in (0x10000, 0x10001, 0x12345, 0x1aaab):
            targets.append((sig << (16 + shift)) + half)  # a tie, both parities
    for t in targets:
        pairs += factor(t, per, rng)
    # ties from 1.5 * m: 3m odd gives a remainder of exactly half
    for _ in range(per * 4):
        ma = 0x10001 | rng.getrandbits(16) & 0x5555  # odd, below 0x15556
        pairs.append((ma, 0x18000))
        pairs.append((0x18000, ma ^ 0x2))
    return pairs


def mul_boundary(form, rng):
    out = []
    for ma, mb in mul_pairs(form, rng):
        _, _, _, shift = split(ma * mb)
        for er in (126, 127, 125, 63, 1, 0, -1):
            total = er + 63 - shift  # ea + eb
            splits = {min(126, total - 1), max(1, total - 126), total // 2}
            for ea in sorted(splits):
                eb = total - ea
                if not (1 <= ea <= 126 and 1 <= eb <= 126):
                    continue
                sa, sb = rng.getrandbits(1), rng.getrandbits(1)
                out.append(vec("mul", enc(sa, ea, ma & 0xffff), enc(sb, eb, mb & 0xffff)))
    return out


# ---- the adder on the edges ----

def add_boundary(form, op, rng):
    out = []
    sigs = [0x0000, 0x0001, 0x7fff, 0x8000, 0xffff] if form == "quick" else \
        [0x0000, 0x0001, 0x0002, 0x3fff, 0x4000, 0x7fff, 0x8000, 0x8001, 0xbfff, 0xfffe, 0xffff]
    # the largest finite plus a step: whole ulp down to a quarter ulp
    for d in range(0, 21):
        for f in sigs:
            for sa in (0, 1):
                for same in (True, False):
                    sb = sa if (same == (op == "add")) else 1 - sa
                    out.append(vec(op, enc(sa, 0x7e, 0xffff), enc(sb, 126 - d, f)))
                    out.append(vec(op, enc(sb, 126 - d, f), enc(sa, 0x7e, 0xffff)))
    # near 2^-62: differences of the smallest normals (underflow, exact zeros)
    small = [1, 2, 3] if form == "quick" else [1, 2, 3, 4, 17, 18]
    for ea in small:
        for eb in small:
            for fa in sigs:
                for fb in sigs:
                    sa = rng.getrandbits(1)
                    sb = 1 - sa if op == "add" else sa
                    out.append(vec(op, enc(sa, ea, fa), enc(sb, eb, fb)))
    # alignment ties: b's lost bits exactly half, just below, just above
    reps = 2 if form == "quick" else 8
    for d in range(1, 18):
        for _ in range(reps):
            e = rng.choice([2, 40, 63, 100, 126]) if d < 18 else 63
            e = max(e, d + 1)
            for fa in (0x0000, 0x0001, rng.getrandbits(16)):
                low = 1 << (d - 1)  # the lost bits of the 17-bit significand: 100..0
                hi = rng.getrandbits(17) & ~((1 << d) - 1) | 0x10000
                for lost in (low, low - 1 if low > 1 else 0, low + 1 if d > 1 else low):
                    mb = hi & ~((1 << d) - 1) | lost
                    if mb < 0x10000:
                        continue
                    for sa, sb in ((0, 0), (0, 1), (1, 0)):
                        out.append(vec(op, enc(sa, e, fa), enc(sb, e - d, mb & 0xffff)))
    return out


def fix_boundary(form):
    out = []
    sigs = [0x0000, 0x0001, 0x7fff, 0x8000, 0xfffe, 0xffff] + ([0x4000, 0xc000, 0x0002, 0xfffd] if form == "full" else [])
    for e in range(60 if form == "quick" else 40, 81):
        for f in sigs:
            for s in (0, 1):
                out.append(vec("fix", enc(s, e, f)))
    return out


# ---- the function unit on the edges ----

def func_boundary(form, op, rng):
    out = []
    step = 5 if form == "quick" else 1
    for e in range(1, 127, step):
        for s in (0, 1):
            out.append(vec(op, enc(s, e, 0)))
            if form == "full":
                out.append(vec(op, enc(s, e, rng.getrandbits(16))))
    if op == "sqrt":
        # exact squares: (m / 2^8)^2 for a 9-bit significand m, both exponent parities
        for _ in range(20 if form == "quick" else 300):
            m = 0x100 | rng.getrandbits(8)  # m / 2^8 in [1, 2)
            sq = m * m                       # (m / 2^8)^2 = sq / 2^16 in [1, 4)
            if sq < 0x20000:
                frac, odd = sq - 0x10000, 0
            elif sq % 2 == 0:
                frac, odd = (sq >> 1) - 0x10000, 1
            else:
                continue
            k = rng.randrange(-30, 31)
            out.append(vec(op, enc(0, 63 + 2 * k + odd, frac)))
    return out


def boundary(form, op, rng):
    if op == "mul":
        return mul_boundary(form, rng)
    if op in ("add", "sub"):
        return add_boundary(form, op, rng)
    if op == "fix":
        return fix_boundary(form)
    if op == "float":
        return [vec(op, i) for i in (0x7ffe, 0x8002, 0x0100, 0x0101, 0xfeff, 0x1fff, 0x2001)]
    if op in ("recip", "sqrt", "sin", "cos"):
        return func_boundary(form, op, rng)
    return []


# ---- random ----

def operand(rng, op):
    if op == "float":
        return rng.choice(EDGE_INT) if rng.random() < 0.25 else rng.getrandbits(16)
    if rng.random() < 0.25:
        f = rng.choice(EDGE_FRAC) if rng.random() < 0.5 else rng.getrandbits(16)
        return enc(rng.getrandbits(1), rng.choice(EDGE_EXP), f)
    return rng.getrandbits(24)


def random_set(form, op, rng):
    out = []
    for i in range(RANDOM[form][op]):
        a = operand(rng, op)
        if op in TWO:
            b = operand(rng, op)
            if op in ("add", "sub") and i % 2:
                e = min(127, max(0, ((a >> 16) & 0x7f) + rng.randrange(-24, 25)))
                b = b & ~(0x7f << 16) | e << 16
            out.append(vec(op, a, b))
        else:
            out.append(vec(op, a))
    return out


def known(path, ops):
    out = []
    with open(path) as f:
        for line in f:
            t = line.split()
            if t and not t[0].startswith("#") and t[0] in ops:
                out.append(" ".join(t))
    return out


def sets(form, ops, known_path):
    """[(set name, [vector lines])] for `ops` (None: every op), `form`
    quick or full."""
    ops = ops or ALL_OPS
    rng = random.Random(f"netlist-{form}")
    result = [("known", known(known_path, ops))]
    for name, gen in (("structured", lambda op: structured(form, op)),
                      ("boundary", lambda op: boundary(form, op, rng)),
                      ("random", lambda op: random_set(form, op, rng))):
        lines = []
        for op in ALL_OPS:  # the same rng sequence whatever `ops` is
            v = gen(op)
            if op in ops:
                lines += v
        result.append((name, lines))
    return result


def main(argv):
    if len(argv) not in (2, 3) or argv[1] not in ("quick", "full"):
        print("usage: netlist_vectors.py quick|full [OP,...]", file=sys.stderr)
        return 2
    ops = argv[2].split(",") if len(argv) == 3 else None
    if ops and any(op not in ALL_OPS for op in ops):
        print(f"netlist_vectors.py: ops are {','.join(ALL_OPS)}", file=sys.stderr)
        return 2
    import os
    here = os.path.dirname(os.path.abspath(__file__))
    for name, lines in sets(argv[1], ops, os.path.join(here, "..", "vectors", "fp24_known.vec")):
        sys.stdout.write(f"# {name}: {len(lines)}\n")
        sys.stdout.write("".join(l + "\n" for l in lines))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
