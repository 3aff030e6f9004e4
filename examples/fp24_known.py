"""FP24 golden vectors through the Python module: python3 fp24_known.py VEC EXPECTED"""
import sys, numpy as np, mc1
vec = [l.split() for l in open(sys.argv[1]) if l.strip() and not l.startswith("#")]
want = [tuple(int(x, 16) for x in l.split()) for l in open(sys.argv[2]) if l.strip()]
arr = lambda x: np.array([int(x, 16)], np.uint32)
bad = [(e, v, g, w) for e in ("model", "rtl") for v, w in zip(vec, want)
       for g in [tuple(int(x[0]) for x in mc1.fp24.run(v[0], arr(v[1]), arr(v[2]) if len(v) > 2 else None, e))] if g != w]
print(f"{len(vec)} vectors on model and rtl, {len(bad)} mismatches", *bad, sep="\n")
sys.exit(1 if bad or not vec or len(vec) != len(want) else 0)
