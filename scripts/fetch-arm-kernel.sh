#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# Fetch Debian's ARM kernel image + headers (and a static busybox for the
# armhf test initramfs) into the project's cache, without adding a foreign
# architecture to dpkg: apt runs with a private lists dir, an empty dpkg
# status and only the Debian sources of this machine.
#
# usage: scripts/fetch-arm-kernel.sh DEBARCH FLAVOUR   e.g. armhf armmp, armel marvell,
#        armel rpi (the armel lane's kernel: QEMU has no Kirkwood/Orion machine)
# prints the root of the extracted tree (contains usr/src/linux-headers-*,
# lib/modules/*, boot/vmlinuz-*). The architecture's build flavour (lib.sh:
# arm_flavour) lives in $ADVEE_CACHE/arm/DEBARCH, another one in
# $ADVEE_CACHE/arm/DEBARCH-FLAVOUR.
set -euo pipefail

debarch=${1:?debian architecture (armhf|armel)}
flavour=${2:?kernel flavour (armmp|marvell|rpi)}
. "$(dirname "$0")/lib.sh"
cache=$ADVEE_CACHE/arm/$debarch
[ "$flavour" = "$(arm_flavour "$debarch")" ] || cache=$cache-$flavour
mkdir -p "$cache/debs"
private_apt "$cache" "$debarch"

# The host's kbuild (amd64, Multi-Arch: foreign) builds for every architecture;
# prefer the ARM kernel of exactly that version so the tools match.
host_kbuild=$(dpkg-query -W -f='${Version}' linux-kbuild-6.1 2>/dev/null || true)

stamp="$cache/extracted.stamp"
link_kbuild() {
	# The flavour's headers include the -common tree by absolute path and link
	# scripts/tools to the host's kbuild: re-point both into this tree, with a
	# modpost built for this target (see cross-modpost.sh).
	local hdr common scripts l
	hdr=$(ls -d "$cache"/root/usr/src/linux-headers-*-"$flavour")
	common=$(ls -d "$cache"/root/usr/src/linux-headers-*-common)
	printf 'include %s/Makefile\n' "$common" >"$hdr/Makefile"
	if [ ! -x "$cache/kbuild/scripts/mod/modpost" ]; then
		"$(dirname "$0")/cross-modpost.sh" "$hdr" "$(case $debarch in armhf) echo arm-linux-gnueabihf- ;; *) echo arm-linux-gnueabi- ;; esac)" \
			"$cache/kbuild" >/dev/null
	fi
	scripts=$cache/kbuild/scripts
	for l in "$hdr/scripts" "$common/scripts"; do
		[ "$(readlink "$l" 2>/dev/null)" = "$scripts" ] || { rm -rf "$l"; ln -s "$scripts" "$l"; }
	done
	for l in "$hdr/tools" "$common/tools"; do
		[ -L "$l" ] && [ "$(readlink "$l")" = /usr/lib/linux-kbuild-6.1/tools ] ||
			{ rm -rf "$l"; ln -s /usr/lib/linux-kbuild-6.1/tools "$l"; }
	done
}
if [ -f "$stamp" ] && [ -d "$cache/root/lib/modules" ]; then
	link_kbuild
	echo "$cache/root"
	exit 0
fi

# One source failing (a security index out of sync) must not stop us when the
# main archive answered; what follows checks for the packages themselves.
apt-get "${apt_opts[@]}" update >"$cache/update.log" 2>&1 ||
	echo "fetch-arm-kernel: apt-get update reported errors (see $cache/update.log); continuing" >&2

meta=linux-image-$flavour
abi=$(apt-cache "${apt_opts[@]}" depends "$meta" 2>/dev/null |
	sed -n "s/.*Depends: linux-image-\(6\.1\.0-[0-9]*\)-$flavour.*/\1/p" | sort -V | tail -1)
[ -n "$abi" ] || { echo "fetch-arm-kernel: cannot resolve $meta for $debarch" >&2; exit 1; }
img=linux-image-$abi-$flavour
# Debian sometimes ships the unsigned image under an -unsigned name.
if ! apt-cache "${apt_opts[@]}" show "$img" >/dev/null 2>&1; then
	img=linux-image-$abi-$flavour-unsigned
fi
ver=$(apt-cache "${apt_opts[@]}" show "$img" | sed -n 's/^Version: //p' | sort -V | tail -1)
pkgs=("$img=$ver" "linux-headers-$abi-$flavour=$ver" "linux-headers-$abi-common=$ver")
# The flavours a VM lane boots get a static busybox for its initramfs.
case $debarch-$flavour in armhf-armmp|armel-rpi) pkgs+=(busybox-static) ;; esac

# Debian's headers depend on linux-kbuild-6.1 (>= their version): a newer host
# kbuild of the same 6.1 series is what Debian itself accepts.
if [ -z "$host_kbuild" ] || dpkg --compare-versions "$host_kbuild" lt "$ver"; then
	echo "fetch-arm-kernel: $debarch kernel is $ver, host linux-kbuild-6.1 is ${host_kbuild:-missing}; installing $ver" >&2
	DEBIAN_FRONTEND=noninteractive apt-get install -y -q "linux-kbuild-6.1=$ver" >&2 || {
		echo "fetch-arm-kernel: linux-kbuild-6.1=$ver is not installable on the host" >&2; exit 1; }
fi

(cd "$cache/debs" && apt-get "${apt_opts[@]}" download "${pkgs[@]}" >"$cache/download.log" 2>&1) || {
	echo "fetch-arm-kernel: download failed:" >&2; tail -5 "$cache/download.log" >&2; exit 1; }

rm -rf "$cache/root"
mkdir -p "$cache/root"
for deb in "$cache"/debs/*.deb; do
	dpkg-deb -x "$deb" "$cache/root"
done

link_kbuild
echo "$abi-$flavour" > "$cache/kernelrelease"
touch "$stamp"
echo "$cache/root"
