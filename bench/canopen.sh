#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# bench/canopen.sh: CANopen master measurements on vcan against the simulated
# EPOS. Needs vcan, so it runs inside the VM: `make bench TEST=canopen`
# (tests/vm/canopen/bench.sh calls this). Prints the numbers and ratios of one
# run; there is no pass/fail on timing. Under QEMU TCG the absolute numbers are
# those of an emulated CPU: compare ratios, not rates, with real hardware.
#   expedited SDO round trips per second (target >= 3000/s)
#   RPDO -> TPDO round-trip latency percentiles (controlword -> statusword)
#   master CPU share and kernel drops while cangen floods the bus
set -uo pipefail
BUILD=${VMTEST_BUILD:-$(cd "$(dirname "$0")/.." && pwd)/build}
BIN=$BUILD/userland/canopen
IF=${CANOPEN_BENCH_IF:-vcan0}
FLOOD_FRAMES=${CANOPEN_BENCH_FLOOD_FRAMES:-200000}
OUT=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null; wait 2>/dev/null; rm -rf "$OUT"' EXIT

# The simulator and the master share one CPU for the round-trip numbers: a
# wake-up across CPUs costs up to a timer tick under TCG, which would measure
# QEMU, not the stack. The flood runs unpinned (cangen gets its own CPU).
PIN=()
command -v taskset >/dev/null && PIN=(taskset -c 0)

ip link show "$IF" >/dev/null 2>&1 || { echo "bench/canopen.sh: no $IF (modprobe vcan; ip link add dev $IF type vcan)" >&2; exit 1; }

"${PIN[@]}" "$BIN/advee-canopen-sim-drive" -i "$IF" -n 1 -p epos >"$OUT/sim.log" 2>&1 &
for _ in $(seq 100); do grep -q "ready on" "$OUT/sim.log" && break; sleep 0.1; done

echo "# pinned: ${PIN[*]:-no}"
echo "== the engine alone: master + simulated drive in one process, virtual bus, 2 s"
"${PIN[@]}" "$BIN/canopen-bench" -n 1 -d 2 engine | tee "$OUT/engine"
echo "== expedited SDO upload 0x6041, back to back, 3 s"
"${PIN[@]}" "$BIN/canopen-bench" -i "$IF" -n 1 -d 3 sdo | tee "$OUT/sdo"
echo "== RPDO1 controlword -> TxPDO1 statusword, 1000 samples"
"${PIN[@]}" "$BIN/canopen-bench" -i "$IF" -n 1 -c 1000 pdo | tee "$OUT/pdo"
kill %1 2>/dev/null
wait 2>/dev/null

echo "== cangen flood: $FLOOD_FRAMES frames at the maximum rate (-g 0, poll on ENOBUFS)"
"$BIN/canopen-bench" -i "$IF" -d 30 flood >"$OUT/flood" &
BENCH=$!
for _ in $(seq 100); do grep -q ready "$OUT/flood" && break; sleep 0.1; done
start=$(date +%s.%N)
cangen "$IF" -g 0 -p 10 -n "$FLOOD_FRAMES"
end=$(date +%s.%N)
sleep 0.5
kill -INT "$BENCH" 2>/dev/null
wait "$BENCH"
grep -v ready "$OUT/flood"

v() { awk -v k="$1" '$1 == k { print $2 }' "$OUT"/*; }
echo "== ratios (one run)"
awk -v r="$(v sdo_round_trips_per_s)" -v e="$(v engine_sdo_round_trips_per_s)" \
	'BEGIN { printf "sdo_rate_over_target_3000 %.2f\nsdo_rate_over_engine_rate %.4f\n", r / 3000, r / e }'
awk -v p50="$(v pdo_rtt_us_p50)" -v p99="$(v pdo_rtt_us_p99)" 'BEGIN { if (p50 > 0) printf "pdo_p99_over_p50 %.2f\n", p99 / p50 }'
awk -v got="$(v flood_frames_received)" -v sent="$FLOOD_FRAMES" -v s="$start" -v e="$end" \
	'BEGIN { printf "flood_frames_sent %d\nflood_frames_missed_by_master %d\nflood_rate_frames_per_s %.0f\n", sent, sent - got, sent / (e - s) }'
