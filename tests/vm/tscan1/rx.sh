#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Frames from another node on the bus (injected into the simulated SJA1000)
# reach candump with identifier, format and data intact; more frames than
# the chip's receive FIFO holds are reported as an overrun, not lost
# silently; a chip in reset mode (interface down) receives nothing.
. "$(dirname "$0")/lib.sh"
tap_require_module ts-can1
CAND=
trap '[ -n "$CAND" ] && kill "$CAND" 2>/dev/null; cleanup_all' EXIT

INJECT=/sys/kernel/debug/ts-can1-sim/inject
tap_plan 10
card_load || { tap_diag "cannot load ts-can1-sim + ts-can1"; exit 1; }
IF=$(can_iface)
[ -n "$IF" ] || { tap_diag "no CAN interface"; exit 1; }
OUT=$VMTEST_SCRATCH/candump-rx.txt
stat() { cat "/sys/class/net/$IF/statistics/$1"; }

tap_ok "interface down: the chip in reset mode refuses frames" \
	sh -c "! echo '123 01' >$INJECT 2>/dev/null"
ip link set "$IF" type can bitrate 500000
ip link set "$IF" up

# dump: wait for candump (it exits after its -n frames; the timeout of 60 s
# only ends a candump that would otherwise wait forever)
dump() {
	wait "$CAND" 2>/dev/null; CAND=
	tap_diag "candump: $(tr '\n' ' ' <"$OUT")"
}

timeout 60 candump -L -n 3 "$IF" >"$OUT" 2>&1 &
CAND=$!
candump_ready "$CAND" || tap_diag "candump did not open its socket"
rx0=$(stat rx_packets)
echo "123 deadbeef" >"$INJECT"
echo "1abcdef0 0102" >"$INJECT"
echo "7ff -" >"$INJECT"
dump
tap_ok "standard frame 123#DEADBEEF received" grep -q " $IF 123#DEADBEEF$" "$OUT"
tap_ok "extended frame 1ABCDEF0#0102 received" grep -q " $IF 1ABCDEF0#0102$" "$OUT"
tap_ok "zero-length frame 7FF# received" grep -q " $IF 7FF#$" "$OUT"
tap_is "rx_packets +3" "$(($(stat rx_packets) - rx0))" 3
tap_is "nothing transmitted" "$(stat tx_packets)" 0

# Six frames at once into a four-frame FIFO; ",#ffffffff" adds error frames.
timeout 60 candump -L -n 5 "$IF,0:0,#ffffffff" >"$OUT" 2>&1 &
CAND=$!
candump_ready "$CAND" || tap_diag "candump did not open its socket"
rx0=$(stat rx_packets)
over0=$(stat rx_over_errors)
echo "100 aa 6" >"$INJECT"
dump
tap_is "overrun: the four frames the FIFO held are delivered" "$(($(stat rx_packets) - rx0))" 4
tap_is "overrun: rx_over_errors +1" "$(($(stat rx_over_errors) - over0))" 1
tap_ok "overrun: candump shows the controller's RX overflow error frame" \
	grep -Eq " $IF 20000[0-9A-F]04#0001" "$OUT"
tap_is "model: two frames did not fit" "$(sim_field overruns)" 2
tap_finish
