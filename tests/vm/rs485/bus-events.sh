#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# The library's event path over the real stack (rs485-bus-events, its own
# TAP): PSC1 PAUSE and POWER callbacks while another thread polls the same
# node, the subscription's on_closed after a detach by another process
# (ENOTCONN) and after a hangup (EIO), Bus destruction within 1 s, re-attach.
. "$(dirname "$0")/common.inc"

rs485_setup "$SIMBIN/advee-rs485-sim" "$LIBBIN/rs485-bus-events"
if ! start_sim "$SUITE/stack.yaml"; then
	echo "Bail out! advee-rs485-sim did not start"
	sed 's/^/# /' "$SCR/sim.err"
	exit 1
fi
# The program prints the plan and the points; its exit status is the verdict.
"$LIBBIN/rs485-bus-events" "$SIMBIN/advee-rs485-sim" "$CTL" /dev/ttyTSU2 0x01
