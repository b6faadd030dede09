#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Each driver of the rs485 library against its simulated board over the real
# stack: readings in metres/radians/amperes, timeouts, RESEND after a bad CRC
# (executed once), UNKINSTR, slow answers, PSC1 events while a transaction
# with the same node is pending, broadcast RESET. The assertions are in
# userland/rs485sim/vmtest/rs485_stack_test.cpp (TAP on stdout).
. "$(dirname "$0")/common.inc"

rs485_setup "$SIMBIN/advee-rs485-sim" "$SIMBIN/rs485-stack-test"
if ! start_sim "$SUITE/stack.yaml" -v; then
	echo "Bail out! advee-rs485-sim did not start"
	sed 's/^/# /' "$SCR/sim.err"
	exit 1
fi
"$SIMBIN/rs485-stack-test" "$CTL" /dev/ttyTSU0 /dev/ttyTSU1 /dev/ttyTSU2 "$TIMEOUT_MS"
rc=$?
if [ $rc -ne 0 ]; then
	echo "# last lines of the simulator's log:"
	tail -40 "$SCR/sim.err" | sed 's/^/#   /'
fi
exit $rc
