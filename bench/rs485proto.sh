#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# bench/rs485proto.sh: back-to-back RS-485 transactions on the simulated bus
# (115200 Bd, slave turnaround 200 us), through n_rs485 and through the
# seed's user-space design over N_TTY, in one run. Needs the project's
# modules, so it runs inside the VM: `make bench TEST=rs485proto`
# (tests/vm/rs485proto/bench.sh calls this). Prints, for each design, the
# rate as a fraction of the wire limit (target >= 0.97), latency percentiles,
# and the ratio of the two rates; never a pass/fail on timing.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

gcc -O2 -Wall -Wextra -Werror -I"$here/../tests/vm/rs485proto" -I"$here/../tests/lib" \
	-I"$here/../kernel/include/uapi" -pthread \
	-o "$out/rs485proto-xact" "$here/rs485proto-xact.c"
"$out/rs485proto-xact"
