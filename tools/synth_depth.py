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
  ltp:    the longest path of all of these.
  paths:  per register, the deepest path into it (paths() below).

Every gate counts one level, an inverter too. An asynchronous memory read
counts the levels of the 2:1 multiplexer tree that would select its word,
ceil(log2 words) (the array's decoder and multiplexer are not gates in the
netlist); analyse(read_tree=False) counts it as one level, as Yosys's `ltp
-noff` does, for the cross-check. A synchronous read port is a register
(rank like a flip-flop, depth 0 at its data).
Exit 0; 2 on a usage or input error.
"""
import json
import re
import sys

RANK_CAP = 16  # a feed-forward pipeline of more stages than this is a loop


def is_ff(cell_type):
    return cell_type.startswith(("$_DFF", "$_SDFF", "$_DFFE", "$_SDFFE", "$_SDFFCE", "$_ALDFF", "$_DLATCH"))


class Netlist:
    """The gates, registers and drivers of one flattened module (see above)."""

    def __init__(self, mod):
        self.mod = mod
        # bit -> ("gate", index) | ("reg", index) | ("in", None)
        self.driver = {}
        self.gates = []        # (inputs, outputs)
        self.gate_counts = []  # False for an asynchronous memory read (not a cell of the stage)
        self.gate_name = []    # a memory's name for its asynchronous read, else None
        self.gate_levels = []  # gate levels of the gate: 1; an asynchronous read: its mux tree
        self.regs = []         # (count of flip-flops (0 for a memory port), input bits)
        self.reg_name = []     # the register's source name (netnames, memories' MEMID)
        self.names = bit_names(mod)
        driver, gates, regs = self.driver, self.gates, self.regs
        for name, p in mod["ports"].items():
            if p["direction"] == "input":
                for b in p["bits"]:
                    driver[b] = ("in", name)
        for cname, c in mod["cells"].items():
            t, conn, dirs = c["type"], c["connections"], c.get("port_directions", {})
            if is_ff(t):
                q = conn.get("Q", [])
                ins = [b for port, bits in conn.items() if port not in ("Q", "C") for b in bits]
                idx = len(regs)
                regs.append((len(q), ins))
                self.reg_name.append(base_name(self.names.get(q[0], cname)) if q else cname)
                for b in q:
                    driver[b] = ("reg", idx)
            elif t.startswith("$mem"):
                p = c["parameters"]
                nrd = _int(p["RD_PORTS"])
                clk_en = _int(p["RD_CLK_ENABLE"])
                abits = _int(p["ABITS"])
                width = _int(p["WIDTH"])
                mem = memory_name(p.get("MEMID", cname))
                tree = max(1, (_int(p["SIZE"]) - 1).bit_length())  # log2 words, rounded up
                wr_ins = [b for port in ("WR_ADDR", "WR_DATA", "WR_EN") for b in conn.get(port, [])]
                regs.append((0, wr_ins))
                self.reg_name.append(mem + " (write)")
                for i in range(nrd):
                    addr = conn["RD_ADDR"][i * abits:(i + 1) * abits]
                    data = conn["RD_DATA"][i * width:(i + 1) * width]
                    if (clk_en >> i) & 1:
                        idx = len(regs)
                        regs.append((0, addr + conn.get("RD_EN", [])[i:i + 1]))
                        self.reg_name.append(mem + " (read)")
                        for b in data:
                            driver[b] = ("reg", idx)
                    else:
                        idx = len(gates)
                        gates.append((addr, data))
                        self.gate_counts.append(False)
                        self.gate_name.append(mem + " (read)")
                        self.gate_levels.append(tree)
                        for b in data:
                            driver[b] = ("gate", idx)
            else:
                ins = [b for port, bits in conn.items() if dirs.get(port) == "input" for b in bits]
                outs = [b for port, bits in conn.items() if dirs.get(port) == "output" for b in bits]
                idx = len(gates)
                gates.append((ins, outs))
                self.gate_counts.append(True)
                self.gate_name.append(None)
                self.gate_levels.append(1)
                for b in outs:
                    driver[b] = ("gate", idx)
        self.order = self._topological_order()

    def _topological_order(self):
        """The gates in topological order (the netlist is combinationally
        acyclic: `check -assert` ran before)."""
        gates, driver = self.gates, self.driver
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
        return order


def _int(v):
    return int(v, 2) if isinstance(v, str) else int(v)


def bit_names(mod):
    """bit -> the user-given net name that carries it: a register's own name
    (s<k>_*, *_q) before the others, the shortest first."""
    names = {}

    def rank(name):  # a register's own name first: s<k>_*, *_q
        leaf = name.rsplit(".", 1)[-1]
        return (0 if re.match(r"s\d+_", leaf) or leaf.endswith("_q") else 1, len(name), name)

    for name, v in sorted(mod["netnames"].items(), key=lambda kv: rank(kv[0])):
        if v.get("hide_name"):
            continue
        for b in v["bits"]:
            if isinstance(b, int) and b not in names:
                names[b] = name
    return names


def memory_name(memid):
    """A memory's source name: flatten's instance path and the memory's name
    (a ROM that proc_rom made from a case: `u_func.u_trig.rom$3399`)."""
    name = memid.lstrip("\\").replace("$flatten\\", "").replace("\\", "")
    return re.sub(r"\$auto\$proc_rom\.cc:\d+:do_switch\$(\d+)", r"rom$\1", name)


def base_name(net):
    """A net's register name: flatten's hierarchy kept, array indices gone."""
    return re.sub(r"\[\d+\]", "", net.lstrip("\\"))


def analyse(mod, net=None, read_tree=True):
    """The stages of one flattened module of a Yosys JSON netlist (see above).
    read_tree=False counts an asynchronous memory read as one level, as
    Yosys's `ltp` does (the cross-check)."""
    net = net or Netlist(mod)
    driver, gates, gate_counts, regs, order = net.driver, net.gates, net.gate_counts, net.regs, net.order
    weight = net.gate_levels if read_tree else [1] * len(gates)

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
                level_of[b] = (lv + weight[g], rk)
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


def paths(mod, net=None):
    """The longest register-to-register path into each register of the
    module: one entry per register name (flatten's hierarchical name without
    the bit index; a memory's ports as "MEM (write)" / "MEM (read)"),
    deepest first:
      {"to": name, "depth": gate levels, "from": the register or input the
       path starts at, "through": the named nets it passes, in order, each
       as [name, the levels done where the path leaves it]}.
    Levels are counted as in analyse() (every gate one level, an
    asynchronous memory read one), so the first entry's depth is its ltp."""
    net = net or Netlist(mod)
    driver, gates, names = net.driver, net.gates, net.names
    level, via = {}, {}  # bit -> levels; bit -> the input bit on its longest path

    def lvl(b):
        d = driver.get(b) if isinstance(b, int) else None
        return level.get(b, 0) if d and d[0] == "gate" else 0

    for g in net.order:
        ins, outs = gates[g]
        best, arg = 0, None
        for b in ins:
            lb = lvl(b)
            if arg is None or lb > best:
                best, arg = lb, b
        for b in outs:
            level[b] = best + net.gate_levels[g]
            via[b] = arg

    def source_name(b):
        d = driver.get(b) if isinstance(b, int) else None
        if d is None:
            return "constant"
        if d[0] == "in":
            return "input " + d[1]
        if d[0] == "reg":
            return net.reg_name[d[1]]
        return None

    def trace(b):
        through = []
        while True:
            d = driver.get(b) if isinstance(b, int) else None
            if d is None or d[0] != "gate":
                return source_name(b), list(reversed(through))
            n = net.gate_name[d[1]] or (base_name(names[b]) if b in names else None)
            if n and (not through or through[-1][0] != n):
                through.append([n, lvl(b)])
            b = via[b]

    worst = {}  # register name -> (depth, endpoint bit)
    for (_, ins), name in zip(net.regs, net.reg_name):
        for b in ins:
            lb = lvl(b)
            if name not in worst or lb > worst[name][0]:
                worst[name] = (lb, b)
    out = []
    for name, (depth, b) in worst.items():
        src, through = trace(b)
        if through and through[-1][0] == name:
            through.pop()
        out.append({"to": name, "depth": depth, "from": src, "through": through})
    out.sort(key=lambda e: (-e["depth"], e["to"]))
    return out


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
    net = Netlist(mod)
    result = analyse(mod, net)
    result["paths"] = paths(mod, net)
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
