#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# bench/tsuart.sh: TS-UART full-duplex throughput on the simulated FPGA. Needs
# the project's modules, so it runs inside the VM: `make bench TEST=tsuart`
# (tests/vm/tsuart/bench.sh calls this). Prints the ratios of one run (no
# pass/fail on timing): achieved character rate / line limit each way (target
# >= 0.99) and guest CPU per 1000 characters, for a 60 s run at 115200 Bd.
#   TSUART_BENCH_SECONDS  run length (default 60)
#   TSUART_BENCH_FLAGS    extra flags for tsuart-fullduplex (e.g. -8 for 8-bit)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"; modprobe -r ts7800_sim 2>/dev/null; modprobe -r ts_uart ts7800_fpga 2>/dev/null || true' EXIT

gcc -O2 -Wall -Wextra -Werror -I"$here/../kernel/include/uapi" -pthread \
	-o "$out/tsuart-fullduplex" "$here/tsuart-fullduplex.c"
modprobe ts_uart
modprobe ts7800_sim
for _ in $(seq 300); do [ -e /dev/ttyTSU0 ] && [ -e /dev/ts7800-sim/uart0 ] && break; sleep 0.01; done
# shellcheck disable=SC2086
"$out/tsuart-fullduplex" -d "${TSUART_BENCH_SECONDS:-60}" ${TSUART_BENCH_FLAGS:-}
