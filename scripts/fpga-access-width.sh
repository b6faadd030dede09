#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# fpga-access-width.sh [FILE...]: one access width on the TS-7800's FPGA
# window (issue 18 item 12, docs/tsuart.md "Access width"). The window is
# reached only through the 16-bit regmap of ts7800-fpga: a 32-bit access at a
# port's STAT also reads DATA and pops a character. The only MMIO accessors
# allowed in the FPGA drivers are those on the SoC's own doorbell registers
# (32-bit). Prints each other accessor call as FILE:LINE: TEXT and exits 1
# if there is one. Default files: tsuart-fix/*.c.
set -uo pipefail
TOP=$(cd "$(dirname "$0")/.." && pwd)
[ $# -gt 0 ] || set -- "$TOP"/tsuart-fix/*.c

accessor='\b(__raw_)?(read|write)[bwlq](_relaxed)?[[:space:]]*\(|\bio(read|write)(8|16|32)(be)?[[:space:]]*\('
if grep -nHE "$accessor" "$@" | grep -vE 'doorbell[[:space:]]*\+'; then
	echo "fpga-access-width: MMIO accessors outside the FPGA regmap (above): use the regmap's 16-bit registers" >&2
	exit 1
fi
exit 0
