#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# vm-debug.sh - the debug-kernel VM lane: every VM test under KASAN, lockdep,
# kmemleak, UBSAN, KFENCE and DEBUG_OBJECTS, with gpio-sim available, on 6.12
# PREEMPT_RT (or 6.1 with PREEMPT: ADVEE_DEBUG_KERNEL=6.1).
#
# Builds (or reuses from its cache) the debug kernel (scripts/debug-kernel.sh),
# builds the project's modules against its tree (build/kmod/debug-SERIES/) and
# the VM test programs, then runs tests/harness/vm-x86.sh on it as lane "debug"
# (results in build/vm/debug/, rows in build/results/debug.tsv).
#
# usage: [ADVEE_DEBUG_KERNEL=6.12-rt|6.1] vm-debug.sh [vm-x86.sh options:
#        --test SUITE[/PROGRAM], --shell, --run PROG, --lane NAME]
# Exit status: 0 when every test passed (in both guests of a one-CPU lane),
# 1 otherwise (also when the debug kernel or the modules cannot be built:
# that is a failure, never a skip).
set -euo pipefail
TOP=$(cd "$(dirname "$0")/../.." && pwd)
. "$TOP/scripts/lib.sh"
. "$TOP/tests/harness/lib-host.sh"

series=${ADVEE_DEBUG_KERNEL:-6.12-rt}
entry=$("$TOP/scripts/debug-kernel.sh" "$series") ||
	die "debug lane: the debug kernel could not be built (see the messages above)"
kver=$(cat "$entry/kver")
"$TOP/scripts/build-kmod.sh" "debug-$series" "$entry/build" ||
	die "debug lane: the project's modules do not build against the debug kernel $kver"
"$TOP/scripts/build-testprogs.sh" x86_64 ||
	die "debug lane: the VM test programs do not build"
# KASAN, lockdep and kmemleak under TCG make everything about SLOWDOWN times
# slower: scale the program timeouts and the boot allowance. Kernel parameters:
# pci=noacpi because the instrumented ACPI interpreter needs over 30 s per
# PCI routing query (AE_AML_LOOP_TIMEOUT) and virtio uses MSI-X anyway;
# kasan_multi_shot so that every KASAN report of a run is printed, not the first.
# Suites whose settings say debug_lane=0 run user space over drivers that
# other suites already cover under KASAN/lockdep (CANopen on vcan, LCM
# daemons, installation files). On this 4x slower kernel they would cost
# about 12 minutes of CI and find nothing new, so a whole-lane run leaves them
# out, visibly: one skipped row each in build/results/debug-skipped.tsv.
# --test (or --shell/--run) runs exactly what is asked.
explicit=0
for a in "$@"; do
	case $a in --test|--shell|--run) explicit=1 ;; esac
done
suites=()
if [ $explicit = 0 ]; then
	mkdir -p "$BUILD/results"
	: >"$BUILD/results/debug-skipped.tsv"
	kernel=" $(kernel_suites | tr '\n' ' ') "
	for settings in "$TOP"/tests/vm/*/settings; do
		suite=$(basename "$(dirname "$settings")")
		case $kernel in
		*" $suite "*) suites+=(--test "$suite") ;;
		*)
			say "debug lane: suite $suite not run (debug_lane=0 in its settings)"
			printf 'debug: %s (suite)	0	0	1	skip	not run on the debug lane: user space over drivers covered by other suites (debug_lane=0)\n' \
				"$suite" >>"$BUILD/results/debug-skipped.tsv" ;;
		esac
	done
fi

export VMTEST_SLOWDOWN=${VMTEST_SLOWDOWN:-4}
# The PREEMPT_RT kernel with one CPU, like the RT lane (vm-x86.sh says why).
[ "$series" = 6.12-rt ] && export VMTEST_SMP=${VMTEST_SMP:-1}
export VMTEST_APPEND="pci=noacpi kasan_multi_shot${VMTEST_APPEND:+ $VMTEST_APPEND}"
lane=debug
for ((i = 1; i <= $#; i++)); do
	[ "${!i}" = --lane ] && j=$((i + 1)) && lane=${!j}
done
vm() {	# vm LANE ARGS...: one guest on the debug kernel
	local name=$1
	shift
	"$TOP/tests/harness/vm-x86.sh" --kernel "$entry/bzImage" --kver "$kver" \
		--modroot "$entry/modroot" --modules "$BUILD/kmod/debug-$series/modules.list" \
		"$@" --lane "$name"
}
rc=0
vm "$lane" "${suites[@]}" "$@" || rc=1
# A whole-lane run on one CPU: the programs that need a second CPU (they
# skipped themselves above, a listed skip) in a second guest with two, as
# lane LANE-smp2 (the failures of a two-CPU PREEMPT_RT guest under TCG that
# made the lane one CPU are in the UART suites, docs/kernels.md).
if [ $explicit = 0 ] && [ "${VMTEST_SMP:-2}" = 1 ]; then
	mapfile -t smp2 < <(two_cpu_programs | awk '{ print "--test"; print }')
	if [ ${#smp2[@]} -gt 0 ]; then
		VMTEST_SMP=2 vm "$lane-smp2" "${smp2[@]}" "$@" || rc=1
	fi
fi
exit $rc
