#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# bench.sh: run bench/dio-i2c.sh (bit-banged SMBus byte-read latency, CPU
# cost of one `sensors` run) in the VM. The one test point is that the
# benchmark ran to the end; its figures are diagnostics only: benchmarks
# never assert timing.
. "$VMTEST_REPO/tests/lib/tap.sh"
tap_plan 1
log=$(mktemp)
"$VMTEST_REPO/bench/dio-i2c.sh" >"$log" 2>&1
st=$?
sed 's/^/# /' "$log"
rm -f "$log"
tap_is "bench/dio-i2c.sh ran to the end (exit status)" "$st" 0
tap_finish
exit $?
