#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# bench/rs485proto.sh: back-to-back RS-485 transactions on the simulated bus
# (115200 Bd, slave turnaround 200 us), through n_rs485's addressing path
# (ADDRB), its mark/space path and the seed's user-space design over N_TTY,
# in one run. Needs the project's modules, so it runs inside the VM:
# `make bench TEST=rs485proto` (tests/vm/rs485proto/bench.sh calls this).
# Prints one table row per design (rate, fraction of the wire limit, idle
# line split, termios switches and drains per frame, guest CPU, latency
# percentiles) and the ratios of the rates; never a pass/fail on timing.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

gcc -O2 -Wall -Wextra -Werror -I"$here/../tests/vm/rs485proto" -I"$here/../tests/lib" \
	-I"$here/../kernel/include/uapi" -pthread \
	-o "$out/rs485proto-xact" "$here/rs485proto-xact.c"
"$out/rs485proto-xact"
