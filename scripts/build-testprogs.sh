#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# build-testprogs.sh TARGET: compile the single-file C test programs of the VM
# suites (tests/vm/<suite>/*.c) into build/tests/TARGET/<suite>/<name>.
# x86_64 builds every suite (the guest runs them in the host's root file
# system); armhf builds the suites marked portable=1, statically linked for the
# busybox initramfs of the ARM lane.
set -euo pipefail
. "$(dirname "$0")/lib.sh"

target=${1:?target (x86_64|armhf)}
cc=${CC_FOR_TESTS:-$(cross_prefix "$target")gcc}
cflags=(-O2 -g -Wall -Wextra -Werror -I"$TOP/tests/lib" -I"$TOP/kernel/include/uapi" -pthread)
[ "$target" = x86_64 ] || cflags+=(-static)

out=$BUILD/tests/$target
mkdir -p "$out"
n=0
for suite_dir in "$TOP"/tests/vm/*/; do
	suite=$(basename "$suite_dir")
	if [ "$target" != x86_64 ] && ! grep -qx 'portable=1' "$suite_dir/settings" 2>/dev/null; then
		continue
	fi
	for src in "$suite_dir"*.c; do
		[ -e "$src" ] || continue
		bin=$out/$suite/$(basename "$src" .c)
		mkdir -p "$out/$suite"
		# Rebuild when the program or any header it can include is newer.
		if [ ! -e "$bin" ] || [ "$src" -nt "$bin" ] ||
		   [ -n "$(find "$TOP/tests/lib" "$suite_dir" "$TOP/kernel/include/uapi" -name '*.h' \
			-newer "$bin" -print -quit 2>/dev/null)" ]; then
			"$cc" "${cflags[@]}" -o "$bin" "$src" || die "cannot build test program $src for $target"
		fi
		n=$((n + 1))
	done
done
say "$n VM test program(s) for $target in $out"
