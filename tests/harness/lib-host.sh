# SPDX-License-Identifier: GPL-2.0
# Host-side helpers shared by the VM lanes (source it after scripts/lib.sh).

# list_tests LANE PROGDIR REPODIR [FILTER...]: print "suite program path
# timeout" for every VM test program of the lane. PROGDIR holds the compiled C
# programs and REPODIR the repository (the shell programs) as the guest sees
# them. The x86_64 lanes run every suite; other lanes run the suites marked
# portable=1, all their programs but those the settings name in
# not_portable= (the ARM guest has Debian's tools: fetch-arm-userland.sh).
# Programs named bench* are benchmarks: listed only when VMTEST_BENCH=1 (make
# bench), and then only they are.
list_tests() {
	local lane=$1 progdir=$2 repodir=$3
	shift 3
	local suite_dir suite timeout src prog f excluded
	for suite_dir in "$TOP"/tests/vm/*/; do
		suite=$(basename "$suite_dir")
		[ -f "$suite_dir/settings" ] || { say "tests/vm/$suite has no settings file: skipped"; continue; }
		excluded=
		case $lane in
		x86_64*) ;;
		*)
			grep -qx 'portable=1' "$suite_dir/settings" || continue
			excluded=" $(sed -n 's/^not_portable=//p' "$suite_dir/settings" | tr -d '"') " ;;
		esac
		timeout=$(sed -n 's/^timeout=\([0-9][0-9]*\)$/\1/p' "$suite_dir/settings")
		timeout=${timeout:-45}
		{
			for src in "$suite_dir"*.c; do
				if [ -e "$src" ]; then
					echo "$(basename "$src" .c) $progdir/$suite/$(basename "$src" .c)"
				fi
			done
			for src in "$suite_dir"*.sh; do
				if [ -x "$src" ]; then echo "$(basename "$src" .sh) $repodir/tests/vm/$suite/$(basename "$src")"; fi
			done
		} | sort | while read -r prog f; do
			case $excluded in *" $prog "*) continue ;; esac
			case $prog in
			bench*) [ "${VMTEST_BENCH:-0}" = 1 ] || continue ;;
			*) [ "${VMTEST_BENCH:-0}" = 1 ] && continue ;;
			esac
			if [ $# -gt 0 ]; then
				local want match=0
				for want in "$@"; do
					if [ "$want" = "$suite" ] || [ "$want" = "$suite/$prog" ]; then match=1; fi
				done
				[ $match = 1 ] || continue
			fi
			echo "$suite $prog $f $timeout"
		done
	done
}

# stage_modules KVER KMODDIR MODULES OUT: OUT/lib/modules/KVER with our
# modules under extra/, the kernel's own tree linked as kernel/, and the
# output of depmod for both (the guest would need a minute for that depmod).
stage_modules() {
	local kver=$1 kmoddir=$2 modules=$3 out=$4 ko
	rm -rf "$out"
	mkdir -p "$out/lib/modules/$kver/extra"
	ln -s "$kmoddir/kernel" "$out/lib/modules/$kver/kernel"
	cp "$kmoddir"/modules.{order,builtin,builtin.modinfo} "$out/lib/modules/$kver/"
	while read -r ko; do cp "$ko" "$out/lib/modules/$kver/extra/"; done <"$modules"
	depmod -b "$out" "$kver" || die "depmod of the project's modules for $kver failed"
}

# boot_vm SHELL ALLOWANCE RESULTS CONSOLELOG APPEND QEMU-ARGS...: an
# interactive guest shell (SHELL=1; does not return) or the timed test run
# (ALLOWANCE: seconds for boot and module checks on top of the test timeouts).
# With BOOT_MARK set (a file the guest's runner creates once it has started:
# guest-run.sh's phases.txt), a guest that has not got that far within twice
# the allowance is stopped there: a boot that hangs or drowns in kernel
# reports would otherwise hold the lane for the whole budget (the debug
# lane's: 25 hours).
boot_vm() {
	local shell=$1 allowance=$2 results=$3 log=$4 append=$5 budget watch=
	shift 5
	if [ "$shell" = 1 ]; then
		say "interactive guest shell; leave with 'exit' (or Ctrl-a x)"
		exec "$@" -append "$append"
	fi
	budget=$(vm_time_budget "$results/tests.list" "$results/modules.list" "$allowance")
	say "booting $(basename "$1") under TCG: $(grep -c . "$results/tests.list") program(s), time budget ${budget}s"
	rm -f "$log.pid" "$log.boot"
	if [ -n "${BOOT_MARK:-}" ]; then
		boot_watch "$BOOT_MARK" $((2 * allowance)) "$log.pid" "$log.boot" &
		watch=$!
	fi
	run_qemu "$budget" "$log" "$@" -pidfile "$log.pid" -append "$append"
	if [ -n "$watch" ]; then
		kill "$watch" 2>/dev/null || true	# it may have ended (the mark came)
		wait "$watch" 2>/dev/null || true
	fi
	[ -s "$log.boot" ] && cat "$log.boot" >>"$log"
	rm -f "$log.pid" "$log.boot"
	return 0
}

# boot_watch MARK SECONDS PIDFILE NOTE: stop the QEMU of PIDFILE when MARK
# does not exist SECONDS after the start, and say so in NOTE.
boot_watch() {
	local mark=$1 secs=$2 pidfile=$3 note=$4 t=0
	while [ "$t" -lt "$secs" ]; do
		[ -e "$mark" ] && return 0
		sleep 2
		t=$((t + 2))
	done
	[ -e "$mark" ] && return 0
	echo "VMTEST-HOST: the guest had not started its test runner ${secs}s after boot; stopped" >"$note"
	[ -s "$pidfile" ] && kill "$(cat "$pidfile")" 2>/dev/null
	return 0
}

# vm_time_budget TESTLIST MODULELIST BOOT: seconds the whole VM run may take.
vm_time_budget() {
	local sum nmods
	sum=$(awk '{ s += $4 + 5 } END { print s + 0 }' "$1")
	nmods=$(grep -c . "$2" || true)
	echo $(($3 + sum + 10 * nmods))
}

# run_qemu BUDGET CONSOLELOG QEMU-ARGS...: run the VM, console to the log
# (and to the terminal with VMTEST_VERBOSE=1), killed when over budget.
run_qemu() {
	local budget=$1 log=$2 rc=0
	shift 2
	if [ "${VMTEST_VERBOSE:-0}" = 1 ]; then
		timeout -k 10 "$budget" "$@" </dev/null 2>&1 | tee "$log" || rc=$?
	else
		timeout -k 10 "$budget" "$@" </dev/null >"$log" 2>&1 || rc=$?
	fi
	[ "$rc" = 124 ] && echo "VMTEST-HOST: the VM ran out of its ${budget}s budget and was killed" >>"$log"
	return 0
}

# report_lane LANE RESULTS CONSOLELOG SECONDS: print the lane's outcome, copy its
# rows to $BUILD/results/LANE.tsv and return 1 on any failure.
report_lane() {
	local lane=$1 results=$2 console=$3 secs=$4 failed=0
	mkdir -p "$BUILD/results"
	local tsv=$BUILD/results/$lane.tsv
	: >"$tsv"
	[ -f "$results/results.tsv" ] && sed "s|^|$lane: |" "$results/results.tsv" >>"$tsv"

	if [ -f "$results/tap.txt" ]; then
		grep -vE '^#' "$results/tap.txt" | sed "s|^|[$lane] |"
	fi
	if [ ! -f "$results/done" ]; then
		local what
		what=$(cat "$results/current" 2>/dev/null || echo "boot")
		echo "[$lane] not ok - the VM stopped before the end, while running: $what"
		echo "[$lane] last lines of the guest console ($console):"
		grep -vE '^(ok|not ok|#) ' "$console" | tail -n 25 | sed "s|^|[$lane]   |"
		printf '%s: VM run (stopped during %s)\t0\t1\t0\tfail\tVM hang or crash\n' "$lane" "$what" >>"$tsv"
		failed=1
	fi
	# Show what failed, with the program's own output.
	local name pass fail skip verdict reason log
	while IFS=$'\t' read -r name pass fail skip verdict reason _secs; do
		[ "$verdict" = fail ] || continue
		failed=1
		log=$results/logs/$(echo "$name" | tr '/' '.').log
		echo "[$lane] FAILED: $name${reason:+ ($reason)}"
		[ -f "$log" ] && tail -n 30 "$log" | sed "s|^|[$lane]   |"
	done < <(cat "$results/results.tsv" 2>/dev/null)
	awk -F'\t' -v lane="$lane" -v secs="$secs" '
		{ p += $2; f += $3; s += $4 }
		END { printf "[%s] %d ok, %d not ok, %d skipped, in %ds\n", lane, p, f, s, secs }' "$tsv"
	return $failed
}

# kernel_suites: the VM suites that test our kernel code (every suite whose
# settings do not say debug_lane=0): what the debug lane and `make
# check-fast` run.
kernel_suites() {
	local settings
	for settings in "$TOP"/tests/vm/*/settings; do
		grep -qx 'debug_lane=0' "$settings" || basename "$(dirname "$settings")"
	done
}
# system_suites: the suites that are not kernel suites (debug_lane=0: the
# user-space stack above our drivers, the install): make check runs them in
# the x86_64 guest on Debian's 6.1, the kernel the robot's Debian runs.
system_suites() {
	local settings
	for settings in "$TOP"/tests/vm/*/settings; do
		grep -qx 'debug_lane=0' "$settings" && basename "$(dirname "$settings")"
	done
	return 0
}
# stock_kernel_suites 6.1|6.12|6.12-rt: the kernel suites make check runs on
# that stock Debian kernel (docs/kernels.md), besides the debug lane, which
# runs all of them: those whose settings say rt_lane=1 (the DIO irqchip,
# ts-can1's shared interrupt, n_rs485 under threaded interrupts) on 6.12-rt,
# the others on 6.12, so that each kernel suite runs on a stock kernel in
# every run; those whose settings say stock_6_1=1 on 6.1 as well (two CPUs
# there: dio-i2c/unbind-poll needs them). A suite runs on 6.12 with some of
# its programs also on 6.12-rt when its settings say rt_programs=PROG...
# (tsuart: traffic, issue 19 item 4).
stock_kernel_suites() {
	local suite settings prog
	for suite in $(kernel_suites); do
		settings=$TOP/tests/vm/$suite/settings
		if [ "$1" = 6.1 ]; then
			grep -qx 'stock_6_1=1' "$settings" && echo "$suite"
			continue
		fi
		if grep -qx 'rt_lane=1' "$settings"; then
			[ "$1" = 6.12-rt ] && echo "$suite"
		else
			[ "$1" = 6.12 ] && echo "$suite"
			[ "$1" = 6.12-rt ] || continue
			for prog in $(sed -n 's/^rt_programs=//p' "$settings"); do
				echo "$suite/$prog"
			done
		fi
	done
	return 0
}
# two_cpu_programs: SUITE/PROGRAM for each kernel-suite program that needs a
# second CPU (its settings say smp_programs=PROG...; with one CPU it skips
# itself): the debug lane's PREEMPT_RT guest has one CPU, so the lane runs
# them in a second guest with two.
two_cpu_programs() {
	local suite prog
	for suite in $(kernel_suites); do
		for prog in $(sed -n 's/^smp_programs=//p' "$TOP/tests/vm/$suite/settings"); do
			echo "$suite/$prog"
		done
	done
	return 0
}

# fuzz_scale: the fuzz programs' sizes for the guest, from ADVEE_FUZZ_SCALE:
# ci (the default: make check's) or full (the goal's of issue 26: 100,000
# ioctls per device kind, 1,000,000 wire characters, 5,000 to 10,000 sysfs
# writes per device; make fuzz). Anything else stops the run: a typo must not
# quietly run the small sizes.
fuzz_scale() {
	case ${ADVEE_FUZZ_SCALE:-ci} in
	ci | full) echo "${ADVEE_FUZZ_SCALE:-ci}" ;;
	*) die "ADVEE_FUZZ_SCALE=$ADVEE_FUZZ_SCALE: ci or full" ;;
	esac
}
