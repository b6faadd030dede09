#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# build-debs.sh [--arch armel|armhf] [--out DIR] [--lintian]: the Debian
# binary packages of the source package in debian/ (dpkg-buildpackage -b,
# debhelper), for the build machine's architecture, into build/debs/ (or
# DIR):
#   advee_VERSION_ARCH.deb         the robot's runtime: daemons, supervisor,
#                                  tools, units, udev rules, configuration
#   advee-sim_VERSION_ARCH.deb     simulators and the demo driver
#   libadvee-dev_VERSION_ARCH.deb  static libraries and headers
#   advee-dkms_VERSION_all.deb     the module sources for DKMS
# debian/rules reuses build/userland (scripts/build-userland.sh) when it is
# up to date. --lintian: lintian on the packages afterwards; any error or
# warning fails. --arch ARCH: cross-built packages for the robot
# (dpkg-buildpackage -a ARCH -B: the architecture-dependent ones, advee-dkms
# is the native build's) into build/debs-ARCH/ (or DIR), over
# build/userland-ARCH, with dpkg-shlibdeps on a private database of
# Debian's ARM libraries (scripts/arm-shlibs-db.sh; nothing is installed for
# ARCH), then a check that every ELF file in them is ARCH's (machine ARM,
# the loader of scripts/build-userland.sh's ABI check).
# docs/install.md section 9.
set -euo pipefail
. "$(dirname "$0")/lib.sh"

out=
lint=0
arch=$(dpkg --print-architecture)
cross=()
btype=(-b)	# everything; a cross build: -B, the architecture-dependent packages
while [ $# -gt 0 ]; do
	case $1 in
	--out) out=$2; shift 2 ;;
	--lintian) lint=1; shift ;;
	--arch)
		case $2 in
		armel|armhf) arch=$2 ;;
		"$arch") ;;
		*) die "build-debs.sh: --arch $2: armel or armhf (or the build machine's, $arch)" ;;
		esac
		shift 2 ;;
	*) die "build-debs.sh: unknown argument $1 (--arch ARCH, --out DIR, --lintian)" ;;
	esac
done
if [ "$arch" != "$(dpkg --print-architecture)" ]; then
	# -d: the Build-Depends are the build machine's packages (the ARM
	# libraries come from the sysroot), not ARCH's, which dpkg would want.
	# shellcheck disable=SC2054 # -P takes one comma-separated list
	cross=(-a"$arch" -d -Pcross,nocheck)
	btype=(-B)
	out=${out:-$BUILD/debs-$arch}
fi
out=${out:-$BUILD/debs}
mkdir -p "$out"
out=$(cd "$out" && pwd)
ver=$(advee_version)
rm -f "$out"/*.deb "$out"/*.changes "$out"/*.buildinfo
say "dpkg-buildpackage ${btype[*]} ${cross[*]} ($arch) into $out"
cd "$TOP"
# Everything goes to $out, not into the directory above the checkout: the
# .debs through debian/rules (ADVEE_DEBS_DIR: dh_builddeb --destdir), the
# .buildinfo and .changes through dpkg-buildpackage's options. --post-clean:
# no debian/tmp or package trees left in the checkout.
DEB_BUILD_OPTIONS=${cross:+nocheck} ADVEE_DEBS_DIR=$out dpkg-buildpackage "${btype[@]}" "${cross[@]}" -us -uc --no-sign --post-clean \
	--buildinfo-option=-u"$out" --changes-option=-u"$out" \
	--buildinfo-file="$out/advee_${ver}_$arch.buildinfo" \
	--changes-file="$out/advee_${ver}_$arch.changes" >"$out/build.log" 2>&1 ||
	{ tail -30 "$out/build.log" >&2; die "dpkg-buildpackage failed; full log: $out/build.log"; }
printf "    %s\n" "$out"/*.deb >&2
if [ ${#cross[@]} -gt 0 ]; then
	# Every ELF file of the packages is ARCH's: ARM, EABI5, and for
	# executables the target's loader (armel ld-linux.so.3, armhf
	# ld-linux-armhf.so.3); a host binary slipped in fails here.
	case $arch in armel) loader=/lib/ld-linux.so.3 ;; armhf) loader=/lib/ld-linux-armhf.so.3 ;; esac
	x=$(mktemp -d)
	n=0 bad=0
	for deb in "$out"/*.deb; do
		rm -rf "$x/root" && dpkg-deb -x "$deb" "$x/root"
		while IFS= read -r -d '' f; do
			desc=$(file -b "$f")
			case $desc in
			ELF*) ;;
			*"ar archive"*)	# libadvee-dev: every member ARM
				n=$((n + 1))
				m=$(readelf -h "$f" | awk '/Machine:/ { print $2 }' | sort -u | tr '\n' ' ')
				[ "$m" = "ARM " ] || { echo "  ${deb##*/}: ${f#"$x/root"}: members for $m" >&2; bad=1; }
				continue ;;
			*) continue ;;
			esac
			n=$((n + 1))
			case $desc in *"ELF 32-bit LSB"*"ARM, EABI5"*) ;; *) echo "  ${deb##*/}: ${f#"$x/root"}: $desc" >&2; bad=1; continue ;; esac
			case $desc in *executable*)
				[[ $desc == *"interpreter $loader,"* ]] ||
					{ echo "  ${deb##*/}: ${f#"$x/root"}: not $arch's loader: $desc" >&2; bad=1; } ;;
			esac
		done < <(find "$x/root" -type f -print0)
	done
	rm -rf "$x"
	[ $bad = 0 ] || die "ELF files of another architecture in the $arch packages"
	say "$n ELF files and static libraries in the $arch packages, all ARM (EABI5, $loader)"
fi
if [ "$lint" = 1 ]; then
	say "lintian"
	# --fail-on error,warning: the default level, nothing tolerated.
	lintian --fail-on error,warning "$out/advee_${ver}_$arch.changes"
fi
