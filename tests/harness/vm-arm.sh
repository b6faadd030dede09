#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# vm-arm.sh - the ARM VM test lanes.
#
# --arch armhf (the default): Debian's armhf armmp kernel on qemu-system-arm
# -M virt (TCG, Cortex-A15, two CPUs). The kernel's own module tree and the
# repository (shell programs) come over virtio-9p, read-only.
# --arch armel: Debian's armel rpi kernel (ARMv6, the armel ABI of the
# robot's ARMv5TE; QEMU has no machine for the marvell kernel,
# docs/kernels.md) on -M raspi0 (ARM1176, one CPU, 512 MB). That machine has
# no virtio: the kernel's module tree is an ext4 image on the SD card and the
# repository is in the initramfs.
# Both: an initramfs with busybox, Debian's tools of that architecture the
# tests call (scripts/fetch-arm-userland.sh), the cross-built modules with the
# depmod output of the whole kernel tree and the statically linked test
# programs of the suites marked portable=1; results come back over the serial
# console.
#
# --cxx (armel): instead of the kernel suites, the C++ unit tests
# (GoogleTest binaries of scripts/build-userland.sh armel-tests, each test a
# TAP point through gtest-tap.sh; lane armel-cxx), with the build tree, the
# repository and Debian's armel libraries at their host paths.
#
# usage: vm-arm.sh [--arch armhf|armel] [--test SUITE[/PROGRAM]] [--cxx] [--shell] [--lane NAME]
# Environment: VMTEST_VERBOSE=1 streams the guest console.
set -euo pipefail
TOP=$(cd "$(dirname "$0")/../.." && pwd)
. "$TOP/scripts/lib.sh"
. "$TOP/tests/harness/lib-host.sh"

tests=() shell=0 lane= arch=armhf cxx=0
while [ $# -gt 0 ]; do
	case $1 in
	--arch) arch=$2; shift 2 ;;
	--test) tests+=("$2"); shift 2 ;;
	--lane) lane=$2; shift 2 ;;
	--shell) shell=1; shift ;;
	--cxx) cxx=1; shift ;;
	-h|--help) sed -n '3,26p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
	*) die "vm-arm.sh: unknown argument $1 (see --help)" ;;
	esac
done
# kmod: the build target of the modules (build-kmod.sh); progs: of the test
# programs (build-testprogs.sh); media: how the kernel's module tree gets in.
case $arch in
armhf) kmod=armhf progs=armhf media=9p ;;
armel) kmod=armel-rpi progs=armel media=sd ;;
*) die "vm-arm.sh: --arch armhf or armel, not $arch" ;;
esac
[ "$cxx" = 0 ] || [ "$arch" = armel ] || die "vm-arm.sh: --cxx is for --arch armel"
if [ "$cxx" = 1 ]; then lane=${lane:-$arch-cxx}; else lane=${lane:-$arch}; fi

root=$(arm_tree "$arch" "$(arm_target_flavour "$kmod")")
kver=$(cat "$(dirname "$root")/kernelrelease")
kernel=$root/boot/vmlinuz-$kver
modules=$BUILD/kmod/$kmod/modules.list
[ -r "$kernel" ] || die "no $arch kernel at $kernel"
[ -r "$modules" ] || die "no $kmod module list (run: scripts/build-kmod.sh $kmod)"
case $TOP in
*[[:space:],]*) die "the repository path must not contain white space or commas (qemu -virtfs): $TOP" ;;
esac
userland=$("$TOP/scripts/fetch-arm-userland.sh" "$arch")
"$TOP/scripts/build-kmod-stock.sh" "$kmod"

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
# No 9p on raspi0: the repository (5 MB without build/) goes in the initramfs.
if [ "$media" = sd ]; then
	rsync -a --exclude=/build/ --exclude=/.git --exclude=/.cache/ "$TOP/" "$stage/repo/"
fi

# Modules: ours (and the kernel's test modules its config lacks:
# build-kmod-stock.sh) under extra/ with the depmod output of the whole tree;
# the kernel's own tree comes over 9p or on the SD card (/init mounts it on
# kernel/), except what /init loads to mount it.
full=$vmdir/modtree
cat "$modules" "$BUILD/kmod/$kmod-stock/modules.list" >"$vmdir/staged-modules.list"
stage_modules "$kver" "$root/lib/modules/$kver" "$vmdir/staged-modules.list" "$full"
mdir=$stage/lib/modules/$kver
mkdir -p "$mdir"
cp -r "$full/lib/modules/$kver"/{modules.*,extra} "$mdir/"
: >"$results/modules.list"
while read -r ko; do echo "$(basename "$ko" .ko)" >>"$results/modules.list"; done <"$modules"
case $media in
9p) boot_modules="virtio_mmio 9pnet_virtio 9p" ;;
sd) boot_modules="crc32c_generic ext4" ;;
esac
for m in $boot_modules; do
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
if [ "$cxx" = 1 ]; then
	# The C++ unit tests: every GoogleTest binary of the armel-tests build,
	# run in its build directory at the host's path (tests read their config
	# directories and start programs by the absolute paths CMake gave them).
	cxxdir=$BUILD/userland-armel-tests
	[ -f "$cxxdir/build.ninja" ] || die "no armel C++ tests (run: scripts/build-userland.sh armel-tests)"
	mkdir -p "$stage/vmtest/cxx" "$stage$cxxdir" "$stage$TOP"
	rsync -a --exclude=/build/ --exclude=/.git --exclude=/.cache/ "$TOP/" "$stage$TOP/"
	(cd "$cxxdir" && find . -name CMakeFiles -prune -o -type f -perm /111 -print) | while read -r f; do
		head -c 4 "$cxxdir/$f" | grep -q ELF || continue
		mkdir -p "$stage$cxxdir/$(dirname "$f")"
		cp "$cxxdir/$f" "$stage$cxxdir/$f"
		case $f in
		*_tests)
			t=$(basename "$f")
			printf '#!/bin/sh\nexec /vmtest/gtest-tap.sh %s\n' "$cxxdir/${f#./}" >"$stage/vmtest/cxx/$t"
			chmod +x "$stage/vmtest/cxx/$t"
			echo "cxx $t /vmtest/cxx/$t $((600 * ${VMTEST_SLOWDOWN:-2}))" ;;
		esac
	done | sort >"$results/tests.list"
	install -m 0755 "$TOP/tests/harness/gtest-tap.sh" "$stage/vmtest/"
	# Debian's armel libraries they link, and the cross toolchain's C++ runtime.
	sysroot=$("$TOP/scripts/fetch-arm-sysroot.sh" armel)
	for d in lib/arm-linux-gnueabi usr/lib/arm-linux-gnueabi; do
		mkdir -p "$stage/$d"
		[ -d "$sysroot/$d" ] || continue
		(cd "$sysroot/$d" && find . -maxdepth 1 -name '*.so.*' -print0 | xargs -0 -r cp -a -t "$stage/$d/")
	done
	cp -a /usr/arm-linux-gnueabi/lib/libstdc++.so.6* /usr/arm-linux-gnueabi/lib/libgcc_s.so.1 \
		"$stage/usr/lib/arm-linux-gnueabi/"
else
	list_tests "$lane" /tests /repo "${tests[@]}" |
		awk -v f="${VMTEST_SLOWDOWN:-2}" '{ $4 *= f; print }' >"$results/tests.list"
	if [ "${#tests[@]}" -gt 0 ] && [ ! -s "$results/tests.list" ]; then
		die "no portable VM test matches: ${tests[*]}"
	fi
fi
while read -r suite prog path limit; do
	case $path in /tests/*) ;; *) continue ;; esac
	mkdir -p "$stage/tests/$suite"
	cp "$BUILD/tests/$progs/$suite/$prog" "$stage/tests/$suite/$prog" ||
		die "test program $suite/$prog was not cross-built (run: scripts/build-testprogs.sh $progs)"
done <"$results/tests.list"
cp "$results/modules.list" "$results/tests.list" "$stage/vmtest/"
fuzz_scale=$(fuzz_scale)
cat >"$stage/vmtest/job.env" <<JOB
VMTEST_LANE=$lane
VMTEST_REPO=/repo
VMTEST_BUILD=/tests
VMTEST_RESULTS=/run/vmtest
VMTEST_MODULES=/vmtest/modules.list
VMTEST_INSTALL_MODULES=0
VMTEST_TESTLIST=/vmtest/tests.list
VMTEST_CONSOLE_RESULTS=1
VMTEST_FUZZ_SCALE=$fuzz_scale
JOB
# The initramfs: the userland archive (built once per userland, shared by
# the lanes) followed by this run's archive; the kernel unpacks both.
userland_cpio=$BUILD/vm/userland-$arch.cpio.gz
if [ ! -s "$userland_cpio" ] || [ "$userland/.advee-packages" -nt "$userland_cpio" ]; then
	(cd "$userland" && find . ! -name .advee-packages | cpio -o -H newc --quiet -R 0:0 | gzip -1) >"$userland_cpio.$$"
	mv "$userland_cpio.$$" "$userland_cpio"
fi
initramfs=$vmdir/initramfs.cpio.gz
{
	cat "$userland_cpio"
	(cd "$stage" && find . | cpio -o -H newc --quiet -R 0:0 | gzip -1)
} >"$initramfs"

case $media in
9p)
	qemu=(qemu-system-arm -M virt -cpu cortex-a15 -smp "${VMTEST_SMP:-2}" -m "${VMTEST_MEM:-1024}"
		-nographic -no-reboot -nic none -kernel "$kernel" -initrd "$initramfs"
		-fsdev "local,id=kmods,path=$root/lib/modules/$kver/kernel,security_model=none,readonly=on"
		-device virtio-9p-device,fsdev=kmods,mount_tag=kmods
		-fsdev "local,id=repo,path=$TOP,security_model=none,readonly=on,multidevs=remap"
		-device virtio-9p-device,fsdev=repo,mount_tag=repo)
	append="console=ttyAMA0 panic=-1 loglevel=5" ;;
sd)
	# QEMU 7.2's raspi0 has no BCM2835 power-management ASB block: the
	# kernel's bcm2835-power driver, which the DT's "asb" registers bring in,
	# dies on an external abort there (docs/kernels.md). The DT without them
	# keeps the PM block's watchdog and drops the power domains.
	dtb=$vmdir/bcm2835-rpi-zero.dtb
	cp "$root/usr/lib/linux-image-$kver/bcm2835-rpi-zero.dtb" "$dtb"
	fdtput -t x "$dtb" /soc/watchdog@7e100000 reg 0x7e100000 0x114
	fdtput -t s "$dtb" /soc/watchdog@7e100000 reg-names pm
	# The kernel's module tree on the SD card (QEMU wants a power-of-two
	# size), read-only for the guest (snapshot=on: writes stay in QEMU).
	sd=$BUILD/vm/kmods-$kver.img
	if [ ! -s "$sd" ] || [ "$root/lib/modules/$kver/kernel" -nt "$sd" ]; then
		size=$(du -sm "$root/lib/modules/$kver/kernel" | cut -f1)
		mb=64
		while [ "$mb" -lt $((size * 3 / 2 + 16)) ]; do mb=$((mb * 2)); done
		rm -f "$sd.$$"
		truncate -s "${mb}M" "$sd.$$"
		mke2fs -q -F -t ext4 -L kmods -d "$root/lib/modules/$kver/kernel" "$sd.$$" ||
			die "cannot make the module tree's SD image"
		mv "$sd.$$" "$sd"
	fi
	qemu=(qemu-system-arm -M raspi0 -nographic -no-reboot -kernel "$kernel" -dtb "$dtb"
		-initrd "$initramfs" -drive "file=$sd,if=sd,format=raw,snapshot=on")
	# Virtual time from the instruction count (-icount; VMTEST_ICOUNT=0: off):
	# without it the guest went idle for good in tsuart/traffic and the C++
	# tests, and timing checks failed under host load (docs/kernels.md).
	[ "${VMTEST_ICOUNT:-1}" = 1 ] && qemu+=(-icount shift=auto,sleep=on)
	# raspi0 has no RTC: /init sets the host's time (tests compare with it).
	append="console=ttyAMA0 panic=-1 loglevel=5 vmtest.media=sd vmtest.date=$(date +%s)" ;;
esac
[ "$shell" = 1 ] && append="$append vmtest.shell=1"
start=$(date +%s)
watch=
if [ "$media" = sd ] && [ "$shell" = 0 ]; then
	# raspi0 cannot reset (QEMU has no BCM2835 PM watchdog): after a panic
	# the kernel prints "Reboot failed -- System halted" and the guest would
	# hold the lane for its whole budget. Stop it there.
	rm -f "$vmdir/console.log"
	(
		while sleep 5; do
			if grep -q 'Reboot failed -- System halted' "$vmdir/console.log" 2>/dev/null; then
				echo "VMTEST-HOST: the guest halted (raspi0 cannot reboot after a panic); stopped" >"$vmdir/console.log.boot"
				[ -s "$vmdir/console.log.pid" ] && kill "$(cat "$vmdir/console.log.pid")" 2>/dev/null
				break
			fi
		done
	) &
	watch=$!
fi
boot_vm "$shell" 90 "$results" "$vmdir/console.log" "$append" "${qemu[@]}"
if [ -n "$watch" ]; then
	kill "$watch" 2>/dev/null || true
	wait "$watch" 2>/dev/null || true
fi

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
