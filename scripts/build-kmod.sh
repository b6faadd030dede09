#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# build-kmod.sh TARGET [KDIR]: build every module of the project's Kbuild tree
# with W=1 for one target kernel. TARGET is x86_64 (KDIR defaults to Debian's
# 6.1 amd64 headers), x86_64-6.12 or x86_64-6.12-rt (bookworm-backports'
# headers; lib.sh: amd64_kernel), armhf (armmp), armel (marvell), armel-rpi
# (armel's rpi kernel, booted by the armel VM lane), debug-6.12-rt
# or debug-6.1 (the debug lane's kernel: scripts/debug-kernel.sh builds or
# finds it) or any name with an explicit KDIR. The sources are mirrored into
# build/kmod/TARGET so that targets never share objects; a compiler warning
# fails the build (W=1 must be clean).
# Output: build/kmod/TARGET/modules.list, one .ko path per line.
set -euo pipefail
. "$(dirname "$0")/lib.sh"

target=${1:?target}
kdir=${2:-}
make_args=(W=1)
case $target in
x86_64|x86_64-*)
	# amd64_kernel sets kdir (and kver, vmlinuz, modbase).
	[ -n "$kdir" ] || amd64_kernel "$(amd64_kernel_of "$target")"
	;;
debug-6.12-rt|debug-6.1)
	[ -n "$kdir" ] || kdir=$("$TOP/scripts/debug-kernel.sh" "${target#debug-}")/build
	;;
armhf|armel|armel-rpi)
	flavour=$(arm_target_flavour "$target")
	root=$(arm_tree "${target%%-*}" "$flavour")
	kdir=${kdir:-$(ls -d "$root"/usr/src/linux-headers-*-"$flavour" | head -1)}
	make_args+=(ARCH=arm CROSS_COMPILE="$(cross_prefix "$target")")
	;;
*)
	[ -n "$kdir" ] || die "target $target needs an explicit KDIR"
	;;
esac
[ -f "$kdir/Makefile" ] || die "no kernel build tree at $kdir (run: make deps)"
# Debian's header packages lack the SJA1000 core's private header that
# ts7800-can/sja1000-layout.c checks our copy of struct sja1000_priv against:
# take it from linux-source-6.1 or -6.12, the source of those kernels.
case $target in
x86_64|armhf|armel|armel-rpi)
	make_args+=(SJA1000_SRC="$("$TOP/scripts/kernel-source.sh" drivers/net/can/sja1000/sja1000.h)")
	;;
x86_64-6.12*)
	make_args+=(SJA1000_SRC="$("$TOP/scripts/kernel-source.sh" 6.12 drivers/net/can/sja1000/sja1000.h)")
	;;
esac

out=$BUILD/kmod/$target
mkdir -p "$out"
# rsync flattens the listed dirs; rebuild the tree layout explicitly.
for d in $KSRC_DIRS; do
	mkdir -p "$out/$d"
	rsync -a --delete --include='*/' --include='*.[ch]' --include='Kbuild' --include='*.S' \
		--exclude='*' "$TOP/$d/" "$out/$d/"
done
cp -p "$TOP/Kbuild" "$out/Kbuild"

say "kernel modules for $target ($kdir)"
log=$out/build.log
if ! make -C "$kdir" M="$out" "${make_args[@]}" ${V:+V=$V} -j"$(nproc)" modules >"$log" 2>&1; then
	cat "$log" >&2
	die "module build for $target failed"
fi
# Warnings from our sources (not from the headers' own tooling notes) fail W=1.
if grep -E '(warning|error):' "$log" | grep -v 'Skipping BTF generation' >&2; then
	die "module build for $target has warnings (W=1 must be clean); full log: $log"
fi
# modules.order holds paths relative to M= or absolute ones, depending on the kbuild.
sed "s|\.o$|.ko|; \|^/|!s|^|$out/|" "$out/modules.order" > "$out/modules.list"
echo "$kdir" > "$out/kdir"
while read -r ko; do printf '    %s\n' "${ko#"$out"/}" >&2; done < "$out/modules.list"
