#!/bin/sh
# SPDX-License-Identifier: GPL-2.0
#
# guest-run.sh JOBFILE: the test runner inside the VM (PID 1), for both lanes.
# POSIX sh: it runs under /bin/sh, dash on both lanes (the host's on x86_64,
# Debian's armhf one from scripts/fetch-arm-userland.sh on ARM).
#
# The job file (written by the host) sets:
#   VMTEST_LANE            x86_64 | armhf
#   VMTEST_REPO            the repository path (tests source tap.sh from it)
#   VMTEST_BUILD           the build directory
#   VMTEST_RESULTS         writable directory for results
#   VMTEST_MODULES         file: project modules, one .ko path per line
#   VMTEST_INSTALL_MODULES 1: overlay VMTEST_MODROOT (extra/*.ko + depmod output,
#                          staged by the host) on /lib/modules/$(uname -r);
#                          0: already installed (ARM initramfs)
#   VMTEST_MODBASE         optional: the booted kernel's own module tree is
#                          VMTEST_MODBASE/lib/modules/$(uname -r) (a kernel the
#                          host has not installed, such as the debug lane's)
#   VMTEST_TESTLIST        file: "suite program path timeout" per line
#   VMTEST_SLOWDOWN        optional: how many times slower than a stock kernel
#                          this guest's kernel runs (the debug lane: 4), for
#                          the programs' timing limits (tsuart/traffic)
#   VMTEST_FUZZ_SCALE      optional: ci (the default) or full, the sizes of the
#                          fuzz programs (tests/lib/fuzz.h, fuzz_size in tap.sh)
#   VMTEST_CONSOLE_RESULTS 1: also print results.tsv to the console (ARM lane)
#   VMTEST_SHELL           1: after installing the modules, an interactive shell
#                          on the console instead of the tests
#
# Results: tap.txt (top-level TAP, program output as "# " lines), results.tsv
# (name, passed, failed, skipped, verdict, reason, seconds), logs/<suite>.<prog>.log,
# dmesg.txt, current (what runs now), done (written last).
# Every program is checked for exit status, timeout and new kernel warnings.

# shellcheck disable=SC1090
. "$1" || { echo "guest-run: cannot read job file $1" >/dev/console; echo o >/proc/sysrq-trigger; }
export VMTEST_REPO VMTEST_BUILD VMTEST_LANE VMTEST_MODULES
export VMTEST_SLOWDOWN="${VMTEST_SLOWDOWN:-1}"
export VMTEST_FUZZ_SCALE="${VMTEST_FUZZ_SCALE:-ci}"
export PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin
export HOME=/root LC_ALL=C
R=$VMTEST_RESULTS
mkdir -p "$R/logs" /run/vmtest-scratch
exec >/dev/console 2>&1

# Kernel messages that fail a run (issue 2 + what lockdep/KASAN/UBSAN/RCU print).
BAD_KMSG='BUG:|WARNING:|Oops|general protection|RIP:|soft lockup|hard LOCKUP|hung task|blocked for more than|detected stalls|UBSAN:|kernel BUG|Kernel panic|unreferenced object'

tap() { echo "$*" >>"$R/tap.txt"; echo "$*"; }
# phase NAME: a timestamped line in phases.txt (and on the console), to see
# where a run spends its time
phase() { read -r up _ </proc/uptime; echo "[$up s] $*" | tee -a "$R/phases.txt"; }
phase "runner started"
n=0
ok_point() {	# ok_point STATUS NAME [REASON]
	n=$((n + 1))
	if [ "$1" = ok ]; then
		tap "ok $n $2"
		printf '%s\t1\t0\t0\tok\t\n' "$2" >>"$R/results.tsv"
	else
		tap "not ok $n $2${3:+ # $3}"
		printf '%s\t0\t1\t0\tfail\t%s\n' "$2" "$3" >>"$R/results.tsv"
	fi
}

# --- kernel log checks -----------------------------------------------------------
# dmesg reads the ring buffer synchronously (no reader process to wait for);
# lines are told apart by their timestamp, which survives a ring buffer wrap.
kmsg_last=-1
# Set $bad to the new bad kernel lines since the last call (empty: clean).
# Not for $(...): the position must survive in this shell. One awk pass: under
# TCG every extra process costs tens of milliseconds.
kmsg_check() {
	out=$(dmesg 2>/dev/null | awk -v last="$kmsg_last" -v re="$BAD_KMSG" '
		{
			# keep the text: printing a number would round it to 6 digits
			stamp = $0; sub(/^\[ */, "", stamp); sub(/\].*/, "", stamp)
			if (stamp + 0 > last + 0 || last < 0) { if ($0 ~ re && bad++ < 5) print; newest = stamp }
		}
		END { print "NEWEST " (newest == "" ? last : newest) }')
	kmsg_last=${out##*NEWEST }
	bad=$(echo "$out" | grep -v '^NEWEST ')
}
kmsg_check	# boot messages are not any test's fault

# kmemleak (debug lane): leaks are reported by a scan after the suite. Objects
# from boot are not any test's fault: report them now and set them aside. An
# object is reported only when two scans agree, hence scan twice.
kmemleak=/sys/kernel/debug/kmemleak
kmemleak_scan() {
	echo scan >"$kmemleak" && sleep 1 && echo scan >"$kmemleak"
}
nleak=0	# TAP points of the leak check: 0 or 1
if [ -w "$kmemleak" ]; then
	nleak=1
	kmemleak_scan && echo clear >"$kmemleak"
else
	kmemleak=
fi

# Shorter detectors than the defaults, so that a hang is named inside the
# per-program timeout instead of after it.
[ -w /proc/sys/kernel/hung_task_timeout_secs ] && echo 20 >/proc/sys/kernel/hung_task_timeout_secs
[ -w /proc/sys/kernel/hung_task_warnings ] && echo -1 >/proc/sys/kernel/hung_task_warnings
echo 1 >/proc/sys/kernel/printk_ratelimit 2>/dev/null

# --- modules -----------------------------------------------------------------
modnames=
while read -r ko; do
	[ -n "$ko" ] || continue
	m=${ko##*/}
	modnames="$modnames ${m%.ko}"
done <"$VMTEST_MODULES"

if [ "$VMTEST_INSTALL_MODULES" = 1 ]; then
	# The host staged extra/*.ko and the depmod output in VMTEST_MODROOT: put it
	# over the stock tree (read-only overlay, upper layer first).
	lower=/lib/modules/$(uname -r)
	if [ -z "${VMTEST_MODBASE:-}" ]; then
		modprobe overlay &&
			mount -t overlay overlay -o "lowerdir=$VMTEST_MODROOT:$lower" "$lower"
	else
		# The host's /lib/modules has no directory for this kernel to mount
		# on: overlay /lib/modules itself, with the kernel's own tree between.
		modprobe -d "$VMTEST_MODBASE" overlay &&
			mount -t overlay overlay -o "lowerdir=${VMTEST_MODROOT%/*}:$VMTEST_MODBASE/lib/modules:/lib/modules" /lib/modules
	fi || { echo "guest-run: cannot install the project's modules"; echo 1 >"$R/install-failed"; }
fi

if [ "${VMTEST_SHELL:-0}" = 1 ]; then
	echo "vmtest: interactive guest shell; the project's modules are installed (modprobe NAME)."
	echo "vmtest: /run/vmtest is the host's $VMTEST_HOST_RESULTS; 'exit' powers off."
	cd / && setsid -c /bin/bash -i </dev/console >/dev/console 2>&1
	echo o >/proc/sysrq-trigger
	sleep 10
fi

phase "runner up"
ntests=$(grep -c . "$VMTEST_TESTLIST")
nmods=$(echo $modnames | wc -w)
tap "TAP version 13"
tap "1..$((nmods + ntests + 1 + nleak))"
tap "# lane $VMTEST_LANE, kernel $(uname -r), $nmods module(s), $ntests program(s)"

# Every module loads and unloads once before any test uses it. All of them in
# one modprobe call each way first (each process costs under TCG); only when
# that fails, one by one, so that the point names the culprit.
# unload_modules MODULE...: unload those that are loaded; sets $left to the
# ones that stay. kmod takes them all in one call; when that fails, one by
# one, and a dependency order the list does not follow needs another pass.
loaded_modules() {
	echo "$*" | tr - _ | awk 'NR == FNR { for (i = 1; i <= NF; i++) ours[$i] = 1; next }
		$1 in ours { print $1 }' - /proc/modules
}
unload_modules() {
	left=$(loaded_modules "$@")
	[ -z "$left" ] && return
	# shellcheck disable=SC2086
	modprobe -r -a $left >/dev/null 2>&1 && { left=; return; }
	for pass in 1 2 3; do
		pending=$left left=
		for m in $pending; do modprobe -r "$m" >/dev/null 2>&1 || left="$left $m"; done
		[ -z "$left" ] && return
	done
	left=$(loaded_modules $left)
}
module_cycle() {	# module_cycle MODULE...: sets $why (empty: clean)
	why=
	if ! out=$(modprobe -a "$@" 2>&1); then
		why="modprobe: $(echo "$out" | tail -1)"
	fi
	unload_modules "$@"
	[ -n "$left" ] && why="${why:+$why; }modprobe -r failed for:$left"
	kmsg_check
	[ -n "$bad" ] && why="${why:+$why; }dmesg: $(echo "$bad" | head -1)"
}
phase "module load/unload cycle"
echo "modules" >"$R/current"
# shellcheck disable=SC2086
[ -n "$modnames" ] && module_cycle $modnames
if [ -z "$why" ]; then
	for m in $modnames; do ok_point ok "module $m loads and unloads"; done
else
	for m in $modnames; do
		echo "module $m" >"$R/current"
		module_cycle "$m"
		if [ -n "$why" ]; then
			ok_point fail "module $m loads and unloads" "$why"
		else
			ok_point ok "module $m loads and unloads"
		fi
	done
fi

phase "test programs"
# --- test programs -------------------------------------------------------------
# run_prog TIMEOUT LOG CMD: run in its own session so that a timeout kills the
# whole process group; prints "timeout" or the exit status.
run_prog() {
	limit=$1 log=$2
	shift 2
	marker=/run/vmtest-timeout.$$
	rm -f "$marker"
	(cd /run/vmtest-scratch && exec setsid "$@") >"$log" 2>&1 </dev/null &
	pid=$!
	(
		sleep "$limit"
		if kill -0 "$pid" 2>/dev/null; then
			: >"$marker"
			kill -TERM -- "-$pid" 2>/dev/null || kill -TERM "$pid"
			sleep 3
			kill -KILL -- "-$pid" 2>/dev/null || kill -KILL "$pid" 2>/dev/null
		fi
	) >/dev/null 2>&1 &	# not holding the caller's $(...) pipe open
	watchdog=$!
	wait "$pid"
	rc=$?
	kill "$watchdog" 2>/dev/null
	wait "$watchdog" 2>/dev/null
	if [ -e "$marker" ]; then echo timeout; else echo "$rc"; fi
	rm -f "$marker"
}

while read -r suite prog path limit; do
	[ -n "$suite" ] || continue
	name="$suite/$prog"
	log="$R/logs/$suite.$prog.log"
	echo "$name" >"$R/current"
	[ "$VMTEST_CONSOLE_RESULTS" = 1 ] && printf 'VMTEST-CURRENT\t%s\n' "$name"
	rm -rf /run/vmtest-scratch && mkdir -p /run/vmtest-scratch
	export VMTEST_SCRATCH=/run/vmtest-scratch
	echo "vmtest: start $name" >/dev/kmsg	# so that dmesg.txt shows who ran when
	start=$(date +%s)
	status=$(run_prog "$limit" "$log" "$path")
	secs=$(($(date +%s) - start))
	kmsg_check
	# One pass over the output: copy it into tap.txt as "# " lines and count
	# the program's own TAP points (top level only; nested ones are indented).
	read -r pass fail skip skipwhy <<EOF
$(awk -v tap="$R/tap.txt" '
	{ print "# " $0 >>tap }
	/^ok [0-9]+/ {
		if ($0 ~ /# *(SKIP|skip)/) {
			s++
			if (why == "") { why = $0; sub(/.*# *(SKIP|skip) */, "", why) }
		} else p++
	}
	/^not ok [0-9]+/ {
		# TODO: a known defect, counted like a skip (tests/expected-skips)
		if ($0 ~ /# *TODO/) {
			s++
			if (why == "") { why = $0; sub(/.*# *TODO */, "TODO ", why) }
		} else f++
	}
	/^1\.\.0 *# *(SKIP|skip)/ && why == "" { why = $0; sub(/.*# *(SKIP|skip) */, "", why) }
	END { printf "%d %d %d %s\n", p, f, s, why }' "$log")
EOF
	reason=
	if [ "$status" = timeout ]; then
		reason="TIMEOUT after $limit s"
	elif [ "$status" != 0 ] && [ "$status" != 4 ]; then
		reason="exit status $status"
	elif [ "$status" = 4 ] && [ $((pass + fail)) -gt 0 ]; then
		reason="exit status 4 (skip) after running tests"
	fi
	[ -n "$bad" ] && reason="${reason:+$reason; }dmesg: $(echo "$bad" | head -1)"
	if [ -n "$bad" ]; then
		echo "$bad" | sed "s|^|# dmesg during $name: |" | tee -a "$R/tap.txt"
	fi
	if [ -n "$reason" ]; then
		# A failure that the program's own points do not show counts once more.
		verdict=fail
		extra=1
		[ "$fail" -gt 0 ] && [ -z "$bad" ] && [ "$status" != timeout ] && extra=0
		fail=$((fail + extra))
	elif [ "$status" = 4 ]; then
		verdict=skip
		[ "$skip" -eq 0 ] && skip=1
	elif [ $((pass + fail + skip)) -eq 0 ]; then
		# A program that printed no TAP point tested nothing we can see:
		# exiting 0 is not a pass.
		reason="no TAP test point (exit status $status)"
		verdict=fail
		fail=1
	else
		verdict=ok
	fi
	[ "$fail" -gt 0 ] && verdict=fail
	# A skip's reason is the program's own (its "# SKIP why"), also for a
	# program that passed with some points skipped: the summary and the
	# skip policy name it.
	[ "$verdict" != fail ] && [ "$skip" -gt 0 ] && [ -z "$reason" ] && reason=$skipwhy
	n=$((n + 1))
	case $verdict in
	ok) tap "ok $n $name # ${secs}s" ;;
	skip) tap "ok $n $name # SKIP $skipwhy" ;;
	fail) tap "not ok $n $name # ${reason:-failed test points} (${secs}s)" ;;
	esac
	printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$pass" "$fail" "$skip" "$verdict" "$reason" "$secs" >>"$R/results.tsv"
done <"$VMTEST_TESTLIST"

# --- end of run: nothing of ours may stay loaded ---------------------------------
phase "final unload check"
echo "unload" >"$R/current"
# shellcheck disable=SC2086
unload_modules $modnames
kmsg_check
if [ -n "$left" ]; then
	ok_point fail "project modules unload after the suite" "still loaded:$left"
elif [ -n "$bad" ]; then
	ok_point fail "project modules unload after the suite" "dmesg: $(echo "$bad" | head -1)"
else
	ok_point ok "project modules unload after the suite"
fi

# Leaks: allocated after boot, referenced by nothing now. Each report is named
# after the program that was running when the object was allocated, and the
# allocating command. kmemleak gives the allocation time in jiffies, which
# start at 2^32 - 300 * HZ (INITIAL_JIFFIES): one reading of jiffies and the
# time in /proc/timer_list gives HZ, hence the uptime of each allocation, which
# the "vmtest: start" lines of the kernel log turn into a program.
if [ -n "$kmemleak" ]; then
	echo "kmemleak scan" >"$R/current"
	kmemleak_scan
	cat "$kmemleak" >"$R/kmemleak.txt" 2>&1
	if [ -s "$R/kmemleak.txt" ]; then
		culprits=$({
			dmesg | grep 'vmtest: start '
			echo TIMER
			grep -m2 -E '^(now at|jiffies:) ' /proc/timer_list
			echo LEAKS
			cat "$R/kmemleak.txt"
		} | awk '
			/^TIMER$/ { part = 1; next }
			/^LEAKS$/ { part = 2; next }
			part == 0 { t = $0; sub(/^\[ */, "", t); sub(/\].*/, "", t); start[++k] = t + 0; name[k] = $NF; next }
			part == 1 && /^now at / { now = $3 / 1e9; next }
			part == 1 && /^jiffies: / { jnow = $2; next }
			part == 2 && /^  comm "/ {
				comm = $0; sub(/^  comm "/, "", comm); sub(/".*/, "", comm)
				who = "?"
				if (now > 0 && jnow != "" && now != 300) {
					hz = (jnow - 4294967296) / (now - 300)
					best = 100
					split("250 300 1000", cand, " ")
					for (c in cand) if ((cand[c] - hz) ^ 2 < (best - hz) ^ 2) best = cand[c]
					born = ($NF - 4294967296) / best + 300
					who = "module-checks"
					for (i = 1; i <= k; i++) if (start[i] <= born) who = name[i]
				}
				print who " (" comm ")"
			}' | sort | uniq -c | awk '{ n = $1; sub(/^ *[0-9]+ /, ""); printf "%s%s x%d", sep, $0, n; sep = ", " }')
		ok_point fail "no kernel memory leaks (kmemleak)" "$(grep -c '^unreferenced object' "$R/kmemleak.txt") leak(s), allocated during: $culprits; see kmemleak.txt"
		sed 's/^/# kmemleak: /' "$R/kmemleak.txt" | head -40 | tee -a "$R/tap.txt"
	else
		ok_point ok "no kernel memory leaks (kmemleak)"
	fi
fi

phase "saving the kernel log"
dmesg >"$R/dmesg.txt" 2>&1
if [ "$VMTEST_CONSOLE_RESULTS" = 1 ]; then
	# No shared file system on this lane: the host reads everything back from
	# the console, so keep kernel messages from splitting these lines.
	dmesg -n 1 2>/dev/null
	sed 's/^/VMTEST-RESULT\t/' "$R/results.tsv"
	sed 's/^/VMTEST-TAP\t/' "$R/tap.txt"
	sed 's/^/VMTEST-DMESG\t/' "$R/dmesg.txt"
	for log in "$R"/logs/*.log; do
		[ -e "$log" ] && sed "s/^/VMTEST-LOG\t$(basename "$log" .log)\t/" "$log"
	done
	printf 'VMTEST-DONE\t%s\n' "$n"
fi
echo "$n" >"$R/done"
sync
echo "vmtest: done" >/dev/console
echo o >/proc/sysrq-trigger
sleep 10
