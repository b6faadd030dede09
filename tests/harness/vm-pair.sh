#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# vm-pair.sh - the two-computer test (issue 21, tests/twocomp/): two x86_64
# guests booted by vm-x86.sh side by side, joined by one Ethernet link that
# exists only between the two QEMU processes (a pair of unix datagram
# sockets in the lanes' directory: no host network, no bridge, no tap).
# Guest A (lane LANE-a) is the robot computer, tests/twocomp/robot.sh; guest B
# (lane LANE-b) the high-level computer, tests/twocomp/high-level.sh.
#
# The host does what no guest can: it takes the link down for
# TWOCOMP_LINK_DOWN_S seconds (default 3) through A's QEMU monitor
# (set_link net0 off/on) when B asks for it (B writes link-down-request in its
# results share; the host answers link-up there), and tells A to finish (stop
# in A's results share) once B is done.
#
# usage: vm-pair.sh [--lane LANE]   (default twocomp: lanes twocomp-a, twocomp-b)
# Exit status: 0 when both guests' programs passed.
set -euo pipefail
TOP=$(cd "$(dirname "$0")/../.." && pwd)
. "$TOP/scripts/lib.sh"

lane=twocomp
while [ $# -gt 0 ]; do
	case $1 in
	--lane) lane=$2; shift 2 ;;
	-h|--help) sed -n '3,19p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
	*) die "vm-pair.sh: unknown argument $1 (see --help)" ;;
	esac
done
down_s=${TWOCOMP_LINK_DOWN_S:-3}
slowdown=${VMTEST_SLOWDOWN:-1}
dir=$BUILD/vm/$lane-pair
mkdir -p "$dir"
rm -f "$dir"/*.sock "$dir"/monitor-a.* "$dir"/pair.log
res_a=$BUILD/vm/$lane-a/results res_b=$BUILD/vm/$lane-b/results
# No request or answer of an earlier run may be taken for this one's.
rm -rf "$res_a" "$res_b"
log() { echo "[pair $(date +%T.%N | cut -c1-12)] $*" | tee -a "$dir/pair.log"; }

# One link: each guest sends to the other's socket and receives on its own.
net() { echo "dgram,local.type=unix,local.path=$dir/$1.sock,remote.type=unix,remote.path=$dir/$2.sock"; }
start=$(date +%s)
"$TOP/tests/harness/vm-x86.sh" --lane "$lane-a" --run "$TOP/tests/twocomp/robot.sh" \
	--run-timeout $((600 * slowdown)) --netdev "$(net a b)" --mac 52:54:00:21:00:0a \
	--monitor "$dir/monitor-a" >"$dir/a.out" 2>&1 &
pid_a=$!
"$TOP/tests/harness/vm-x86.sh" --lane "$lane-b" --run "$TOP/tests/twocomp/high-level.sh" \
	--run-timeout $((540 * slowdown)) --netdev "$(net b a)" --mac 52:54:00:21:00:0b >"$dir/b.out" 2>&1 &
pid_b=$!
cleanup() { kill "$pid_a" "$pid_b" 2>/dev/null || true; kill "${mon_reader:-}" 2>/dev/null || true; }
trap cleanup EXIT

# The monitor's output is read all along (an unread pipe would stall QEMU).
for _ in $(seq 100); do [ -p "$dir/monitor-a.out" ] && break; sleep 0.1; done
cat "$dir/monitor-a.out" >"$dir/monitor-a.log" 2>/dev/null &
mon_reader=$!
monitor() { log "monitor A: $*"; echo "$*" >"$dir/monitor-a.in"; }

# The link drop, on B's request; then A's end, once B is done.
dropped=0
while kill -0 "$pid_b" 2>/dev/null; do
	if [ "$dropped" = 0 ] && [ -f "$res_b/link-down-request" ]; then
		monitor "set_link net0 off"
		t0=$(date +%s.%N)
		sleep "$down_s"	# the stimulus: the link is down this long
		monitor "set_link net0 on"
		t1=$(date +%s.%N)
		awk -v a="$t0" -v b="$t1" 'BEGIN { printf "down_s=%.3f\n", b - a }' >"$res_b/link-up"
		log "link down for $(cat "$res_b/link-up")"
		dropped=1
	fi
	sleep 0.2
done
wait "$pid_b" && rc_b=0 || rc_b=$?
log "B finished (exit $rc_b); telling A to finish"
[ -f "$res_b/high-level-path.txt" ] && cp "$res_b/high-level-path.txt" "$res_a/"
touch "$res_a/stop"
wait "$pid_a" && rc_a=0 || rc_a=$?
log "A finished (exit $rc_a) after $(($(date +%s) - start)) s"
sed 's/^/[A] /' "$dir/a.out"
sed 's/^/[B] /' "$dir/b.out"
[ "$rc_a" = 0 ] && [ "$rc_b" = 0 ]
