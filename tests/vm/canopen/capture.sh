#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# candump of a propulsion run: after the boot, the control loop is exactly
# RPDO4 (controlword + target velocity) out, TxPDO1/TxPDO4 in, heartbeats;
# no SDO.
# The RPDO4 frames must be exactly the expected sequence.
. "$(dirname "$0")/common.inc"
canopen_setup
tap_plan 6

start_sim epos -n 1 -p epos || exit 1
start_candump
"$BIN/canopen-scenario" -i "$IF" capture >"$SCR/scenario.log" 2>&1
rc=$?
stop_candump
tap_is "scenario exit status" "$rc" 0
[ "$rc" -eq 0 ] || sed 's/^/# /' "$SCR/scenario.log"

# The control window: first RPDO4 frame up to the final NMT pre-operational.
awk '/^501#/ { on = 1 } on { print } /^000#8001$/ { if (on) exit }' "$SCR/frames" >"$SCR/window"
tap_ok "window ends with NMT enter pre-operational" grep -qx "000#8001" "$SCR/window"
tap_is "no SDO in the control loop" "$(grep -cE '^(58|60)[0-9A-F]#' "$SCR/window")" 0
# TxPDO1 (0x181, statusword) is valid in the EPOS defaults and stays on.
tap_is "only RPDO4, TxPDO1/4, heartbeats and the final NMT in the loop" \
	"$(grep -vE '^(501#|181#|481#|701#|77F#|000#8001$)' "$SCR/window" | head -3)" ""
tap_is "every TxPDO4 is statusword + velocity (6 bytes)" \
	"$(grep '^481#' "$SCR/window" | grep -cvE '^481#[0-9A-F]{12}$')" 0

# Expected RPDO4: shutdown, switch on, enable, 20 speeds of 0.01*i m/s
# (rpm = v / (2 pi 0.1 m) * 60 * 26), quick stop keeping the last target.
awk 'function le32(x) { if (x < 0) x += 4294967296
	return sprintf("%02X%02X%02X%02X", x % 256, int(x / 256) % 256, int(x / 65536) % 256, int(x / 16777216) % 256) }
BEGIN {
	print "501#060000000000"; print "501#070000000000"; print "501#0F0000000000"
	for (i = 1; i <= 20; i++) { rpm = int(0.01 * i / (2 * 3.14159265358979 * 0.1) * 60 * 26 + 0.5); print "501#0F00" le32(rpm) }
	print "501#0200" le32(rpm)
}' >"$SCR/expected"
grep '^501#' "$SCR/window" >"$SCR/rpdo4"
tap_ok "RPDO4 frames are exactly the expected sequence" diff -u "$SCR/expected" "$SCR/rpdo4"

tap_finish
