#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# check.sh [--test NAME]...: the project's whole test run (the README's test
# command, and CI's). Installs what is missing, then runs, in order:
#   kernel gates (W=1 on x86_64/armhf/armel, checkpatch --strict, sparse),
#   unit tests (CTest, plain and ASan/UBSan), the web dashboard in headless
#   Chromium (userland/web/tests/browser-check.sh), ARM userland cross builds,
#   the x86_64 VM lane, the armhf VM lane and the debug-kernel VM lane (KASAN,
#   lockdep, kmemleak, UBSAN; its kernel is built once and cached, see
#   scripts/debug-kernel.sh).
# Every stage runs even if an earlier one failed; the last line counts every
# TAP test point and every CTest test: "N passed, N failed, N skipped".
# With --test, only the x86_64 VM lane runs that suite (or suite/program); set
# VMTEST_LANES="x86_64 armhf debug" to run it on the other lanes too.
set -uo pipefail
. "$(dirname "$0")/lib.sh"

tests=()
while [ $# -gt 0 ]; do
	case $1 in
	--test) tests+=(--test "$2"); shift 2 ;;
	-h|--help) sed -n '3,15p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
	*) die "check.sh: unknown argument $1" ;;
	esac
done

start=$(date +%s)
"$TOP/scripts/deps.sh" || die "dependencies could not be installed"
rm -rf "$BUILD/results"
mkdir -p "$BUILD/results"
stage_row() {	# stage_row NAME STATUS
	if [ "$2" = 0 ]; then
		printf 'build: %s\t1\t0\t0\tok\t\n' "$1" >>"$BUILD/results/stages.tsv"
	else
		printf 'build: %s\t0\t1\t0\tfail\tsee output above\n' "$1" >>"$BUILD/results/stages.tsv"
	fi
}
stage() {	# stage NAME CMD...: run one step, record it, go on
	local name=$1 rc
	shift
	say "$name"
	"$@"
	rc=$?
	[ $rc = 0 ] || say "FAILED: $name"
	return $rc
}

if [ "${#tests[@]}" -eq 0 ]; then
	stage "kernel quality gates" "$TOP/scripts/kernel-gates.sh"
	stage "unit tests" "$TOP/scripts/unit.sh"
	# The web dashboard end to end on the host: advee-web, LCM over loopback
	# multicast, headless Chromium; one row per check in results/web.tsv.
	rm -f "$BUILD/results/web.tsv"
	stage "web dashboard (headless Chromium)" "$TOP/userland/web/tests/browser-check.sh"
	[ -s "$BUILD/results/web.tsv" ] ||
		printf 'web: browser check did not run\t0\t1\t0\tfail\tsee output above\n' >>"$BUILD/results/stages.tsv"
	for a in armhf armel; do
		stage "userland cross build ($a)" "$TOP/scripts/build-userland.sh" "$a"
		stage_row "userland cross build ($a)" $?
	done
	# dkms add/build/install in a private tree, then the VM loads its modules.
	stage "DKMS packaging (scripts/dkms-check.sh)" "$TOP/scripts/dkms-check.sh"
	stage_row "DKMS packaging: dkms add/build/install, modules load in the VM" $?
	lanes=${VMTEST_LANES:-x86_64 armhf debug}
else
	stage "kernel modules (x86_64)" "$TOP/scripts/build-kmod.sh" x86_64
	stage_row "kernel modules (x86_64)" $?
	# VM suites run user-space programs from build/userland (simulators, tools).
	stage "userland (native)" "$TOP/scripts/build-userland.sh" native
	stage_row "userland (native)" $?
	lanes=${VMTEST_LANES:-x86_64}
fi

for lane in $lanes; do
	case $lane in
	x86_64)
		[ -s "$BUILD/kmod/x86_64/modules.list" ] || "$TOP/scripts/build-kmod.sh" x86_64
		stage "test programs (x86_64)" "$TOP/scripts/build-testprogs.sh" x86_64
		stage_row "test programs (x86_64)" $?
		stage "x86_64 VM lane" "$TOP/tests/harness/vm-x86.sh" "${tests[@]}"
		;;
	armhf)
		[ -s "$BUILD/kmod/armhf/modules.list" ] || "$TOP/scripts/build-kmod.sh" armhf
		stage "test programs (armhf)" "$TOP/scripts/build-testprogs.sh" armhf
		stage_row "test programs (armhf)" $?
		stage "armhf VM lane" "$TOP/tests/harness/vm-arm.sh" "${tests[@]}"
		;;
	debug)
		# vm-debug.sh builds (or reuses) the debug kernel and our modules for
		# it; when that fails, no test ran: a failure, never a silent skip.
		rm -f "$BUILD/results/debug.tsv"
		stage "debug-kernel VM lane" "$TOP/tests/harness/vm-debug.sh" "${tests[@]}"
		if [ ! -s "$BUILD/results/debug.tsv" ]; then
			say "FAILED: the debug lane did not run: its kernel, our modules for it or its VM could not be set up (see above)"
			printf 'debug: lane did not run\t0\t1\t0\tfail\tdebug kernel, its modules or its VM could not be set up\n' \
				>>"$BUILD/results/stages.tsv"
		fi
		;;
	*) die "unknown lane $lane" ;;
	esac
done

# Summary over every row of this run.
cat "$BUILD"/results/*.tsv >"$BUILD/results/all.tsv"
echo
echo "Failures:"
awk -F'\t' '$5 == "fail" { printf "  %s%s\n", $1, ($6 != "" ? " (" $6 ")" : ""); n++ }
	END { if (!n) print "  none" }' "$BUILD/results/all.tsv"
echo "Skipped:"
awk -F'\t' '$4 > 0 { printf "  %s%s\n", $1, ($6 != "" ? " (" $6 ")" : ""); n++ }
	END { if (!n) print "  none" }' "$BUILD/results/all.tsv"
echo "Time: $(($(date +%s) - start)) s; details in build/results/"
awk -F'\t' '{ p += $2; f += $3; s += $4 } END {
	printf "%d passed, %d failed, %d skipped\n", p, f, s; exit (f > 0) }' "$BUILD/results/all.tsv"
