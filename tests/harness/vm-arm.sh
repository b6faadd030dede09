#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# vm-arm.sh - the ARM VM test lane.
#
# Boots Debian's armhf armmp kernel on qemu-system-arm -M virt (TCG) with an
# initramfs that holds busybox, the cross-built modules (plus the in-tree
# modules they depend on) and the statically linked test programs of the
# suites marked portable=1; results come back over the serial console.
#
# usage: vm-arm.sh [--test SUITE[/PROGRAM]] [--shell] [--lane NAME]
# Environment: VMTEST_VERBOSE=1 streams the guest console.
set -euo pipefail
TOP=$(cd "$(dirname "$0")/../.." && pwd)
. "$TOP/scripts/lib.sh"
. "$TOP/tests/harness/lib-host.sh"

tests=() shell=0 lane=armhf
while [ $# -gt 0 ]; do
	case $1 in
	--test) tests+=("$2"); shift 2 ;;
	--lane) lane=$2; shift 2 ;;
	--shell) shell=1; shift ;;
	-h|--help) sed -n '3,13p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
	*) die "vm-arm.sh: unknown argument $1 (see --help)" ;;
	esac
done

root=$(arm_tree armhf armmp)
kver=$(cat "$(dirname "$root")/kernelrelease")
kernel=$root/boot/vmlinuz-$kver
modules=$BUILD/kmod/armhf/modules.list
[ -r "$kernel" ] || die "no armhf kernel at $kernel"
[ -r "$modules" ] || die "no armhf module list (run: scripts/build-kmod.sh armhf)"

vmdir=$BUILD/vm/$lane
mkdir -p "$vmdir"
# One run per lane directory at a time: a second run waits instead of
# deleting the first one's results (use --lane NAME to run side by side).
exec 9>"$vmdir/.lock"
if ! flock -n 9; then
	say "another run uses $vmdir; waiting for it"
	flock 9
fi
results=$vmdir/results
rm -rf "$vmdir/initramfs" "$results"
mkdir -p "$results"
stage=$vmdir/initramfs
mkdir -p "$stage"/{bin,vmtest,tests,proc,sys,dev,run,tmp,root}
cp "$root/bin/busybox" "$stage/bin/busybox"
install -m 0755 "$TOP/tests/harness/initramfs-init-arm" "$stage/init"
cp "$TOP/tests/harness/guest-run.sh" "$stage/vmtest/"

# Modules: ours under extra/, plus every in-tree module they need, then depmod.
full=$vmdir/modtree
stage_modules "$kver" "$root/lib/modules/$kver" "$modules" "$full"
mdir=$stage/lib/modules/$kver
mkdir -p "$mdir"
cp "$root/lib/modules/$kver"/modules.{order,builtin,builtin.modinfo} "$mdir/"
: >"$results/modules.list"
while read -r ko; do
	name=$(basename "$ko" .ko)
	echo "$name" >>"$results/modules.list"
	modprobe -d "$full" -S "$kver" --show-depends "$name" | awk '$1 == "insmod" { print $2 }'
done <"$modules" | sort -u | while read -r path; do
	rel=${path#"$full/lib/modules/$kver/"}
	mkdir -p "$mdir/$(dirname "$rel")"
	cp -L "$path" "$mdir/$rel"
done
depmod -b "$stage" "$kver"

# Programs of the portable suites.
list_tests "$lane" /tests "${tests[@]}" >"$results/tests.list"
if [ "${#tests[@]}" -gt 0 ] && [ ! -s "$results/tests.list" ]; then
	die "no portable VM test matches: ${tests[*]}"
fi
while read -r suite prog path limit; do
	mkdir -p "$stage/tests/$suite"
	cp "$BUILD/tests/armhf/$suite/$prog" "$stage/tests/$suite/$prog" ||
		die "test program $suite/$prog was not cross-built (run: scripts/build-testprogs.sh armhf)"
done <"$results/tests.list"
cp "$results/modules.list" "$results/tests.list" "$stage/vmtest/"
cat >"$stage/vmtest/job.env" <<JOB
VMTEST_LANE=$lane
VMTEST_REPO=/vmtest
VMTEST_BUILD=/tests
VMTEST_RESULTS=/run/vmtest
VMTEST_MODULES=/vmtest/modules.list
VMTEST_INSTALL_MODULES=0
VMTEST_TESTLIST=/vmtest/tests.list
VMTEST_CONSOLE_RESULTS=1
JOB
initramfs=$vmdir/initramfs.cpio.gz
(cd "$stage" && find . | cpio -o -H newc --quiet -R 0:0 | gzip -1) >"$initramfs"

qemu=(qemu-system-arm -M virt -cpu cortex-a15 -smp "${VMTEST_SMP:-2}" -m "${VMTEST_MEM:-1024}"
	-nographic -no-reboot -nic none -kernel "$kernel" -initrd "$initramfs")
append="console=ttyAMA0 panic=-1 loglevel=5"
[ "$shell" = 1 ] && append="$append vmtest.shell=1"
start=$(date +%s)
boot_vm "$shell" 90 "$results" "$vmdir/console.log" "$append" "${qemu[@]}"

# Rebuild the result files from the console.
console=$vmdir/console.log
tr -d '\r' <"$console" >"$console.clean"
mkdir -p "$results/logs"
awk -F'\t' -v r="$results" '
	$1 == "VMTEST-RESULT" { sub(/^VMTEST-RESULT\t/, ""); print > (r "/results.tsv") }
	$1 == "VMTEST-TAP"    { sub(/^VMTEST-TAP\t/, ""); print > (r "/tap.txt") }
	$1 == "VMTEST-DMESG"  { sub(/^VMTEST-DMESG\t/, ""); print > (r "/dmesg.txt") }
	$1 == "VMTEST-LOG"    { f = r "/logs/" $2 ".log"; sub(/^VMTEST-LOG\t[^\t]*\t/, ""); print > f }
	$1 == "VMTEST-CURRENT" { print $2 > (r "/current"); close(r "/current") }
	$1 == "VMTEST-DONE"   { print $2 > (r "/done") }' "$console.clean"
report_lane "$lane" "$results" "$console.clean" $(($(date +%s) - start))
