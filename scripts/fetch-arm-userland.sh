#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# fetch-arm-userland.sh DEBARCH: the Debian user space the VM test suites call
# (bash, coreutils, kmod, i2c-tools, lm-sensors, gpiod, can-utils, iproute2...)
# for the ARM VM lane, so that the shell programs of a portable suite run there
# exactly as on the x86_64 lane. Downloaded with apt-get download through the
# private apt setup of fetch-arm-kernel.sh (no foreign architecture is ever
# added to dpkg) and extracted into $ADVEE_CACHE/arm/DEBARCH/userland (lib.sh). Prints that
# directory.
#
# Only the tools below and the libraries they load are taken: maintainer
# scripts never run, so what packages depend on for them (perl, debconf,
# adduser...) is left out; every ELF file's NEEDED library is checked.
set -euo pipefail
. "$(dirname "$0")/lib.sh"

debarch=${1:?debian architecture (armhf|armel)}
cache=$ADVEE_CACHE/arm/$debarch
arm_apt_opts "$debarch"

# What the VM test programs run, by package (the x86_64 guest has them from
# the host: scripts/packages.txt). dash is /bin/sh, as on the host: busybox sh
# would run its own applets (its modprobe, for one) for system() and sh -c.
tools=(dash bash coreutils grep sed mawk findutils diffutils procps util-linux mount kmod
	i2c-tools lm-sensors gpiod can-utils iproute2)
tree=$cache/userland
stamp=$tree/.advee-packages
# Made again when this script (the list above) changes; one maker at a time
# (the cache is shared by worktrees).
want="$(sha256sum <"$0" | cut -c1-16) ${tools[*]}"
exec 8>"$cache/userland.lock"
flock 8
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ]; then
	echo "$tree"
	exit 0
fi

# The tools plus, transitively, the library packages (lib*, zlib1g) they
# depend on.
declare -A seen=()
queue=("${tools[@]}")
while [ "${#queue[@]}" -gt 0 ]; do
	next=()
	for p in "${queue[@]}"; do seen[$p]=1; done
	while read -r dep; do
		[ -n "${seen[$dep]:-}" ] && continue
		seen[$dep]=1
		next+=("$dep")
	done < <(apt-cache "${apt_opts[@]}" depends --no-recommends --no-suggests --no-conflicts \
			--no-breaks --no-replaces --no-enhances "${queue[@]}" |
		sed -n 's/^ *|\{0,1\}\(Pre\)\{0,1\}Depends: \(z\{0,1\}lib[^ <>]*\)$/\2/p' | sort -u)
	queue=("${next[@]}")
done
pkgs=("${!seen[@]}")

debs=$cache/userland-debs
mkdir -p "$debs"
rm -f "$debs"/*.deb
say "ARM test userland ($debarch): apt-get download ${#pkgs[@]} packages"
(cd "$debs" && apt-get "${apt_opts[@]}" download "${pkgs[@]}" >"$cache/userland-download.log" 2>&1) || {
	tail -5 "$cache/userland-download.log" >&2; die "download of the ARM test userland failed"; }
rm -rf "$tree"
mkdir -p "$tree"
for deb in "$debs"/*.deb; do dpkg-deb -x "$deb" "$tree"; done
# Documentation and character set converters (the tests run with LC_ALL=C).
rm -rf "$tree"/usr/share/{doc,man,info,locale,lintian,bash-completion} "$tree"/usr/lib/*/gconv
# What update-alternatives would have made (the host's awk is mawk too).
ln -sfn mawk "$tree/usr/bin/awk"

# Every shared library an ELF file of the tree needs is in the tree (readelf
# fails on the scripts among the executables: not an error).
missing=$( { find "$tree" -type f -perm /111 -print0 |
	xargs -0 "$(cross_prefix "$debarch")readelf" -d 2>/dev/null || true; } |
	sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' | sort -u | while read -r lib; do
		compgen -G "$tree/lib/*/$lib" >/dev/null || compgen -G "$tree/usr/lib/*/$lib" >/dev/null ||
			compgen -G "$tree/lib/$lib" >/dev/null || echo "$lib"
	done)
[ -z "$missing" ] || die "ARM test userland: no package provides $(echo $missing)"
echo "$want" >"$stamp"
echo "$tree"
