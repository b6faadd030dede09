#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# vm-debug.sh - the debug-kernel VM lane: every VM test under KASAN, lockdep,
# kmemleak, UBSAN, KFENCE, DEBUG_OBJECTS and PREEMPT, with gpio-sim available.
#
# Builds (or reuses from its cache) the debug kernel (scripts/debug-kernel.sh),
# builds the project's modules against its tree (build/kmod/debug/) and the VM
# test programs, then runs tests/harness/vm-x86.sh on it as lane "debug"
# (results in build/vm/debug/, rows in build/results/debug.tsv).
#
# usage: vm-debug.sh [vm-x86.sh options: --test SUITE[/PROGRAM], --shell, --run PROG]
# Exit status: 0 when every test passed, 1 otherwise (also when the debug
# kernel or the modules cannot be built: that is a failure, never a skip).
set -euo pipefail
TOP=$(cd "$(dirname "$0")/../.." && pwd)
. "$TOP/scripts/lib.sh"

entry=$("$TOP/scripts/debug-kernel.sh") ||
	die "debug lane: the debug kernel could not be built (see the messages above)"
kver=$(cat "$entry/kver")
"$TOP/scripts/build-kmod.sh" debug "$entry/build" ||
	die "debug lane: the project's modules do not build against the debug kernel $kver"
"$TOP/scripts/build-testprogs.sh" x86_64 ||
	die "debug lane: the VM test programs do not build"
# KASAN, lockdep and kmemleak under TCG make everything about SLOWDOWN times
# slower: scale the program timeouts and the boot allowance. Kernel parameters:
# pci=noacpi because the instrumented ACPI interpreter needs over 30 s per
# PCI routing query (AE_AML_LOOP_TIMEOUT) and virtio uses MSI-X anyway;
# kasan_multi_shot so that every KASAN report of a run is printed, not the first.
export VMTEST_SLOWDOWN=${VMTEST_SLOWDOWN:-4}
export VMTEST_APPEND="pci=noacpi kasan_multi_shot${VMTEST_APPEND:+ $VMTEST_APPEND}"
exec "$TOP/tests/harness/vm-x86.sh" --kernel "$entry/bzImage" --kver "$kver" \
	--modroot "$entry/modroot" --modules "$BUILD/kmod/debug/modules.list" --lane debug "$@"
