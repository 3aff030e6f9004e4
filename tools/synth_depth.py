#!/usr/bin/env python3
"""Pipeline stages and logic depth of a flattened gate-level Yosys netlist.

    synth_depth.py NETLIST.json TOP

NETLIST.json is `write_json` after generic `synth` (gates $_AND_, $_MUX_, ...,
flip-flops $_DFF*_/$_SDFF*_, memories $mem_v2). Prints one JSON object:

  stages: one entry per register rank k = 1, 2, ...: the flip-flops whose
          input cone starts at the top's inputs or at rank k-1 registers
          (k = 1 + the highest rank in the cone), their count and the cone's
          depth in gate levels (the longest path from an input or a register
          to any input pin of a rank-k flip-flop: D, enable, reset).
  loop:   flip-flops whose cone reaches themselves (state fed back: a
          sequencer's pc, ...), same fields; ranks are meaningless there.
  outputs: the depth of the logic in front of the top's outputs.
  ltp:    the longest path of all of these, for the cross-check with
          `ltp -noff`.

Every gate counts one level, an inverter too. An asynchronous memory read
counts one level from its address to its data (the array's decoder and
multiplexer are not gates in the netlist); a synchronous read port is a
register (rank like a flip-flop, depth 0 at its data).
Exit 0; 2 on a usage or input error.
"""
import json
import sys

RANK_CAP = 16  # a feed-forward pipeline of more stages than this is a loop


def is_ff(cell_type):
    return cell_type.startswith(("$_DFF", "$_SDFF", "$_DFFE", "$_SDFFE", "$_SDFFCE", "$_ALDFF", "$_DLATCH"))


def analyse(mod):
    """The stages of one flattened module of a Yosys JSON netlist (see above)."""
    driver = {}   # bit -> ("gate", index) | ("reg", index) | ("in", None) | ("memrd", (cell, port))
    gates = []    # (inputs, outputs)
    gate_counts = []  # False for an asynchronous memory read (not a cell of the stage)
    regs = []     # (count of flip-flops (0 for a memory port), input bits)
    mem_async = []  # (addr bits, data bits)
    for name, p in mod["ports"].items():
        if p["direction"] == "input":
            for b in p["bits"]:
                driver[b] = ("in", None)
    for cname, c in mod["cells"].items():
        t, conn, dirs = c["type"], c["connections"], c.get("port_directions", {})
        if is_ff(t):
            q = conn.get("Q", [])
            ins = [b for port, bits in conn.items() if port not in ("Q", "C") for b in bits]
            idx = len(regs)
            regs.append((len(q), ins))
            for b in q:
                driver[b] = ("reg", idx)
        elif t.startswith("$mem"):
            p = c["parameters"]
            nrd = int(p["RD_PORTS"], 2) if isinstance(p["RD_PORTS"], str) else p["RD_PORTS"]
            clk_en = p["RD_CLK_ENABLE"]
            clk_en = int(clk_en, 2) if isinstance(clk_en, str) else clk_en
            abits = int(p["ABITS"], 2) if isinstance(p["ABITS"], str) else p["ABITS"]
            width = int(p["WIDTH"], 2) if isinstance(p["WIDTH"], str) else p["WIDTH"]
            wr_ins = [b for port in ("WR_ADDR", "WR_DATA", "WR_EN") for b in conn.get(port, [])]
            regs.append((0, wr_ins))
            for i in range(nrd):
                addr = conn["RD_ADDR"][i * abits:(i + 1) * abits]
                data = conn["RD_DATA"][i * width:(i + 1) * width]
                if (clk_en >> i) & 1:
                    idx = len(regs)
                    regs.append((0, addr + conn.get("RD_EN", [])[i:i + 1]))
                    for b in data:
                        driver[b] = ("reg", idx)
                else:
                    idx = len(gates)
                    gates.append((addr, data))
                    gate_counts.append(False)
                    for b in data:
                        driver[b] = ("gate", idx)
        else:
            ins = [b for port, bits in conn.items() if dirs.get(port) == "input" for b in bits]
            outs = [b for port, bits in conn.items() if dirs.get(port) == "output" for b in bits]
            idx = len(gates)
            gates.append((ins, outs))
            gate_counts.append(True)
            for b in outs:
                driver[b] = ("gate", idx)

    # Topological order of the gates (the netlist is combinationally acyclic:
    # `check -assert` ran before).
    order, state = [], [0] * len(gates)
    for g0 in range(len(gates)):
        if state[g0]:
            continue
        stack = [(g0, iter(gates[g0][0]))]
        state[g0] = 1
        while stack:
            g, it = stack[-1]
            nxt = None
            for b in it:
                d = driver.get(b)
                if d and d[0] == "gate" and not state[d[1]]:
                    nxt = d[1]
                    break
            if nxt is None:
                stack.pop()
                state[g] = 2
                order.append(g)
            else:
                state[nxt] = 1
                stack.append((nxt, iter(gates[nxt][0])))

    rank = [1] * len(regs)
    level_of = {}
    for _ in range(RANK_CAP + 1):
        level_of = {}   # bit -> (levels, highest source rank)

        def bit_info(b):
            d = driver.get(b)
            if d is None or d[0] == "in":
                return (0, 0)
            if d[0] == "reg":
                return (0, rank[d[1]])
            return level_of.get(b, (0, 0))

        for g in order:
            ins, outs = gates[g]
            lv, rk = 0, 0
            for b in ins:
                l, r = bit_info(b)
                lv, rk = max(lv, l), max(rk, r)
            for b in outs:
                level_of[b] = (lv + 1, rk)
        new = []
        for _, ins in regs:
            new.append(1 + max((bit_info(b)[1] for b in ins if isinstance(b, int)), default=0))
        if new == rank:
            break
        rank = [min(r, RANK_CAP + 1) for r in new]

    def cone(bits):
        best = 0
        for b in bits:
            if not isinstance(b, int):
                continue
            d = driver.get(b)
            if d and d[0] == "gate":
                best = max(best, level_of.get(b, (0, 0))[0])
        return best

    stages, loop = {}, {"cells": 0, "flip_flops": 0, "depth": 0}

    def entry(r):
        return loop if r > RANK_CAP else stages.setdefault(r, {"rank": r, "cells": 0, "flip_flops": 0, "depth": 0})

    for (n_ff, ins), r in zip(regs, rank):
        e = entry(r)
        e["flip_flops"] += n_ff
        e["depth"] = max(e["depth"], cone(ins))
    # A gate belongs to the stage that computes from its sources: one past
    # the highest register rank in its cone (the top's inputs are rank 0).
    for g in range(len(gates)):
        outs = gates[g][1]
        if outs and gate_counts[g]:
            entry(level_of.get(outs[0], (0, 0))[1] + 1)["cells"] += 1
    out_bits = [b for p in mod["ports"].values() if p["direction"] == "output" for b in p["bits"]]
    result = {
        "stages": [stages[k] for k in sorted(stages)],
        "loop": loop if loop["flip_flops"] or loop["cells"] else None,
        "outputs": cone(out_bits),
    }
    result["ltp"] = max([s["depth"] for s in result["stages"]] + [loop["depth"], result["outputs"]])
    return result


def main(argv):
    if len(argv) != 3:
        print("usage: synth_depth.py NETLIST.json TOP", file=sys.stderr)
        return 2
    try:
        with open(argv[1]) as f:
            mod = json.load(f)["modules"][argv[2]]
    except (OSError, ValueError, KeyError) as e:
        print(f"synth_depth.py: {argv[1]}: cannot read module {argv[2]}: {e}", file=sys.stderr)
        return 2
    print(json.dumps(analyse(mod)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
