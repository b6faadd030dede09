#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# fetch-arm-sysroot.sh DEBARCH: Debian's armel/armhf builds of the libraries
# the userland links (LCM, libgpiod, yaml-cpp, libsystemd, spdlog/fmt, ncurses
# and what their .so files need, libsodium and OpenSSL for advee-web, and the
# header-only Eigen, CLI11, nlohmann-json, websocketpp, asio),
# downloaded with apt-get download through the
# private apt setup of fetch-arm-kernel.sh (its lists dir; no foreign
# architecture is ever added to dpkg) and extracted into
# $ADVEE_CACHE/arm/DEBARCH/sysroot (lib.sh). Prints that directory.
set -euo pipefail
. "$(dirname "$0")/lib.sh"

debarch=${1:?debian architecture (armhf|armel)}
cache=$ADVEE_CACHE/arm/$debarch
arm_apt_opts "$debarch"

# fetch-arm-sysroot.sh DEBARCH gtest: Debian's DEBARCH GoogleTest (static
# libraries, headers, CMake config) in a root of its own,
# $ADVEE_CACHE/arm/DEBARCH/gtest/root, for build-userland.sh armel-tests.
if [ "${2:-}" = gtest ]; then
	g=$cache/gtest
	gpkgs=(libgtest-dev libgmock-dev)
	exec 8>"$cache/gtest.lock"
	flock 8
	if [ "$(cat "$g/root/.advee-packages" 2>/dev/null)" != "${gpkgs[*]}" ]; then
		rm -rf "$g"
		mkdir -p "$g/debs" "$g/root"
		(cd "$g/debs" && apt-get "${apt_opts[@]}" download "${gpkgs[@]}" >/dev/null)
		for deb in "$g"/debs/*.deb; do dpkg-deb -x "$deb" "$g/root"; done
		echo "${gpkgs[*]}" >"$g/root/.advee-packages"
	fi
	echo "$g/root"
	exit 0
fi

# The -dev packages and the runtime libraries behind every .so they link
# (the cross toolchain brings libc, libstdc++, libgcc); the header-only ones
# (Eigen, CLI11, nlohmann-json: Architecture all) too, so that find_package
# finds them in the target's root like the others.
pkgs=(liblcm-dev liblcm1 libglib2.0-dev libglib2.0-0 libpcre2-8-0 libffi8 libmount1 libblkid1 libselinux1
libgpiod-dev libgpiod2 libyaml-cpp-dev libyaml-cpp0.7
libsystemd-dev libsystemd0 libcap2 libgcrypt20 libgpg-error0 liblz4-1 liblzma5 libzstd1
libspdlog-dev libspdlog1.10 libfmt-dev libfmt9
libncurses-dev libncurses6 libncursesw6 libtinfo6
libeigen3-dev libcli11-dev nlohmann-json3-dev libwebsocketpp-dev libasio-dev libsodium-dev libsodium23
libssl-dev libssl3)
sysroot=$cache/sysroot
stamp=$sysroot/.advee-packages
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "${pkgs[*]}" ]; then
	echo "$sysroot"
	exit 0
fi
mkdir -p "$cache/sysroot-debs"
rm -f "$cache"/sysroot-debs/*.deb
say "ARM sysroot ($debarch): apt-get download ${#pkgs[@]} packages"
(cd "$cache/sysroot-debs" && apt-get "${apt_opts[@]}" download "${pkgs[@]}" >/dev/null)
rm -rf "$sysroot"
mkdir -p "$sysroot"
for deb in "$cache"/sysroot-debs/*.deb; do dpkg-deb -x "$deb" "$sysroot"; done
# Absolute symlinks (libfoo.so -> /lib/...) must point into the sysroot.
find "$sysroot" -type l -lname '/*' | while read -r l; do
	ln -sfn "$sysroot$(readlink "$l")" "$l"
done
echo "${pkgs[*]}" >"$stamp"
echo "$sysroot"
