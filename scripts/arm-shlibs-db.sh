#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# arm-shlibs-db.sh DEBARCH: a private dpkg database of Debian's DEBARCH
# libraries for dpkg-shlibdeps in a cross build of the packages
# (scripts/build-debs.sh --arch DEBARCH, debian/rules), without installing
# any foreign package and without touching the machine's dpkg or apt
# configuration (dpkg --print-foreign-architectures stays empty).
#
# dpkg-shlibdeps finds a needed library in its -l directories, asks
# dpkg-query --search (under --admindir) which package owns that path, and
# reads the package's symbols or shlibs file from the database. So the
# database made here lists each package with the paths where its files
# really are on this machine: the ARM sysroot of fetch-arm-sysroot.sh (its
# downloaded .debs, the libraries the userland links) and a root of the
# target's libc6, libstdc++6, libgcc-s1 and libatomic1 (the cross toolchain links its
# own copies, whose packages are the -cross ones, no dependency of a robot).
# The control files (symbols, shlibs) are those of the .debs.
#
# Prints three lines: the admin directory, then the -l directories for
# dpkg-shlibdeps (colon-separated), then the sysroot.
set -euo pipefail
. "$(dirname "$0")/lib.sh"

debarch=${1:?debian architecture (armhf|armel)}
case $debarch in armhf|armel) ;; *) die "arm-shlibs-db.sh: unknown architecture $debarch" ;; esac
cache=$ADVEE_CACHE/arm/$debarch
sysroot=$("$TOP/scripts/fetch-arm-sysroot.sh" "$debarch")
triplet=$(dpkg-architecture -a"$debarch" -qDEB_HOST_MULTIARCH 2>/dev/null)
rtpkgs=(libc6 libstdc++6 libgcc-s1 libatomic1)
db=$cache/shlibs-db
rt=$cache/shlibs-runtime
want="${rtpkgs[*]} $(cat "$sysroot/.advee-packages") v2"

exec 9>"$cache/shlibs-db.lock"
flock 9
if [ "$(cat "$db/.advee-packages" 2>/dev/null)" != "$want" ]; then
	arm_apt_opts "$debarch"
	rm -rf "$db" "$rt"
	mkdir -p "$rt/debs" "$rt/root" "$db/info" "$db/updates" "$db/triggers"
	echo 1 >"$db/info/format"	# the multiarch layout: pkg:arch.list for Multi-Arch: same
	(cd "$rt/debs" && apt-get "${apt_opts[@]}" download "${rtpkgs[@]}" >/dev/null)
	for deb in "$rt"/debs/*.deb; do dpkg-deb -x "$deb" "$rt/root"; done
	: >"$db/status"
	# Both architectures, so that dpkg-query accepts the packages.
	printf '%s\n' "$(dpkg --print-architecture)" "$debarch" >"$db/arch"
	register() {	# register DEB ROOT: DEB's stanza, file list (under ROOT) and control files
		local deb=$1 root=$2 pkg arch ma key tmp
		pkg=$(dpkg-deb -f "$deb" Package)
		arch=$(dpkg-deb -f "$deb" Architecture)
		ma=$(dpkg-deb -f "$deb" Multi-Arch)
		key=$pkg
		[ "$ma" = same ] && key=$pkg:$arch
		{
			dpkg-deb -f "$deb" | sed '/^Status:/d' | awk -v st='Status: install ok installed' \
				'NR == 1 { print; print st; next } { print }'
			echo
		} >>"$db/status"
		dpkg-deb --fsys-tarfile "$deb" | tar -t | sed 's|^\./|/|; s|/$||; /^\.\{0,1\}$/d' |
			sed "s|^|$root|" >"$db/info/$key.list"
		tmp=$(mktemp -d)
		dpkg-deb -e "$deb" "$tmp"
		for f in symbols shlibs; do
			[ -f "$tmp/$f" ] && cp "$tmp/$f" "$db/info/$key.$f"
		done
		rm -rf "$tmp"
	}
	for deb in "$rt"/debs/*.deb; do register "$deb" "$rt/root"; done
	for deb in "$cache"/sysroot-debs/*.deb; do register "$deb" "$sysroot"; done
	echo "$want" >"$db/.advee-packages"
fi
echo "$db"
echo "$rt/root/lib/$triplet:$rt/root/usr/lib/$triplet:$sysroot/lib/$triplet:$sysroot/usr/lib/$triplet"
echo "$sysroot"
