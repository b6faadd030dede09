#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# vm-arm.sh - the ARM VM test lane.
#
# Boots Debian's armhf armmp kernel on qemu-system-arm -M virt (TCG) with an
# initramfs that holds busybox, Debian's armhf tools the tests call
# (scripts/fetch-arm-userland.sh), the cross-built modules with the depmod
# output of the whole kernel tree and the statically linked test programs of
# the suites marked portable=1. The kernel's own module tree and the
# repository (shell programs) come over virtio-9p, read-only; results come back
# over the serial console.
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
case $TOP in
*[[:space:],]*) die "the repository path must not contain white space or commas (qemu -virtfs): $TOP" ;;
esac
userland=$("$TOP/scripts/fetch-arm-userland.sh" armhf)
"$TOP/scripts/build-kmod-stock.sh" armhf

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

# Modules: ours (and the kernel's test modules the armmp config lacks:
# build-kmod-stock.sh) under extra/ with the depmod output of the whole tree;
# the kernel's own tree comes over 9p (/init mounts it on kernel/), except
# what /init loads to mount it.
full=$vmdir/modtree
cat "$modules" "$BUILD/kmod/armhf-stock/modules.list" >"$vmdir/staged-modules.list"
stage_modules "$kver" "$root/lib/modules/$kver" "$vmdir/staged-modules.list" "$full"
mdir=$stage/lib/modules/$kver
mkdir -p "$mdir"
cp -r "$full/lib/modules/$kver"/{modules.*,extra} "$mdir/"
: >"$results/modules.list"
while read -r ko; do echo "$(basename "$ko" .ko)" >>"$results/modules.list"; done <"$modules"
for m in virtio_mmio 9pnet_virtio 9p; do
	modprobe -d "$full" -S "$kver" --show-depends "$m" | awk '$1 == "insmod" { print $2 }'
done | sort -u | while read -r path; do
	rel=${path#"$full/lib/modules/$kver/"}
	mkdir -p "$mdir/$(dirname "$rel")"
	cp -L "$path" "$mdir/$rel"
done

# Programs of the portable suites: the C ones in the initramfs, the shell
# ones from the repository share.
# TCG emulates this 32-bit guest slower than the x86_64 one (tsuart/traffic:
# 158 s there, over 600 s here), so the per-program timeouts (hang guards)
# are multiplied by VMTEST_SLOWDOWN, 2 unless set.
list_tests "$lane" /tests /repo "${tests[@]}" |
	awk -v f="${VMTEST_SLOWDOWN:-2}" '{ $4 *= f; print }' >"$results/tests.list"
if [ "${#tests[@]}" -gt 0 ] && [ ! -s "$results/tests.list" ]; then
	die "no portable VM test matches: ${tests[*]}"
fi
while read -r suite prog path limit; do
	case $path in /tests/*) ;; *) continue ;; esac
	mkdir -p "$stage/tests/$suite"
	cp "$BUILD/tests/armhf/$suite/$prog" "$stage/tests/$suite/$prog" ||
		die "test program $suite/$prog was not cross-built (run: scripts/build-testprogs.sh armhf)"
done <"$results/tests.list"
cp "$results/modules.list" "$results/tests.list" "$stage/vmtest/"
cat >"$stage/vmtest/job.env" <<JOB
VMTEST_LANE=$lane
VMTEST_REPO=/repo
VMTEST_BUILD=/tests
VMTEST_RESULTS=/run/vmtest
VMTEST_MODULES=/vmtest/modules.list
VMTEST_INSTALL_MODULES=0
VMTEST_TESTLIST=/vmtest/tests.list
VMTEST_CONSOLE_RESULTS=1
JOB
# The initramfs: the userland archive (built once per userland, shared by
# the lanes) followed by this run's archive; the kernel unpacks both.
userland_cpio=$BUILD/vm/userland-armhf.cpio.gz
if [ ! -s "$userland_cpio" ] || [ "$userland/.advee-packages" -nt "$userland_cpio" ]; then
	(cd "$userland" && find . ! -name .advee-packages | cpio -o -H newc --quiet -R 0:0 | gzip -1) >"$userland_cpio.$$"
	mv "$userland_cpio.$$" "$userland_cpio"
fi
initramfs=$vmdir/initramfs.cpio.gz
{
	cat "$userland_cpio"
	(cd "$stage" && find . | cpio -o -H newc --quiet -R 0:0 | gzip -1)
} >"$initramfs"

qemu=(qemu-system-arm -M virt -cpu cortex-a15 -smp "${VMTEST_SMP:-2}" -m "${VMTEST_MEM:-1024}"
	-nographic -no-reboot -nic none -kernel "$kernel" -initrd "$initramfs"
	-fsdev "local,id=kmods,path=$root/lib/modules/$kver/kernel,security_model=none,readonly=on"
	-device virtio-9p-device,fsdev=kmods,mount_tag=kmods
	-fsdev "local,id=repo,path=$TOP,security_model=none,readonly=on,multidevs=remap"
	-device virtio-9p-device,fsdev=repo,mount_tag=repo)
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
