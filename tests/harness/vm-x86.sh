#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# vm-x86.sh - the x86_64 VM test lane.
#
# Boots Debian's installed 6.1 amd64 kernel (or with --kernel-flavour one of
# the other supported amd64 kernels) under QEMU TCG (never KVM) with a
# busybox initramfs that mounts the host's root read-only over virtio-9p and a
# writable results share, installs the just-built modules in the guest and runs
# the VM test programs (tests/vm/<suite>/) in one boot. See docs/testing.md.
#
# usage: vm-x86.sh [--test SUITE[/PROGRAM]] [--shell] [--kver RELEASE]
#                  [--modules LIST] [--kernel VMLINUZ] [--lane NAME] [--modroot DIR]
#                  [--kernel-flavour NAME]
#   --test     run only this suite, or one program of it (repeatable)
#   --kernel-flavour  6.1 (default), 6.12 or 6.12-rt (lib.sh: AMD64_KERNELS):
#              boot that Debian kernel with the modules built for it
#              (build-kmod.sh x86_64 or x86_64-NAME); sets --kver, --kernel,
#              --modroot, --modules and the lane (x86_64-NAME) unless given
#   --shell    boot to an interactive shell in the guest instead of testing
#   --kver     kernel release to boot (default: scripts/kver.sh)
#   --kernel   kernel image (default: /boot/vmlinuz-RELEASE)
#   --modules  file listing the .ko files to install (default: build/kmod/x86_64/modules.list)
#   --lane     name of the lane in results (default x86_64)
#   --modroot  base of the kernel's installed module tree, DIR/lib/modules/RELEASE
#              (default: the host's; make modules_install INSTALL_MOD_PATH=DIR)
#   --run PROG run this one program (path on the host) instead of the suites,
#              and print its output (used by make demo)
#   --interactive  with --run: the VM's console is this terminal and the program
#              has no time limit (it opens /dev/ttyS0 itself: make demo's TUI)
#   --run-timeout SECONDS  with --run: the program's time limit (default 300)
#   --netdev SPEC  one Ethernet interface (virtio-net, eth0 in the guest) on the
#              QEMU network backend SPEC (-netdev SPEC,id=net0), e.g. a
#              datagram socket to another guest (tests/harness/vm-pair.sh)
#   --mac MAC  its MAC address (two guests on one link need two)
#   --monitor PATH  the QEMU monitor on the pipes PATH.in and PATH.out
#              (created here): `echo set_link net0 off >PATH.in`
# Environment: VMTEST_VERBOSE=1 streams the guest console; VMTEST_SMP, VMTEST_MEM;
#   VMTEST_SLOWDOWN=N multiplies every program timeout and the boot allowance
#   (a slower kernel: the debug lane); VMTEST_APPEND adds kernel parameters;
#   ADVEE_FUZZ_SCALE=ci|full the sizes of the fuzz programs (default ci: those
#   of make check; full: the goal's, make fuzz; docs/testing.md), passed to
#   the guest as VMTEST_FUZZ_SCALE.
# Exit status: 0 when every test passed (or was skipped with a reason), 1 otherwise.
set -euo pipefail
TOP=$(cd "$(dirname "$0")/../.." && pwd)
. "$TOP/scripts/lib.sh"
. "$TOP/tests/harness/lib-host.sh"

tests=() shell=0 interactive=0 kver= kernel= modules= lane= run= modbase= run_timeout=300 netdev= mac= monitor= flavour=
while [ $# -gt 0 ]; do
	case $1 in
	--test) tests+=("$2"); shift 2 ;;
	--shell) shell=1; shift ;;
	--kver) kver=$2; shift 2 ;;
	--kernel) kernel=$2; shift 2 ;;
	--modules) modules=$2; shift 2 ;;
	--lane) lane=$2; shift 2 ;;
	--modroot) modbase=$(readlink -f "$2"); shift 2 ;;
	--kernel-flavour) flavour=$2; shift 2 ;;
	--run) run=$(readlink -f "$2"); shift 2 ;;
	--interactive) interactive=1; shift ;;
	--run-timeout) run_timeout=$2; shift 2 ;;
	--netdev) netdev=$2; shift 2 ;;
	--mac) mac=$2; shift 2 ;;
	--monitor) monitor=$2; shift 2 ;;
	-h|--help) sed -n '3,41p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
	*) die "vm-x86.sh: unknown argument $1 (see --help)" ;;
	esac
done
if [ -n "$flavour" ] && [ "$flavour" != 6.1 ]; then
	flavour_kver=$kver flavour_kernel=$kernel flavour_modbase=$modbase
	amd64_kernel "$flavour"	# sets kver, vmlinuz, modbase (kdir)
	kver=${flavour_kver:-$kver} kernel=${flavour_kernel:-$vmlinuz} modbase=${flavour_modbase:-$modbase}
	modules=${modules:-$BUILD/kmod/x86_64-$flavour/modules.list}
	lane=${lane:-x86_64-$flavour}
fi
lane=${lane:-x86_64}
kver=${kver:-$("$TOP/scripts/kver.sh")}
kernel=${kernel:-/boot/vmlinuz-$kver}
modules=${modules:-$BUILD/kmod/x86_64/modules.list}
[ -r "$kernel" ] || die "no kernel image $kernel (run: make deps)"
[ -r "$modules" ] || die "no module list $modules (run: make modules${flavour:+, or scripts/build-kmod.sh x86_64-$flavour})"
# The kernel's own modules: the host's /lib/modules, or a tree given by --modroot.
kmods=$modbase/lib/modules/$kver
[ -d "$kmods" ] || die "no module tree $kmods for $kver"

case $TOP in
*[[:space:]]*) die "the repository path must not contain white space (kernel command line): $TOP" ;;
esac
vmdir=$BUILD/vm/$lane
mkdir -p "$vmdir"
# One run per lane directory at a time: a second run waits instead of
# deleting the first one's results (use --lane NAME to run side by side).
exec 9>"$vmdir/.lock"
if ! flock -n 9; then
	say "another run uses $vmdir; waiting for it"
	flock 9
fi

# --- initramfs: busybox + virtio/9p modules + /init, rebuilt when inputs change ---
initramfs=$vmdir/initramfs-$kver.cpio.gz
init_src=$TOP/tests/harness/initramfs-init-x86
if [ ! -s "$initramfs" ] || [ "$init_src" -nt "$initramfs" ] || [ "$0" -nt "$initramfs" ] || [ /bin/busybox -nt "$initramfs" ]; then
	say "initramfs for $kver"
	stage=$(mktemp -d)
	mkdir -p "$stage"/{bin,mods,proc,sys,dev,newroot}
	cp /bin/busybox "$stage/bin/busybox"
	install -m 0755 "$init_src" "$stage/init"
	: >"$stage/mods/order"	# stays empty when virtio and 9p are built in
	for m in virtio_pci 9pnet_virtio 9p; do modprobe ${modbase:+-d "$modbase"} -S "$kver" --show-depends "$m"; done |
		awk '$1 == "insmod" && !seen[$2]++ { print $2 }' | while read -r ko; do
		cp "$ko" "$stage/mods/"
		basename "$ko" >>"$stage/mods/order"
	done
	(cd "$stage" && find . | cpio -o -H newc --quiet | gzip -1) >"$initramfs.tmp"
	mv "$initramfs.tmp" "$initramfs"
	rm -rf "$stage"
fi

# --- the project's modules, installed as the guest will see them ---
# depmod runs here (about 1 s) instead of in the guest (over a minute under
# TCG on 9p); the guest overlays this tree on /lib/modules/RELEASE.
modroot=$vmdir/modroot
stage_modules "$kver" "$kmods" "$modules" "$modroot"
rm "$modroot/lib/modules/$kver/kernel"

# --- the job ---
results=$vmdir/results
rm -rf "$results"
mkdir -p "$results"
cp "$modules" "$results/modules.list"
if [ -n "$run" ]; then
	echo "main $(basename "$run" .sh) $run $([ "$interactive" = 1 ] && echo 604800 || echo "$run_timeout")" >"$results/tests.list"
else
	list_tests x86_64 "$BUILD/tests/x86_64" "$TOP" "${tests[@]}" >"$results/tests.list"
fi
slowdown=${VMTEST_SLOWDOWN:-1}
fuzz_scale=$(fuzz_scale)
if [ "$slowdown" != 1 ]; then
	awk -v f="$slowdown" '{ $4 *= f; print }' "$results/tests.list" >"$results/tests.list.tmp"
	mv "$results/tests.list.tmp" "$results/tests.list"
fi
if [ "${#tests[@]}" -gt 0 ] && [ ! -s "$results/tests.list" ]; then
	die "no VM test matches: ${tests[*]} (suites: $(ls "$TOP/tests/vm" | tr '\n' ' '))"
fi
cat >"$results/job.env" <<EOF
VMTEST_LANE=$lane
VMTEST_REPO=$TOP
VMTEST_BUILD=$BUILD
VMTEST_RESULTS=/run/vmtest
VMTEST_MODULES=/run/vmtest/modules.list
VMTEST_INSTALL_MODULES=1
VMTEST_MODROOT=$modroot/lib/modules/$kver
VMTEST_MODBASE=$modbase
VMTEST_TESTLIST=/run/vmtest/tests.list
VMTEST_SLOWDOWN=$slowdown
VMTEST_FUZZ_SCALE=$fuzz_scale
VMTEST_CONSOLE_RESULTS=0
VMTEST_SHELL=$shell
VMTEST_HOST_RESULTS=$results
EOF

# A PREEMPT_RT guest gets one CPU, as the robot has (the TS-7800's ARM926):
# there the priorities order the simulator's line (timer softirq thread)
# and the driver's threaded handler as they would on the robot. With two,
# TCG can leave the vCPU of the handler's thread unscheduled while the
# other fills the simulated FIFO: overruns no robot would see (tsuart/traffic
# lost 32 of 6912 characters at 115200 Bd, rs485proto/concurrency retried
# 22 times; with one CPU none, docs/kernels.md).
smp=${VMTEST_SMP:-$([ "$flavour" = 6.12-rt ] && echo 1 || echo 2)}
qemu=(qemu-system-x86_64 -machine pc -accel tcg -cpu "${VMTEST_CPU:-max}" -smp "$smp" -m "${VMTEST_MEM:-2048}"
	-nographic -no-reboot -nic none
	-kernel "$kernel" -initrd "$initramfs"
	-virtfs local,path=/,mount_tag=hostroot,security_model=none,readonly=on,multidevs=remap
	-virtfs "local,path=$results,mount_tag=results,security_model=none"
	-virtfs "local,path=$TOP,mount_tag=repo,security_model=none,readonly=on,multidevs=remap")
if [ -n "$netdev" ]; then
	# The guest's one NIC: this link instead of -nic none.
	nics=() prev=
	for a in "${qemu[@]}"; do
		if [ "$prev" = -nic ] && [ "$a" = none ]; then unset "nics[${#nics[@]}-1]"; else nics+=("$a"); fi
		prev=$a
	done
	qemu=("${nics[@]}" -netdev "$netdev,id=net0" -device "virtio-net-pci,netdev=net0${mac:+,mac=$mac}")
fi
if [ -n "$monitor" ]; then
	rm -f "$monitor.in" "$monitor.out"
	mkfifo "$monitor.in" "$monitor.out"
	qemu+=(-chardev "pipe,id=mon0,path=$monitor" -mon chardev=mon0,mode=readline)
fi
append="console=ttyS0 panic=-1 loglevel=5 nokaslr mitigations=off vmtest.repo=$TOP vmtest.runner=$TOP/tests/harness/guest-run.sh${VMTEST_APPEND:+ $VMTEST_APPEND}"

if [ -n "$run" ] && [ "$interactive" = 1 ]; then
	# VMTEST_HOSTFWD=PORT: the guest's TCP PORT on the host's 127.0.0.1:PORT
	# (the demo's web dashboard); user networking, no way out of the host.
	if [ -n "${VMTEST_HOSTFWD:-}" ]; then
		for i in "${!qemu[@]}"; do
			[ "${qemu[i]}" = "-nic" ] && [ "${qemu[i + 1]}" = none ] &&
				qemu[i + 1]="user,model=virtio-net-pci,restrict=on,hostfwd=tcp:127.0.0.1:$VMTEST_HOSTFWD-10.0.2.15:$VMTEST_HOSTFWD"
		done
		append+=" vmtest.hostfwd=$VMTEST_HOSTFWD"
	fi
	say "the guest's program gets this terminal; Ctrl-a x stops the VM"
	exec "${qemu[@]}" -append "$append"
fi
start=$(date +%s)
# --run: the program's output as it is written (the guest writes its log
# through the results share), not only once the VM is off.
follow=
if [ -n "$run" ]; then
	tail -n +1 -F "$results/logs/main.$(basename "$run" .sh).log" 2>/dev/null &
	follow=$!
fi
BOOT_MARK=$results/phases.txt boot_vm "$shell" $((60 * slowdown)) "$results" "$vmdir/console.log" "$append" "${qemu[@]}"
if [ -n "$follow" ]; then
	sleep 1	# tail -F polls once a second: let it print the last lines
	kill "$follow" 2>/dev/null
	wait "$follow" 2>/dev/null || true
fi
report_lane "$lane" "$results" "$vmdir/console.log" $(($(date +%s) - start))
