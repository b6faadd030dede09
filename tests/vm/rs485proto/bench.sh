#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# bench.sh: run bench/rs485proto.sh in the VM (make bench TEST=rs485proto).
# The benchmark's own TAP points check that every transaction got its own
# answer; its rates and latencies are diagnostics only (benchmarks never
# assert timing).
exec "$VMTEST_REPO/bench/rs485proto.sh"
