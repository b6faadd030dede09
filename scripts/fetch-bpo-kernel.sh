#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# Fetch Debian's 6.12 amd64 kernels from bookworm-backports (the stock
# flavour and the PREEMPT_RT one: images, headers, their -common trees and
# the matching linux-kbuild) into the project's cache, with a private apt
# (lib.sh: private_apt; nothing is installed on this machine). The modules
# are built against these headers and the x86_64 VM lane boots these images
# (--kernel-flavour 6.12 / 6.12-rt), and linux-source-6.12.
#
# usage: scripts/fetch-bpo-kernel.sh
# prints the root of the extracted tree: usr/src/linux-headers-RELEASE,
# lib/modules/RELEASE (with depmod's index), boot/vmlinuz-RELEASE,
# usr/src/linux-source-6.12.tar.xz, and
# release-amd64 / release-rt-amd64 holding the two RELEASEs.
set -euo pipefail
. "$(dirname "$0")/lib.sh"

cache=$ADVEE_CACHE/bpo/amd64
root=$cache/root
stamp=$cache/extracted.stamp
if [ -f "$stamp" ]; then
	echo "$root"
	exit 0
fi
# Two builds may ask at once (make gates, the VM lanes): one fetches.
mkdir -p "$cache/debs"
exec 8>"$cache/.lock"
flock 8
[ -f "$stamp" ] && { echo "$root"; exit 0; }

private_apt "$cache" amd64 bookworm-backports
apt-get "${apt_opts[@]}" update >"$cache/update.log" 2>&1 ||
	die "apt-get update of bookworm-backports failed (see $cache/update.log)"

# The ABI the metapackages point at, e.g. 6.12.95+deb12.
abi=$(apt-cache "${apt_opts[@]}" depends linux-image-amd64 2>/dev/null |
	sed -n 's/.*Depends: linux-image-\(6\.12\.[0-9]*+deb12\)-amd64.*/\1/p' | sort -V | tail -1)
[ -n "$abi" ] || die "bookworm-backports has no linux-image-6.12.*+deb12-amd64"
pkgs=()
for flavour in amd64 rt-amd64; do
	img=linux-image-$abi-$flavour
	# The signed image, or the same kernel under its -unsigned name.
	apt-cache "${apt_opts[@]}" show "$img" >/dev/null 2>&1 || img=$img-unsigned
	pkgs+=("$img" "linux-headers-$abi-$flavour")
done
# linux-source-6.12: checkpatch.pl and the private headers that
# ts7800-can checks its struct copy against (kernel-source.sh 6.12).
pkgs+=("linux-headers-$abi-common" "linux-headers-$abi-common-rt" "linux-kbuild-$abi" linux-source-6.12)

rm -f "$cache"/debs/*.deb
(cd "$cache/debs" && apt-get "${apt_opts[@]}" download "${pkgs[@]}" >"$cache/download.log" 2>&1) ||
	die "download failed: $(tail -3 "$cache/download.log")"

rm -rf "$root"
mkdir -p "$root"
for deb in "$cache"/debs/*.deb; do
	dpkg-deb -x "$deb" "$root"
done
for flavour in amd64 rt-amd64; do
	rel=$abi-$flavour
	hdr=$root/usr/src/linux-headers-$rel
	# The flavour's Makefile includes its -common tree by absolute path
	# (scripts/ and tools/ are relative links into the kbuild package).
	sed -i "s|^include /usr/src/|include $root/usr/src/|" "$hdr/Makefile"
	# The image package leaves the index of its modules to its postinst;
	# the VM's initramfs (modprobe -d) needs it.
	depmod -b "$root" "$rel"
	echo "$rel" >"$root/release-$flavour"
done
touch "$stamp"
echo "$root"
