#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Frames through the whole stack: SocketCAN -> sja1000 core -> ts-can1 ->
# simulated PC/104 window -> SJA1000 model and back through its interrupt.
# With "loopback on" the chip receives its own frame (self reception), so
# candump sees it arrive on the RX path; with loopback off only the local
# echo returns. The bit timing the core computes for 1 Mbit/s must fit the
# card's 8 MHz CAN clock.
. "$(dirname "$0")/lib.sh"
tap_require_module ts-can1
CAND=
trap '[ -n "$CAND" ] && kill "$CAND" 2>/dev/null; cleanup_all' EXIT

tap_plan 13
card_load || { tap_diag "cannot load ts-can1-sim + ts-can1"; exit 1; }
IF=$(can_iface)
[ -n "$IF" ] || { tap_diag "no CAN interface"; exit 1; }
OUT=$VMTEST_SCRATCH/candump.txt

# stat DIR FIELD: interface statistics
stat() { cat "/sys/class/net/$IF/statistics/${1}_$2"; }

tap_ok "bitrate 1000000, loopback on" ip link set "$IF" type can bitrate 1000000 loopback on
tap_ok "interface up" ip link set "$IF" up
# 8 MHz / 1 Mbit/s = 8 quanta: brp 1, tseg1 5, tseg2 2 (sample point 75 %).
tap_is "BTR0/BTR1 for 1 Mbit/s at 8 MHz" "$(sim_field btr0) $(sim_field btr1)" "0x00 0x14"
tap_is "SJA1000 in operating mode" "$(sim_field mod)" 0x00

candump -L -n 4 "$IF" >"$OUT" 2>&1 &
CAND=$!
candump_ready "$CAND" || tap_diag "candump did not open its socket"
rx0=$(stat rx packets)
cansend "$IF" 123#DEADBEEF
cansend "$IF" 12345678#0011223344556677
wait_lines "$OUT" . 4 20
wait "$CAND" 2>/dev/null
CAND=
tap_diag "candump: $(tr '\n' ' ' <"$OUT")"
tap_is "standard frame seen twice (echo + self reception)" "$(grep -c " $IF 123#DEADBEEF$" "$OUT")" 2
tap_is "extended frame seen twice" "$(grep -c " $IF 12345678#0011223344556677$" "$OUT")" 2
tap_is "two frames received by the chip (rx_packets)" "$(($(stat rx packets) - rx0))" 2
tap_ok "tx_packets counts them" test "$(stat tx packets)" -ge 2
tap_is "model: 2 frames sent, 2 self-received, none left in the FIFO" \
	"$(sim_field tx) $(sim_field self) $(sim_field pending)" "2 2 0"

# A burst: every frame must come back (TX queue stopped/woken per frame).
rx0=$(stat rx packets)
for i in $(seq 0 99); do
	cansend "$IF" "$(printf '%03X' "$i")#$(printf '%02X' "$i")" || break
done
rx_since() { [ "$(($(stat rx packets) - rx0))" -ge "$1" ]; }
wait_until 20 rx_since 100
tap_is "burst of 100 frames all self-received" "$(($(stat rx packets) - rx0))" 100

# Loopback off: the frame leaves (the virtual second node acks it), nothing
# comes back through the chip, candump sees the local echo only.
ip link set "$IF" down
ip link set "$IF" type can loopback off
ip link set "$IF" up
rx0=$(stat rx packets)
candump -L -n 1 "$IF" >"$OUT" 2>&1 &
CAND=$!
candump_ready "$CAND" || tap_diag "candump did not open its socket"
cansend "$IF" 7FF#CAFE
wait_until 20 test -s "$OUT"
kill "$CAND" 2>/dev/null; wait "$CAND" 2>/dev/null; CAND=
tap_ok "loopback off: local echo of 7FF#CAFE" grep -q " $IF 7FF#CAFE$" "$OUT"
tap_is "loopback off: no self reception" "$(($(stat rx packets) - rx0))" 0
ip link set "$IF" down
tap_is "down: SJA1000 back in reset mode" "$(sim_field mod)" 0x01
tap_finish
