#!/usr/bin/env python3
"""Waveforms that explain a bank stall (issue 45), end to end on the built
tools. One part a run:

  frame    mc1 render of whitted 32x32 on 4 NCs: the stall profile's summary
           and JSON give, for the top BANK stall site, the MPU's activities
           in its stall cycles (their cycles sum to the site's BANK stalls);
           the NC and time of that site's worst run traced in a window: the
           frame's simulated time is the untraced one's; the save file has
           the MPU group, its filters, and marker A at the site, named with
           the MPU's shares; the FST read back (fst2vcd): at marker A's cycle
           the APU waits for the bank (TOP.mc1.bank_req) at the site's word,
           and the MPU does what the profile names first; over the window, the
           MPU's activities in the site's BANK cycles are the marker's shares.
  apu_run  apu-run --trace of a stream kernel on four data blocks: the tool's
           hand-overs (TOP.mc1.bank_grant) and, in every BANK stall cycle,
           mpu_doing `poll` (the tool hands the next bank over at its next
           poll); the stall profile's marker names it.
  gtkwave  the frame's save file opened in GTKWave under Xvfb: it loads the
           trace and every filter, and its screenshot is not blank (skipped
           without xvfb-run).

  waveform_test.py PART BIN_DIR SOURCE_DIR WORK_DIR FST2VCD"""
import json
import os
import re
import shutil
import subprocess
import sys

PART, BIN, SRC, WORK, FST2VCD = sys.argv[1:6]
CYCLE_PS = 250000


sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "testlib"))
import mc1_testlib as lib  # noqa: E402
lib.setup(f"waveform {PART}", work=WORK, bin_dir=BIN)
fail, run, tool = lib.fail, lib.run, lib.tool


def read(name):
    return open(os.path.join(WORK, name)).read()


def filter_table(name):
    """A GTKWave translate filter: value text -> name."""
    table = {}
    for line in read(name).splitlines():
        if line and not line.startswith("#"):
            value, _, text = line.partition(" ")
            table[value.upper()] = text
    return table


def vcd_cycles(fst, names):
    """The FST's values of `names` (full names, TOP.x.y) in each APU cycle:
    the values dumped at the cycle's start (the falling edge before it), as
    (time_ps, {name: int}), one per rising edge of TOP.apu_core.clk."""
    if not FST2VCD:
        fail("no fst2vcd")
    vcd = subprocess.run(["timeout", "120", FST2VCD, os.path.join(WORK, fst)], capture_output=True, text=True)
    if vcd.returncode != 0:
        fail(f"fst2vcd {fst}: exit {vcd.returncode}")
    ids, scope, body = {}, [], 0
    lines = vcd.stdout.splitlines()
    for i, line in enumerate(lines):
        w = line.split()
        if not w:
            continue
        if w[0] == "$scope":
            scope.append(w[2])
        elif w[0] == "$upscope":
            scope.pop()
        elif w[0] == "$var":
            full = ".".join(scope + [w[4]])
            if full in names or full == "TOP.apu_core.clk":
                ids.setdefault(w[3], []).append(full)
        elif w[0] == "$enddefinitions":
            body = i + 1
            break
    missing = [n for n in names if not any(n in v for v in ids.values())]
    if missing:
        fail(f"{fst}: no signal {missing}")
    state, out, time, before = {}, [], 0, {}
    for line in lines[body:]:
        if line.startswith("#"):
            before = dict(state)
            time = int(line[1:])
            continue
        if line[0] in "01xz" and line[1:] in ids:
            value, ident = line[0], line[1:]
        elif line[0] == "b" and line.split()[1] in ids:
            value, ident = line[1:].split()
        else:
            continue
        v = int(value, 2) if set(value) <= {"0", "1"} else -1
        for n in ids[ident]:
            if n == "TOP.apu_core.clk" and v == 1 and before.get(n) == 0:
                out.append((time - CYCLE_PS // 2, dict(before)))
            state[n] = v
    return out


def shares_of(text):
    """'copy (s2 shadows) 58%, wait_rc 42%' -> {'copy (s2 shadows)': 58, ...}."""
    return {m.group(1): int(m.group(2)) for m in re.finditer(r"(?:^|, )(.+?) (\d+)%", text)}


MPU = ["TOP.mc1.mpu_doing", "TOP.mc1.mpu_step", "TOP.mc1.bank_req", "TOP.mc1.bank_grant", "TOP.mc1.kernel_id",
       "TOP.apu_core.pc", "TOP.mc1.mpu_words_left"]


def top_bank_site(prof):
    best = None
    for k in prof["kernels"]:
        for s in k["sites"]:
            if s["stalls"]["bank"] and (best is None or s["stalls"]["bank"] > best[1]["stalls"]["bank"]):
                best = (k, s)
    if best is None:
        fail("the profile has no BANK stall")
    return best


def frame():
    scene = os.path.join(SRC, "scenes/whitted.json")
    base = [tool("mc1"), "render", scene, "--size", "32x32", "--nodes", "4"]
    out = run(base + ["--stats", "s.json", "--profile", "p.json"]).stdout
    prof = json.load(open(os.path.join(WORK, "p.json")))
    kernel, site = top_bank_site(prof)
    bank = site["stalls"]["bank"]
    named = sum(a["cycles"] for a in site.get("bank_mpu", []))
    if named != bank:
        fail(f"{kernel['name']} 0x{site['pc']:03x}: the MPU's activities cover {named} of its {bank} BANK stall cycles")
    first = site["bank_mpu"][0]["activity"]
    line = re.search(rf"{kernel['name']} +0x{site['pc']:03x} .*\n +the MPU in its {bank} BANK stall cycles: (.*)\n", out)
    if not line or not line.group(1).startswith(first + " "):
        fail(f"the summary does not give the MPU's shares of {kernel['name']} 0x{site['pc']:03x} ({first} first):\n{out}")
    # The site's worst run, traced on its NC.
    worst = site["worst"]
    start = worst["time_ps"] - 20 * CYCLE_PS
    end = worst["time_ps"] + (worst["cycles"] + 400) * CYCLE_PS
    run(base + ["--quiet", "--stats", "s2.json", "--trace", "t.fst", "--trace-node", str(worst["nc"]),
                "--trace-from", f"{start}ps", "--trace-to", f"{end}ps"])
    t1 = json.load(open(os.path.join(WORK, "s.json")))["simulated_time_ps"]
    t2 = json.load(open(os.path.join(WORK, "s2.json")))["simulated_time_ps"]
    if t1 != t2:
        fail(f"the trace moved the frame: {t1} ps untraced, {t2} ps traced")
    save = read("t.fst.gtkw")
    for want in ["-MPU\n", "^17 " + os.path.join(WORK, "t.fst.mpu_doing.txt") + "\nTOP.mc1.mpu_doing[3:0]",
                 "^18 " + os.path.join(WORK, "t.fst.mpu_step.txt") + "\nTOP.mc1.mpu_step[15:0]", "TOP.mc1.bank_req\n"]:
        if want not in save:
            fail(f"t.fst.gtkw has no '{want}'")
    # GTKWave sizes the signal pane's name column to its longest label, and
    # a long group title pushed the values past the pane's edge ("kpc=b").
    long = [line for line in save.splitlines() if line.startswith("-") and len(line) > 25]
    if long:
        fail(f"t.fst.gtkw has group titles over 24 characters, which cut the values off in GTKWave: {long}")
    m = re.search(r"^\[\*\] A (\d+) ps \(.*\): (\S+) pc 0x([0-9a-f]+), .*\n\[\*\]   the MPU in its BANK stalls there: (.*)$",
                  save, re.M)
    if not m or m.group(2) != kernel["name"] or int(m.group(3), 16) != site["pc"]:
        fail(f"marker A is not at {kernel['name']} 0x{site['pc']:03x} with the MPU's shares:\n{save[:1500]}")
    at, marker_shares = int(m.group(1)), shares_of(m.group(4))
    name = re.search(r"^\[markername\] A(.*)$", save, re.M)
    if not name or "MPU " + m.group(4) not in name.group(1):
        fail(f"marker A's name does not carry the MPU's shares: {name and name.group(1)}")
    check_frame_fst(kernel, site, at, marker_shares, prof)


def mpu_name(doing, step, cycle):
    d = doing.get(f"{cycle['TOP.mc1.mpu_doing']:X}", "?")
    s = step.get(f"{cycle['TOP.mc1.mpu_step']:04X}", "-")
    return d if s == "-" else f"{d} ({s})"


def check_frame_fst(kernel, site, at, marker_shares, prof):
    doing, step = filter_table("t.fst.mpu_doing.txt"), filter_table("t.fst.mpu_step.txt")
    kernels = filter_table("t.fst.kernel.txt")
    cycles = vcd_cycles("t.fst", MPU)
    here = [c for t, c in cycles if abs(t - at) < CYCLE_PS // 2]
    if not here:
        fail(f"no cycle of the trace starts at marker A ({at} ps)")
    c = here[0]
    if not (c["TOP.mc1.bank_req"] == 1 and kernels.get(f"{c['TOP.mc1.kernel_id']:04X}") == kernel["name"]
            and c["TOP.apu_core.pc"] == site["pc"]):
        fail(f"at marker A the APU does not wait for the bank at {kernel['name']} 0x{site['pc']:03x}: {c}")
    now = mpu_name(doing, step, c)
    names = [a["activity"] for a in site["bank_mpu"]]
    if now not in names:
        fail(f"at marker A the MPU does '{now}', which the profile does not name ({names})")
    # Over the window: the site's BANK cycles by MPU activity, as the marker says.
    count = {}
    for t, c in cycles:
        if (c["TOP.mc1.bank_req"] == 1 and c["TOP.apu_core.pc"] == site["pc"]
                and kernels.get(f"{c['TOP.mc1.kernel_id']:04X}") == kernel["name"]):
            n = mpu_name(doing, step, c)
            count[n] = count.get(n, 0) + 1
    total = sum(count.values())
    got = {n: round(100 * k / total) for n, k in count.items()}
    for n, share in marker_shares.items():
        if n != "other" and abs(got.get(n, 0) - share) > 1:
            fail(f"marker A says the MPU did '{n}' {share}% of the site's BANK stalls; the waveform: {got}")
    print(f"waveform frame: marker A {kernel['name']} 0x{site['pc']:03x} at {at} ps, MPU '{now}'; "
          f"window shares {got}; profile {names}")


# A stream kernel that does nothing with its blocks: it waits for the next
# at once, so the tool's 16-cycle polls keep it waiting (BANK stalls).
STREAM = """        .org 0
block:  swapd
        ld f63, [a0+0]
        movfa a2, f63
        bz a2, done
        jmp block
done:   halt
"""


def apu_run():
    open(os.path.join(WORK, "s.apu"), "w").write(STREAM)
    args = [tool("apu-run"), "s.apu", "--engine", "rtl", "--trace", "x.fst", "--profile-json", "x.json"]
    for i in range(3):
        open(os.path.join(WORK, f"n{i}.txt"), "w").write("@0 000001\n")
        args += ["--data", f"n{i}.txt"]
    open(os.path.join(WORK, "end.txt"), "w").write("@0 000000\n")
    run(args + ["--data", "end.txt"])
    doing = filter_table("x.fst.mpu_doing.txt")
    cycles = vcd_cycles("x.fst", MPU)
    grants = sum(1 for _, c in cycles if c["TOP.mc1.bank_grant"] == 1)
    bank = [doing.get(f"{c['TOP.mc1.mpu_doing']:X}") for _, c in cycles if c["TOP.mc1.bank_req"] == 1]
    if grants < 2:
        fail(f"apu-run's hand-overs: {grants} cycles with TOP.mc1.bank_grant in the waveform")
    if not bank or set(bank) != {"poll"}:
        fail(f"apu-run: the tool's activity in the BANK stall cycles: {sorted(set(bank))} (wanted poll)")
    prof = json.load(open(os.path.join(WORK, "x.json")))
    _, site = top_bank_site(prof)
    if [a["activity"].split()[0] for a in site["bank_mpu"]] != ["poll"] or site["bank_mpu"][0]["cycles"] != len(bank):
        fail(f"apu-run's profile: {site['bank_mpu']} for {len(bank)} BANK cycles in the waveform")
    if not re.search(r"^\[markername\] A.* bank: MPU poll", read("x.fst.gtkw"), re.M):
        fail("apu-run's marker A does not name the tool's poll")
    print(f"waveform apu_run: {grants} hand-over cycles, {len(bank)} BANK cycles, all 'poll'")


def gtkwave():
    if not shutil.which("xvfb-run") or not shutil.which("gtkwave"):
        print("waveform gtkwave: no xvfb-run or gtkwave; not checked")
        return
    scene = os.path.join(SRC, "scenes/whitted.json")
    run([tool("mc1"), "render", scene, "--size", "32x32", "--nodes", "4", "--quiet", "--trace", "g.fst",
         "--trace-node", "3", "--trace-from", "156ms", "--trace-to", "157ms"])
    fb = os.path.join(WORK, "fb")
    os.makedirs(fb, exist_ok=True)
    script = os.path.join(WORK, "shot.sh")
    open(script, "w").write("#!/bin/sh\ngtkwave \"$1\" > \"$2\" 2>&1 &\npid=$!\nsleep 8\n"
                            f"cp {fb}/Xvfb_screen0 \"$3\"\nkill $pid\n")
    os.chmod(script, 0o755)
    subprocess.run(["timeout", "120", "xvfb-run", "-a", "-s", f"-screen 0 1600x1000x24 -fbdir {fb}", script,
                    os.path.join(WORK, "g.fst.gtkw"), os.path.join(WORK, "gtkwave.log"),
                    os.path.join(WORK, "g.xwd")], capture_output=True, timeout=180)
    log = read("gtkwave.log")
    if "Could not" in log or "Error" in log or not os.path.exists(os.path.join(WORK, "g.xwd")):
        fail(f"GTKWave under Xvfb:\n{log}")
    run([sys.executable, os.path.join(SRC, "tools/xwd2png.py"), "g.xwd", "g.png"])
    data = open(os.path.join(WORK, "g.xwd"), "rb").read()
    if len(set(data[-200000:])) < 8:
        fail("GTKWave's screenshot is blank")
    print(f"waveform gtkwave: screenshot {os.path.join(WORK, 'g.png')}")


os.makedirs(WORK, exist_ok=True)
{"frame": frame, "apu_run": apu_run, "gtkwave": gtkwave}[PART]()
