#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# build-kmod-stock.sh TARGET: the kernel's own test modules that the VM suites
# load but the target's Debian kernel config leaves out (armmp has no
# i2c-stub, which the max6615 suite puts its chip on), built from Debian's
# linux-source-6.1 (scripts/kernel-source.sh) as out-of-tree modules against
# the target's headers. They are never installed on the robot.
# Output: build/kmod/TARGET-stock/modules.list (one .ko per line; empty when
# the kernel has them all).
set -euo pipefail
. "$(dirname "$0")/lib.sh"

target=${1:?target (armhf|armel)}
kdir=$(cat "$BUILD/kmod/$target/kdir" 2>/dev/null) || die "build the project's modules for $target first (scripts/build-kmod.sh $target)"
config=$kdir/.config
[ -r "$config" ] || die "no kernel config at $config"

# CONFIG symbol, then the source file in the kernel tree.
wanted="CONFIG_I2C_STUB drivers/i2c/i2c-stub.c"
out=$BUILD/kmod/$target-stock
mkdir -p "$out"
srcs=()
while read -r sym src; do
	grep -Eq "^$sym=[ym]$" "$config" || srcs+=("$src")
done <<<"$wanted"
if [ "${#srcs[@]}" -eq 0 ]; then
	: >"$out/modules.list"
	exit 0
fi
ksrc=$("$TOP/scripts/kernel-source.sh" "${srcs[@]}")
: >"$out/Kbuild"
for src in "${srcs[@]}"; do
	cp -p "$ksrc/$src" "$out/"
	echo "obj-m += $(basename "$src" .c).o" >>"$out/Kbuild"
done
say "kernel test modules missing from the $target kernel: ${srcs[*]##*/}"
make -C "$kdir" M="$out" ARCH=arm CROSS_COMPILE="$(cross_prefix "$target")" -j"$(nproc)" modules \
	>"$out/build.log" 2>&1 || { cat "$out/build.log" >&2; die "build of ${srcs[*]} for $target failed"; }
for src in "${srcs[@]}"; do echo "$out/$(basename "$src" .c).ko"; done >"$out/modules.list"
