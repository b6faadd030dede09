#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# compat32 - the outcome test (xfer.c) built as a 32-bit i386 program and run
# on the 64-bit kernel: the ioctl structures must have the same layout and the
# discipline's compat_ioctl path must give the same results.
. "$VMTEST_REPO/tests/lib/tap.sh"

src=$VMTEST_REPO/tests/vm/rs485proto/xfer.c
bin=$VMTEST_SCRATCH/xfer32
if ! echo 'int main(void) { return 0; }' |
	gcc -m32 -x c - -o "$VMTEST_SCRATCH/probe32" 2>/dev/null; then
	printf 'TAP version 13\n1..0 # SKIP no 32-bit toolchain (gcc-multilib) on this machine\n'
	exit 4
fi
if ! "$VMTEST_SCRATCH/probe32" 2>/dev/null; then
	printf 'TAP version 13\n1..0 # SKIP this kernel runs no 32-bit programs (CONFIG_IA32_EMULATION)\n'
	exit 4
fi
tap_plan 2
# Debian's gcc-multilib brings no i386 <asm/*.h>; the x86 ones serve both
# word sizes, so they are taken from the 64-bit directory (searched last).
tap_ok "xfer.c builds as a 32-bit program" \
	gcc -m32 -idirafter /usr/include/x86_64-linux-gnu -O2 -Wall -Wextra -Werror -I"$VMTEST_REPO/tests/lib" \
	-I"$VMTEST_REPO/kernel/include/uapi" -pthread -o "$bin" "$src"
tap_ok "the 32-bit outcome test passes (compat_ioctl path)" "$bin"
tap_finish
