#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# build-debs.sh [--out DIR] [--lintian]: the Debian binary packages of the
# source package in debian/ (dpkg-buildpackage -b, debhelper), for the build
# machine's architecture, into build/debs/ (or DIR):
#   advee_VERSION_ARCH.deb         the robot's runtime: daemons, supervisor,
#                                  tools, units, udev rules, configuration
#   advee-sim_VERSION_ARCH.deb     simulators and the demo driver
#   libadvee-dev_VERSION_ARCH.deb  static libraries and headers
#   advee-dkms_VERSION_all.deb     the module sources for DKMS
# debian/rules reuses build/userland (scripts/build-userland.sh) when it is
# up to date. --lintian: lintian on the packages afterwards; any error or
# warning fails. docs/install.md section 9.
set -euo pipefail
. "$(dirname "$0")/lib.sh"

out=$BUILD/debs
lint=0
while [ $# -gt 0 ]; do
	case $1 in
	--out) out=$2; shift 2 ;;
	--lintian) lint=1; shift ;;
	*) die "build-debs.sh: unknown argument $1 (--out DIR, --lintian)" ;;
	esac
done
mkdir -p "$out"
out=$(cd "$out" && pwd)
ver=$(advee_version)
arch=$(dpkg --print-architecture)
rm -f "$out"/*.deb "$out"/*.changes "$out"/*.buildinfo
say "dpkg-buildpackage -b ($arch) into $out"
cd "$TOP"
# Everything goes to $out, not into the directory above the checkout: the
# .debs through debian/rules (ADVEE_DEBS_DIR: dh_builddeb --destdir), the
# .buildinfo and .changes through dpkg-buildpackage's options. --post-clean:
# no debian/tmp or package trees left in the checkout.
ADVEE_DEBS_DIR=$out dpkg-buildpackage -b -us -uc --no-sign --post-clean \
	--buildinfo-option=-u"$out" --changes-option=-u"$out" \
	--buildinfo-file="$out/advee_${ver}_$arch.buildinfo" \
	--changes-file="$out/advee_${ver}_$arch.changes" >"$out/build.log" 2>&1 ||
	{ tail -30 "$out/build.log" >&2; die "dpkg-buildpackage failed; full log: $out/build.log"; }
printf "    %s\n" "$out"/*.deb >&2
if [ "$lint" = 1 ]; then
	say "lintian"
	# --fail-on error,warning: the default level, nothing tolerated.
	lintian --fail-on error,warning "$out/advee_${ver}_$arch.changes"
fi
