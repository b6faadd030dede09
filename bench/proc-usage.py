#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0
"""proc-usage.py: memory and CPU of running processes over one window.

    proc-usage.py [--window S] [--guest] [--baseline PID] NAME=PID...

Reads /proc/PID/stat (utime + stime) at the start and the end of the window
and /proc/PID/status (VmRSS, VmHWM) + /proc/PID/smaps_rollup (Pss, private
pages) every SAMPLE_S during it, then prints one row per process, the total,
and each against the targets of issue 9 (8 MB of memory for the whole
stack, 2 % of one core). Memory columns are the largest value sampled in the
window. The target is judged on Pss: VmRSS counts every shared library page
once per process that maps it (libc, libstdc++, liblcm and glib are in every
module), so the sum of VmRSS counts them five or six times; Pss divides a
shared page among the processes that map it, so the sum of Pss is the
memory the stack really occupies (what the sum of USS, the private pages, is
the lower bound of, and the sum of VmRSS the upper bound). AnonHuge is the
anonymous memory in transparent huge pages (2 MB each on x86_64; already in
the other columns). growth: the judged Pss at the last sample minus at the
first (a module still growing in the window is not at its steady state).

--guest: the processes are qemu-user (qemu-arm) running ARM programs. The
ARM program's memory is then the part of qemu's address space that holds the
guest's 4 GiB address space (qemu reserves it in one piece at start-up; its
own code, heap and translation buffer lie outside): "guest Rss/Pss" sum the
smaps entries inside that window, which is what the ARM process's own Rss/Pss
would be (same 4 KiB pages, same files mapped). qemu's VmRSS is shown too,
and, with --baseline PID (an idle qemu-arm running a program that only
pause()s), qemu's VmRSS minus that idle emulator's. CPU is the host (here:
the VM's) CPU time of the emulator, emulation included.

Prints "gone NAME" for a process that ended or was replaced during the
window (its row is then left out), "pss_total_kb N", "cpu_total_pct X".
"""
import argparse
import os
import sys
import time

SAMPLE_S = 5.0
RSS_TARGET_KB = 8 * 1024
CPU_TARGET_PCT = 2.0
GUEST_SPACE = 1 << 32  # a 32-bit guest's address space


def read_stat(pid):
    """(utime, stime, start time) of PID in clock ticks."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    # fields[0] is field 3 (state): utime = 14, stime = 15, starttime = 22
    return int(fields[11]), int(fields[12]), int(fields[19])


def read_kv(path):
    out = {}
    with open(path) as f:
        for line in f:
            k, _, v = line.partition(":")
            v = v.split()
            if v and v[0].isdigit():
                out[k] = int(v[0])
    return out


def guest_usage(pid):
    """(Rss, Pss, USS) in kB of the smaps entries inside the guest's address space.

    qemu-user reserves the guest's whole address space as its first (lowest)
    mapping; every guest mapping is carved out of it. None if the layout is
    not that (no file mapping inside the window).
    """
    rss = pss = uss = 0
    lo = None
    inside = False
    files_inside = 0
    with open(f"/proc/{pid}/smaps") as f:
        for line in f:
            head = line.split()
            if "-" in head[0] and len(head) >= 5 and not head[0].endswith(":"):
                start, end = (int(x, 16) for x in head[0].split("-"))
                if lo is None:
                    lo = start
                inside = end <= lo + GUEST_SPACE
                if inside and len(head) >= 6 and head[5].startswith("/"):
                    files_inside += 1
            elif inside and head[0] == "Rss:":
                rss += int(head[1])
            elif inside and head[0] == "Pss:":
                pss += int(head[1])
            elif inside and head[0] in ("Private_Clean:", "Private_Dirty:"):
                uss += int(head[1])
    return (rss, pss, uss) if files_inside else None


def breakdown(name, pid, guest, top):
    """Pss of PID grouped by what is mapped: file name, [heap], [stack],
    anonymous (thread stacks, malloc arenas, LCM buffers); the guest's
    mappings only with guest."""
    groups = {}
    huge = []  # (mapping size, AnonHugePages) of anonymous mappings holding huge pages
    lo = None
    key = None
    size = 0
    with open(f"/proc/{pid}/smaps") as f:
        for line in f:
            head = line.split()
            if "-" in head[0] and len(head) >= 5 and not head[0].endswith(":"):
                start, end = (int(x, 16) for x in head[0].split("-"))
                lo = start if lo is None else lo
                key = None
                size = (end - start) // 1024
                if not guest or end <= lo + GUEST_SPACE:
                    key = os.path.basename(head[5]) if len(head) >= 6 else "[anonymous]"
            elif key and head[0] == "Pss:":
                groups[key] = groups.get(key, 0) + int(head[1])
            elif key and head[0] == "AnonHugePages:" and int(head[1]):
                huge.append((size, int(head[1])))
    best = sorted(groups.items(), key=lambda kv: -kv[1])[:top]
    print(f"pss of {name}: " + ", ".join(f"{k} {v}" for k, v in best) + f" (kB; all {sum(groups.values())})")
    for size, kb in huge:
        print(f"huge pages of {name}: {kb} kB in an anonymous mapping of {size} kB")


def sample_memory(pid, guest):
    st = read_kv(f"/proc/{pid}/status")
    roll = read_kv(f"/proc/{pid}/smaps_rollup")
    m = {
        "rss": st.get("VmRSS", 0),
        "hwm": st.get("VmHWM", 0),
        "pss": roll.get("Pss", 0),
        "uss": roll.get("Private_Clean", 0) + roll.get("Private_Dirty", 0),
        "thp": roll.get("AnonHugePages", 0),
    }
    if guest:
        g = guest_usage(pid)
        m["grss"], m["gpss"], m["guss"] = g if g else (-1, -1, -1)
    return m


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--window", type=float, default=30.0, help="seconds (default 30)")
    ap.add_argument("--guest", action="store_true", help="qemu-user processes: guest memory too")
    ap.add_argument("--baseline", type=int, help="pid of an idle qemu-arm (with --guest)")
    ap.add_argument("--breakdown", type=int, default=0, metavar="N",
                    help="per process, the N mappings (grouped by file) with the most Pss")
    ap.add_argument("procs", nargs="+", metavar="NAME=PID")
    a = ap.parse_args()
    procs = [(n, int(p)) for n, p in (x.split("=", 1) for x in a.procs)]
    hz = os.sysconf("SC_CLK_TCK")

    start, mem, first, last, gone = {}, {}, {}, {}, set()
    t0 = time.monotonic()
    for name, pid in procs:
        try:
            start[name] = read_stat(pid)
        except OSError:
            gone.add(name)
    while True:
        for name, pid in procs:
            if name in gone:
                continue
            try:
                s = sample_memory(pid, a.guest)
            except OSError:
                gone.add(name)
                continue
            first.setdefault(name, s)
            last[name] = s
            old = mem.setdefault(name, dict(s))
            for k, v in s.items():
                old[k] = max(old[k], v)
        left = a.window - (time.monotonic() - t0)
        if left <= 0:
            break
        time.sleep(min(SAMPLE_S, left))
    t1 = time.monotonic()
    cpu = {}
    for name, pid in procs:
        if name in gone:
            continue
        try:
            utime, stime, started = read_stat(pid)
        except OSError:
            gone.add(name)
            continue
        if started != start[name][2]:
            gone.add(name)
            continue
        cpu[name] = ((utime - start[name][0]) / hz, (stime - start[name][1]) / hz)
    base = sample_memory(a.baseline, True) if a.baseline else None

    wall = t1 - t0
    mb = lambda kb: kb / 1024.0
    print(f"window {wall:.1f} s, CLK_TCK {hz}, memory in kB: the largest of samples every {SAMPLE_S:.0f} s; "
          f"ratios: {'guest ' if a.guest else ''}Pss / 8 MB, CPU (user + system) / 2 % of one core")
    if a.guest:
        mem_cols = [("qemu_VmRSS", "rss"), ("-idle_qemu", "extra"), ("guest_Rss", "grss"), ("guest_Pss", "gpss"),
                    ("guest_USS", "guss")]
        judged_key = "gpss"
    else:
        mem_cols = [("VmRSS", "rss"), ("VmHWM", "hwm"), ("Pss", "pss"), ("USS", "uss"), ("AnonHuge", "thp")]
        judged_key = "pss"
    cols = [("module", 15), ("pid", 6)] + [(c, max(7, len(c))) for c, _ in mem_cols] + \
        [("growth", 6), ("user_s", 6), ("sys_s", 6), ("CPU_%", 6), ("mem/8MB", 7), ("CPU/2%", 6)]
    line = lambda vals: " ".join(f"{v:<{w}}" if i == 0 else f"{v:>{w}}" for i, ((_, w), v) in enumerate(zip(cols, vals)))
    print(line([c for c, _ in cols]))
    tot = {k: 0 for _, k in mem_cols}
    tot_u = tot_s = 0.0
    tot_g = 0
    for name, pid in procs:
        if name in gone:
            print(f"gone {name}")
            continue
        m = dict(mem[name])
        m["extra"] = m["rss"] - base["rss"] if base else -1
        growth = last[name][judged_key] - first[name][judged_key]
        tot_g += growth
        u, st = cpu[name]
        pct = 100.0 * (u + st) / wall
        for _, k in mem_cols:
            tot[k] += m[k]
        tot_u += u
        tot_s += st
        print(line([name, pid] + [m[k] for _, k in mem_cols] +
                   [growth, f"{u:.2f}", f"{st:.2f}", f"{pct:.2f}", f"{m[judged_key] / RSS_TARGET_KB:.3f}", f"{pct / CPU_TARGET_PCT:.3f}"]))
    pct = 100.0 * (tot_u + tot_s) / wall
    judged = tot[judged_key]
    print(line(["total", ""] + [tot[k] for _, k in mem_cols] +
               [tot_g, f"{tot_u:.2f}", f"{tot_s:.2f}", f"{pct:.2f}", f"{judged / RSS_TARGET_KB:.3f}", f"{pct / CPU_TARGET_PCT:.3f}"]))
    if a.guest:
        if base:
            print(f"idle qemu-arm (a program that only pause()s): VmRSS {base['rss']} kB, guest Rss {base['grss']} kB, "
                  f"guest Pss {base['gpss']} kB, guest USS {base['guss']} kB")
        print(f"memory total (sum of guest Pss, the target's measure) {mb(judged):.2f} MB = {judged / RSS_TARGET_KB:.2f} of 8 MB")
        print(f"memory total (sum of guest Rss, shared libraries once per process) {mb(tot['grss']):.2f} MB = {tot['grss'] / RSS_TARGET_KB:.2f} of 8 MB")
        print(f"memory total (sum of guest USS, private pages only) {mb(tot['guss']):.2f} MB = {tot['guss'] / RSS_TARGET_KB:.2f} of 8 MB")
        print(f"emulator total (sum of qemu-arm VmRSS, not a measure of the ARM programs) {mb(tot['rss']):.2f} MB")
    else:
        print(f"memory total (sum of Pss, the target's measure) {mb(judged):.2f} MB = {judged / RSS_TARGET_KB:.2f} of 8 MB")
        print(f"memory total (sum of VmRSS, shared libraries once per process) {mb(tot['rss']):.2f} MB = {tot['rss'] / RSS_TARGET_KB:.2f} of 8 MB")
        print(f"memory total (sum of USS, private pages only) {mb(tot['uss']):.2f} MB = {tot['uss'] / RSS_TARGET_KB:.2f} of 8 MB")
    print(f"CPU total {pct:.2f} % of one core (user {100 * tot_u / wall:.2f}, system {100 * tot_s / wall:.2f}) = {pct / CPU_TARGET_PCT:.2f} of 2 %")
    if a.breakdown:
        for name, pid in procs:
            if name not in gone:
                breakdown(name, pid, a.guest, a.breakdown)
    print(f"pss_total_kb {judged}")
    print(f"cpu_total_pct {pct:.3f}")
    print(f"measured {len(procs) - len(gone)} of {len(procs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
