#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# advee-rs485ctl against advee-rs485-sim: a scan of each bus finds exactly the simulated
# boards with their firmware versions (stack.yaml), a raw instruction gets
# the board's answer, an unknown one the UNKINSTR outcome.
. "$(dirname "$0")/common.inc"

CTLBIN=$LIBBIN/advee-rs485ctl
rs485_setup "$SIMBIN/advee-rs485-sim" "$CTLBIN"
tap_plan 6
if ! start_sim "$SUITE/stack.yaml"; then
	echo "Bail out! advee-rs485-sim did not start"
	sed 's/^/# /' "$SCR/sim.err"
	exit 1
fi

# The three buses are independent: scan them at once (255 addresses each).
# Retries are 0 in a scan, so the timeout must cover the worst round trip
# under TCG (calls of several hundred ms were seen in the soak): 200 ms,
# about 51 s per bus.
for bus in 0 1 2; do
	"$CTLBIN" -b /dev/ttyTSU$bus scan --timeout 200ms >"$SCR/scan$bus.out" 2>"$SCR/scan$bus.err" &
	pids[$bus]=$!
done
for bus in 0 1 2; do
	wait "${pids[$bus]}"
	rcs[$bus]=$?
done
found() {	# found BUS: "0x10=1.2 ..." from the scan's text output
	sed -n 's/^\(0x[0-9a-f][0-9a-f]\): firmware \([0-9.]*\)$/\1=\2/p' "$SCR/scan$1.out" | sort | tr '\n' ' '
}
for bus in 0 1 2; do
	[ "${rcs[$bus]}" = 0 ] || sed 's/^/# /' "$SCR/scan$bus.err"
done
tap_is "scan of bus a: exactly sd1@0x10, sd1@0x11, so1@0x20 (exit ${rcs[0]})" "$(found 0)" "0x10=1.2 0x11=1.3 0x20=2.0 "
tap_is "scan of bus b: exactly sbs1@0x30 (exit ${rcs[1]})" "$(found 1)" "0x30=3.1 "
tap_is "scan of the power link: exactly psc1@0x01 (exit ${rcs[2]})" "$(found 2)" "0x01=4.0 "
# Nothing else answered in any form (BADCRC, UNKINSTR, ...): every report line is a firmware line.
tap_is "no address answered anything but a firmware version" \
	"$(cat "$SCR"/scan?.out | grep -c '^0x[0-9a-f]*: ' )" "5"

sim set a:so1@0x20 ticks 258 -3 >/dev/null
out=$("$CTLBIN" -b /dev/ttyTSU0 xfer 0x20 0x01 02 --timeout 200ms 2>&1); rc=$?
sed "s/^/# /" <<<"$out"
tap_ok "xfer GET_TICKS to so1@0x20 shows the little-endian counters 02 01 fd ff (exit $rc)" \
	bash -c '[ "$1" = 0 ] && grep -qi "02 01 fd ff" <<<"$2"' _ "$rc" "$out"
out=$("$CTLBIN" -b /dev/ttyTSU0 xfer 0x10 0x77 --timeout 200ms 2>&1); rc=$?
sed "s/^/# /" <<<"$out (exit $rc)"
tap_ok "xfer of an unknown instruction reports UNKINSTR, exit 1" \
	bash -c '[ "$1" = 1 ] && grep -q "UNKINSTR" <<<"$2"' _ "$rc" "$out"
tap_finish
