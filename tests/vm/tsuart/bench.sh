#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# bench.sh: run bench/tsuart.sh (60 s full duplex at 115200 Bd) in the VM.
# The one test point is the data check of that run (nothing altered either
# way, every character lost on receive accounted for as an overrun); the
# rates and CPU figures are printed as diagnostics only: benchmarks never
# assert timing.
. "$VMTEST_REPO/tests/lib/tap.sh"
tap_plan 1
log=$(mktemp)
"$VMTEST_REPO/bench/tsuart.sh" >"$log" 2>&1
st=$?
sed 's/^/# /' "$log"
rm -f "$log"
tap_is "60 s full duplex at 115200 Bd: nothing altered, every loss an overrun (exit status)" "$st" 0
tap_finish
exit $?
