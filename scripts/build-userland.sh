#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# build-userland.sh VARIANT: configure and build userland/ with CMake + Ninja.
#   native  build/userland         RelWithDebInfo, unit tests
#   asan    build/userland-asan    Debug, AddressSanitizer + UBSan, unit tests
#   armhf   build/userland-armhf   cross (arm-linux-gnueabihf), no tests
#   armel   build/userland-armel   cross (arm-linux-gnueabi, the TS-7800), no tests
set -euo pipefail
. "$(dirname "$0")/lib.sh"

variant=${1:?variant (native|asan|armhf|armel)}
# Installed (scripts/install.sh) as a Debian package would be: /usr, /etc.
args=(-G Ninja -S "$TOP/userland" -DCMAKE_INSTALL_PREFIX=/usr -DCMAKE_INSTALL_SYSCONFDIR=/etc)
case $variant in
native) dir=$BUILD/userland; args+=(-DCMAKE_BUILD_TYPE=RelWithDebInfo) ;;
asan) dir=$BUILD/userland-asan; args+=(-DCMAKE_BUILD_TYPE=Debug -DADVEE_SANITIZE=ON) ;;
armhf|armel)
	dir=$BUILD/userland-$variant
	args+=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DADVEE_BUILD_TESTS=OFF
		-DCMAKE_TOOLCHAIN_FILE="$TOP/userland/cmake/$(cross_prefix "$variant" | sed 's/-$//').cmake") ;;
*) die "unknown userland variant $variant" ;;
esac
say "userland ($variant) in $dir"
log=$dir.log
if ! { cmake -B "$dir" "${args[@]}" && ninja -C "$dir"; } >"$log" 2>&1; then
	tail -40 "$log" >&2
	die "userland build ($variant) failed; full log: $log"
fi
