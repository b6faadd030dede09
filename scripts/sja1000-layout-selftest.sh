#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# sja1000-layout-selftest.sh: proves that the build-time layout check of
# ts-can1's private copy of struct sja1000_priv (ts7800-can/sja1000-layout.c)
# catches a difference: compiles it once against Debian's amd64 headers with
# the copy's members ocr and cdr swapped and succeeds only if that build fails
# with the check's message. Used by scripts/kernel-gates.sh.
set -euo pipefail
. "$(dirname "$0")/lib.sh"

kdir=/usr/src/linux-headers-$("$TOP/scripts/kver.sh")
src=$("$TOP/scripts/kernel-source.sh" drivers/net/can/sja1000/sja1000.h)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/ts7800-can"
cp "$TOP"/ts7800-can/{Kbuild,sja1000-core.h,sja1000-layout.c} "$tmp/ts7800-can/"
echo 'obj-y += ts7800-can/' >"$tmp/Kbuild"
# Swap two members of the copy: same size, other offsets.
sed -i 's/^\tu8 ocr;/\tu8 @@;/; s/^\tu8 cdr;/\tu8 ocr;/; s/^\tu8 @@;/\tu8 cdr;/' \
	"$tmp/ts7800-can/sja1000-core.h"
grep -q $'^\tu8 cdr;' "$tmp/ts7800-can/sja1000-core.h" || die "cannot alter the copy"
if out=$(LC_ALL=C make -C "$kdir" M="$tmp" W=1 SJA1000_SRC="$src" ts7800-can/sja1000-layout.o 2>&1); then
	die "a struct sja1000_priv copy with ocr and cdr swapped still builds"
fi
if ! grep -q 'differs from struct sja1000_priv of this kernel' <<<"$out"; then
	printf '%s\n' "$out" | tail -5 >&2
	die "the altered copy failed to build, but not by the layout check"
fi
say "the layout check rejects a struct sja1000_priv copy with ocr and cdr swapped"
