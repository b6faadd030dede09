#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# check.sh [--fast] [--test NAME]...: the project's whole test run (the README's
# test command, and CI's). Installs what is missing, then runs:
#   kernel gates (W=1 on every supported kernel, checkpatch --strict, sparse),
#   unit tests (CTest in one ASan/UBSan build; the plain build the VMs use has
#   no test binaries), the web dashboard in headless Chromium
#   (userland/web/tests/browser-check.sh), ARM userland cross builds with the
#   install manifest of each target, DKMS (on 6.1, 6.12, 6.12-rt), the x86_64
#   VM lanes (the suites above our drivers on 6.1; the kernel suites dealt
#   over stock 6.1, 6.12 and 6.12-rt, docs/kernels.md),
#   the debug-kernel VM lane (6.12 PREEMPT_RT with KASAN, lockdep, kmemleak,
#   UBSAN: every kernel suite; its kernel is built once and cached, see
#   scripts/debug-kernel.sh, in the background while the other stages run)
#   and the armhf VM lane.
# --fast (make check-fast): gates, then side by side the unit tests and the
# kernel suites in two x86_64 guests.
# Every stage runs even if an earlier one failed. Before the summary: the
# time of every stage and VM suite (also in build/results/time.tsv), then
# the failures and skips; a skip not listed in tests/expected-skips fails the
# run. The last line counts every TAP test point, CTest test and gate:
# "N passed, N failed, N skipped".
# With --test, only the x86_64 VM lane runs that suite (or suite/program); set
# VMTEST_LANES="x86_64 armhf debug" to run it on the other lanes too.
set -uo pipefail
. "$(dirname "$0")/lib.sh"
. "$TOP/tests/harness/lib-host.sh"

tests=() mode=full
while [ $# -gt 0 ]; do
	case $1 in
	--test) tests+=(--test "$2"); shift 2 ;;
	--fast) mode=fast; shift ;;
	-h|--help) sed -n '3,24p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
	*) die "check.sh: unknown argument $1" ;;
	esac
done
[ "${#tests[@]}" -gt 0 ] && mode=selected

start=$(date +%s)
RESULTS=$BUILD/results
rm -rf "$RESULTS"
mkdir -p "$RESULTS"
TIMES=$RESULTS/time.tsv
: >"$TIMES"

stage_row() {	# stage_row NAME STATUS: one row for a stage without rows of its own
	if [ "$2" = 0 ]; then
		printf 'build: %s\t1\t0\t0\tok\t\n' "$1" >>"$RESULTS/stages.tsv"
	else
		printf 'build: %s\t0\t1\t0\tfail\tsee output above\n' "$1" >>"$RESULTS/stages.tsv"
	fi
}
# fd 3: the terminal, also from the tracks (whose output goes to their logs):
# one line as each stage starts and ends.
exec 3>&2
stage() {	# stage NAME CMD...: run one step, time it, go on
	local name=$1 rc t0 secs
	shift
	say "$name"
	printf '==> [%s] start: %s\n' "$(date +%T)" "$name" >&3
	t0=$(date +%s)
	"$@"
	rc=$?
	secs=$(($(date +%s) - t0))
	printf 'stage\t%s\t%d\t%s\n' "$name" "$secs" "$([ $rc = 0 ] && echo ok || echo fail)" >>"$TIMES"
	printf '==> [%s] %s: %s (%d s)\n' "$(date +%T)" "$([ $rc = 0 ] && echo done || echo FAILED)" "$name" "$secs" >&3
	[ $rc = 0 ] || say "FAILED: $name"
	return $rc
}

stage "dependencies (scripts/deps.sh)" "$TOP/scripts/deps.sh" ||
	die "dependencies could not be installed"

lanes=${VMTEST_LANES:-x86_64 armhf debug}
[ "$mode" = fast ] && lanes=x86_64
[ "$mode" = selected ] && lanes=${VMTEST_LANES:-x86_64}

# The debug lane's kernel: 6.12 with PREEMPT_RT (issue 19 item 3;
# docs/kernels.md); ADVEE_DEBUG_KERNEL=6.1 for the 6.1 PREEMPT one.
export ADVEE_DEBUG_KERNEL=${ADVEE_DEBUG_KERNEL:-6.12-rt}
# The debug kernel (a cold build: 21 minutes next to the other stages on a
# quiet 2-core machine) is needed only by the debug lane: build it in the
# background from the start, at the same priority as the stages in front
# (at a lower one, the builds in front starve it and the debug lane waits
# for it at the end). vm-debug.sh waits for it (scripts/debug-kernel.sh
# takes a lock); a cached kernel costs nothing here.
case " $lanes " in
*" debug "*)
	(
		t0=$(date +%s)
		ADVEE_KNICE=${ADVEE_KNICE:-0} "$TOP/scripts/debug-kernel.sh" >"$RESULTS/debug-kernel.log" 2>&1
		rc=$?
		printf 'stage\t%s\t%d\t%s\n' "debug kernel build or cache look-up (background, from the start)" \
			$(($(date +%s) - t0)) "$([ $rc = 0 ] && echo ok || echo fail)" >>"$TIMES"
	) &
	;;
esac

# A track: stages that run one after the other, in the background, with
# their output in build/results/track-NAME.log (printed when it ends).
track_pids=() track_names=()
track() {	# track NAME FUNCTION
	local name=$1
	say "track '$name' started (output: build/results/track-$name.log)"
	("$2" >"$RESULTS/track-$name.log" 2>&1) &
	track_pids+=($!) track_names+=("$name")
}
wait_tracks() {
	local i
	for i in "${!track_pids[@]}"; do
		wait "${track_pids[$i]}"
		echo "---- output of track '${track_names[$i]}' ----"
		cat "$RESULTS/track-${track_names[$i]}.log"
		echo "---- end of track '${track_names[$i]}' ----"
	done
	track_pids=() track_names=()
}

x86_lane() {	# x86_lane LANE [--test SUITE]...: one x86_64 guest
	local lane=$1
	shift
	[ -s "$BUILD/kmod/x86_64/modules.list" ] || "$TOP/scripts/build-kmod.sh" x86_64
	stage "$lane VM lane" "$TOP/tests/harness/vm-x86.sh" --lane "$lane" "$@"
}
stock_kernel() {	# stock_kernel 6.1|6.12|6.12-rt: its share of the kernel suites (lib-host.sh: stock_kernel_suites)
	local k=$1 sel
	mapfile -t sel < <(stock_kernel_suites "$k" | awk '{ print "--test"; print }')
	if [ "$k" = 6.1 ]; then
		# The debug lane runs on 6.1 itself when ADVEE_DEBUG_KERNEL=6.1.
		[ "$ADVEE_DEBUG_KERNEL" = 6.1 ] && return 0
		x86_lane x86_64-6.1 "${sel[@]}"
		return
	fi
	[ -s "$BUILD/kmod/x86_64-$k/modules.list" ] || "$TOP/scripts/build-kmod.sh" "x86_64-$k"
	stage "x86_64-$k VM lane" "$TOP/tests/harness/vm-x86.sh" --kernel-flavour "$k" "${sel[@]}"
}
armhf_lane() {
	[ -s "$BUILD/kmod/armhf/modules.list" ] || "$TOP/scripts/build-kmod.sh" armhf
	stage "test programs (armhf)" "$TOP/scripts/build-testprogs.sh" armhf
	stage_row "test programs (armhf)" $?
	stage "armhf VM lane" "$TOP/tests/harness/vm-arm.sh" "${tests[@]}"
}
debug_lane() {
	# vm-debug.sh waits for the background build of the debug kernel (a lock
	# in scripts/debug-kernel.sh) and then finds it in the cache.
	# vm-debug.sh builds (or reuses) the debug kernel and our modules for
	# it; when that fails, no test ran: a failure, never a silent skip.
	rm -f "$RESULTS/debug.tsv"
	stage "debug-kernel VM lane" "$TOP/tests/harness/vm-debug.sh" "${tests[@]}"
	if [ ! -s "$RESULTS/debug.tsv" ]; then
		say "FAILED: the debug lane did not run: its kernel, our modules for it or its VM could not be set up"
		printf 'debug: lane did not run\t0\t1\t0\tfail\tdebug kernel, its modules or its VM could not be set up\n' \
			>>"$RESULTS/stages.tsv"
	fi
}
# The host-side checks that need no VM of their own, at a low priority next
# to the VM lanes: CPU-bound builds fill the time the guests spend waiting.
host_checks() {
	stage "unit tests (ASan/UBSan)" nice -n 10 "$TOP/scripts/unit.sh"
	# The web dashboard end to end on the host: advee-web, LCM over loopback
	# multicast, headless Chromium, then real browsers driven by puppeteer-core
	# (login, control, refusals, fuzz, phone); one row per check in results/web.tsv.
	stage "web dashboard (headless Chromium)" "$TOP/userland/web/tests/browser-check.sh"
	[ -s "$RESULTS/web.tsv" ] ||
		printf 'web: browser check did not run\t0\t1\t0\tfail\tsee output above\n' >>"$RESULTS/stages.tsv"
	debs_check
}
debs_check() {	# the packages of the stage "Debian packages": lintian, programs
	stage "Debian packages: lintian" lintian --fail-on error,warning "$BUILD"/debs/advee_*.changes
	stage_row "Debian packages: lintian, no error and no warning" $?
	stage "Debian packages: man page and --version" "$TOP/scripts/debs-programs.sh"
	stage_row "Debian packages: every program has a man page and --version" $?
}
cross_check() {	# cross_check TARGET: every program of the install manifest exists for it
	stage "userland cross build + install manifest ($1)" nice -n 10 "$TOP/scripts/cross-check.sh" "$1"
	stage_row "userland cross build + install manifest ($1)" $?
}
debs_cross_check() {	# debs_cross_check ARCH: the robot's packages cross-built over cross_check's build
	# (18-33 s: dpkg-buildpackage -a ARCH, help2man under qemu-user, lintian)
	stage "Debian packages ($1): dpkg-buildpackage -a $1, ARM ELF check, lintian" \
		nice -n 10 "$TOP/scripts/build-debs.sh" --arch "$1" --lintian
	stage_row "Debian packages ($1): built, every ELF file ARM, lintian no error and no warning" $?
}
pair_check() {	# the two-computer test: two x86_64 guests on a private link (tests/twocomp)
	stage "two computers (tests/harness/vm-pair.sh)" "$TOP/tests/harness/vm-pair.sh"
	stage_row "two computers: both guests ran their programs" $?
}
dkms_check() {	# dkms add/build/install in a private tree, then a VM loads its modules
	stage "DKMS packaging (scripts/dkms-check.sh)" "$TOP/scripts/dkms-check.sh"
	stage_row "DKMS packaging: dkms add/build/install, modules load in the VM" $?
}

# The debug lane is the longest track (about 25 minutes of a guest) and needs
# neither the gates nor the userland build: only its kernel, our modules for
# it (vm-debug.sh builds them) and the C test programs. In a full run it
# starts here, next to the stages below, instead of after them.
stage "test programs (x86_64)" "$TOP/scripts/build-testprogs.sh" x86_64
stage_row "test programs (x86_64)" $?
[ "$mode" = full ] && track debug debug_lane

case $mode in
selected)
	stage "kernel modules (x86_64)" "$TOP/scripts/build-kmod.sh" x86_64
	stage_row "kernel modules (x86_64)" $?
	;;
*)
	stage "kernel quality gates" "$TOP/scripts/kernel-gates.sh"	# also builds the modules of every target
	;;
esac
# The VM suites and the browser check run the plain build's programs; its
# test binaries would only repeat what the ASan build runs.
ADVEE_UNIT_TESTS=0 stage "userland (native)" "$TOP/scripts/build-userland.sh" native
stage_row "userland (native)" $?
# The CANopen example of docs/canopen.md built against a staged install of
# that build's libadvee-dev files (CMake package and pkg-config); the ASan
# build, the only one with tests here, cannot link it. Before the lanes (a
# few seconds): canopen/dcf-download runs it against a simulated node.
stage "CANopen example against the installed library" "$TOP/userland/canopen/examples/build-against-install.sh" \
	"$BUILD/userland" "$BUILD/canopen-example" \
	"$(sed -n 's/^CMAKE_INSTALL_LIBDIR:PATH=//p' "$BUILD/userland/CMakeCache.txt")" c++
stage_row "CANopen example builds against the staged install (find_package, pkg-config)" $?
# The Debian packages of that build (debian/rules reuses it: 21-36 s on a
# loaded 2-core machine), before the tracks: the install suite installs them
# (make check TEST=install[/debs] builds them too, other selections do not).
if [ "$mode" = full ] || printf '%s\n' "${tests[@]}" | grep -qx 'install\(/debs\)\{0,1\}'; then
	ADVEE_UNIT_TESTS=0 stage "Debian packages (dpkg-buildpackage)" "$TOP/scripts/build-debs.sh"
	stage_row "Debian packages (dpkg-buildpackage)" $?
fi

case $mode in
fast)
	# The unit tests and the kernel suites in two x86_64 guests (the suites
	# dealt out in turn), side by side.
	mapfile -t sel1 < <(kernel_suites | awk 'NR % 2 == 1 { print "--test"; print }')
	mapfile -t sel2 < <(kernel_suites | awk 'NR % 2 == 0 { print "--test"; print }')
	unit_track() { stage "unit tests (ASan/UBSan)" nice -n 10 "$TOP/scripts/unit.sh"; }
	vm1_track() { x86_lane x86_64 "${sel1[@]}"; }
	vm2_track() { x86_lane x86_64-2 "${sel2[@]}"; }
	track unit unit_track
	track vm vm1_track
	track vm2 vm2_track
	wait_tracks
	;;
selected)
	for lane in $lanes; do
		case $lane in
		x86_64) x86_lane x86_64 "${tests[@]}" ;;
		armhf) armhf_lane ;;
		debug) debug_lane ;;
		*) die "unknown lane $lane" ;;
		esac
	done
	;;
full)
	# Four tracks side by side. A TCG guest waits on timers most of the
	# time (an x86_64 guest kept 0.6 of a core busy over its 30 minutes), so
	# up to three guests (each with 2 vCPUs) run next to the host's builds
	# (CPU-bound, at a lower priority). Each kernel suite runs on 6.12
	# PREEMPT_RT (the debug lane), on 6.1 (the armhf lane if portable) and
	# on stock 6.12 or 6.12-rt, some also on stock 6.1 (stock_6_1=1;
	# docs/kernels.md); the other suites on Debian's 6.1:
	#   vm      the kernel suites on stock 6.12, then those on stock 6.1,
	#           then the armhf lane, then the two-computer test (two guests
	#           at once, about 3 min), then the armel cross build and its
	#           Debian packages (this track ends first otherwise);
	#   vmuser  the x86_64 guest (6.1) of the suites that are not kernel
	#           suites (user-space stack, install), then DKMS (a guest per
	#           amd64 kernel), then the kernel suites with rt_lane=1 on
	#           6.12 PREEMPT_RT, then the armhf cross build;
	#   debug   the debug lane, started before the gates (above), as soon
	#           as its kernel is there (a cold build runs in the background
	#           from the start; vm-debug.sh waits);
	#   host    the unit tests (the longest stage: a build at a lower
	#           priority next to three guests), the browser check, lintian
	#           and the packages' programs.
	mapfile -t system_sel < <(system_suites | awk '{ print "--test"; print }')
	vm_track() { stock_kernel 6.12; stock_kernel 6.1; armhf_lane; pair_check; cross_check armel; debs_cross_check armel; }
	vmuser_track() { x86_lane x86_64 "${system_sel[@]}"; dkms_check; stock_kernel 6.12-rt; cross_check armhf; }
	track vm vm_track
	track vmuser vmuser_track
	track host host_checks
	wait_tracks
	;;
esac
wait	# the debug kernel build, when no lane needed it
# Summary over every row of this run.
for f in "$RESULTS"/*.tsv; do
	case ${f##*/} in time.tsv|all.tsv|skip-policy.tsv) ;; *) cat "$f" ;; esac
done >"$RESULTS/all.tsv"
"$TOP/scripts/skip-policy.sh" "$RESULTS/all.tsv" >"$RESULTS/skip-policy.tsv"
cat "$RESULTS/skip-policy.tsv" >>"$RESULTS/all.tsv"
# VM time per suite and lane (the 7th column of the lanes' rows).
for lane in x86_64 x86_64-2 x86_64-6.1 x86_64-6.12 x86_64-6.12-rt armhf debug debug-smp2 twocomp-a twocomp-b; do
	[ -s "$RESULTS/$lane.tsv" ] || continue
	awk -F'\t' -v lane="$lane" '$7 != "" {
			s = $1; sub(/^[^:]*: /, "", s); sub(/\/.*/, "", s); t[s] += $7
		} END { for (s in t) printf "suite\t%s: %s\t%d\n", lane, s, t[s] }' "$RESULTS/$lane.tsv" | sort >>"$TIMES"
done
total=$(($(date +%s) - start))
printf 'total\tcheck.sh %s\t%d\n' "$mode" "$total" >>"$TIMES"
echo
echo "Time (build/results/time.tsv):"
awk -F'\t' '
	$1 == "stage" { printf "  %6d s  %s%s\n", $3, $2, ($4 == "fail" ? "  (failed)" : "") }
	$1 == "suite" { printf "  %6d s      VM suite %s\n", $3, $2 }
	$1 == "total" { printf "  %6d s  total\n", $3 }' "$TIMES"
echo "Failures:"
awk -F'\t' '$5 == "fail" { printf "  %s%s\n", $1, ($6 != "" ? " (" $6 ")" : ""); n++ }
	END { if (!n) print "  none" }' "$RESULTS/all.tsv"
echo "Skipped (one not listed in tests/expected-skips is also a failure above):"
awk -F'\t' '$4 > 0 { printf "  %s%s\n", $1, ($6 != "" ? " (" $6 ")" : ""); n++ }
	END { if (!n) print "  none" }' "$RESULTS/all.tsv"
echo "Time: $total s; details in build/results/"
awk -F'\t' '{ p += $2; f += $3; s += $4 } END {
	printf "%d passed, %d failed, %d skipped\n", p, f, s; exit (f > 0) }' "$RESULTS/all.tsv"
