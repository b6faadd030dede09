#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# build-userland.sh VARIANT: configure and build userland/ with CMake + Ninja.
#   native  build/userland         -O2, no debug information (as Debian ships
#                                  binaries, stripped), unit tests (none with
#                                  ADVEE_UNIT_TESTS=0: what the VMs, the demo
#                                  and the browser check run needs no tests)
#   asan    build/userland-asan    -O1 (what the sanitizers' authors advise,
#                                  and less compile time than -O2, not
#                                  measured alone; the -O2 build that ships
#                                  is what every VM suite runs) with line
#                                  tables only (-g1: file:line in sanitizer
#                                  reports),
#                                  AddressSanitizer + UBSan: the unit tests
#                                  and the programs they start
#   armhf   build/userland-armhf   cross (arm-linux-gnueabihf), -O2, no tests
#   armel   build/userland-armel   cross (arm-linux-gnueabi, the TS-7800), -O2, no tests
#   armel-tests build/userland-armel-tests  the armel build with the unit
#                                  tests (GoogleTest of Debian's armel
#                                  libgtest-dev: fetch-arm-sysroot.sh armel
#                                  gtest), only what CTest runs; the armel VM
#                                  lane runs them (vm-arm.sh --arch armel --cxx)
# Full debug information (-g) costs a fifth of the compile time of every
# file and five times the size of the binaries the VM tests package; nothing
# here reads it.
# Unity builds (CMake merges up to 8 sources of a target into one file):
# the standard, GoogleTest, CLI11, yaml-cpp and LCM headers are parsed once
# per batch instead of once per source, which is most of the compile time
# of these files; every variant is a whole build in make check. The price:
# names at file scope must be unique within a target (an anonymous
# namespace does not separate the files of one batch).
# Compiler cache: every compilation goes through ccache, whose cache lives
# outside the repository like the debug kernel's, in
# ${ADVEE_CCACHE:-$ADVEE_MACHINE_CACHE/ccache} (scripts/lib.sh;
# ADVEE_CCACHE=off: no cache), so a fresh CI clone on the same machine
# compiles only what changed since the last run (a native build went from 276
# to 37 CPU-s in a second clone at another path). For hits across clones at
# different paths: CCACHE_BASEDIR makes the paths under the clone relative on
# the command line, CCACHE_NOHASHDIR leaves the working directory out of the
# hash, and -ffile-prefix-map turns the clone's path into "" in __FILE__,
# std::source_location and the debug information (file names in reports are
# then relative to the repository).
# ccache never changes what is built; a cache that cannot be created only
# costs time and is said.
# The cross builds link Debian's armhf/armel libraries from the sysroot of
# scripts/fetch-arm-sysroot.sh ($ADVEE_CACHE/arm/ARCH/sysroot) and end with an ABI
# check of every ELF file they produced.
set -euo pipefail
. "$(dirname "$0")/lib.sh"

variant=${1:?variant (native|asan|armhf|armel|armel-tests)}
arch=${variant%-tests}
# Installed (scripts/install.sh) as a Debian package would be: /usr, /etc.
args=(-G Ninja -S "$TOP/userland" -DCMAKE_INSTALL_PREFIX=/usr -DCMAKE_INSTALL_SYSCONFDIR=/etc
	-DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=8)
shipped=(-DCMAKE_BUILD_TYPE=Release "-DCMAKE_C_FLAGS_RELEASE=-O2 -DNDEBUG" "-DCMAKE_CXX_FLAGS_RELEASE=-O2 -DNDEBUG")
case $variant in
native)
	dir=$BUILD/userland
	args+=("${shipped[@]}")
	[ "${ADVEE_UNIT_TESTS:-1}" = 0 ] && args+=(-DADVEE_BUILD_TESTS=OFF)
	;;
asan)
	dir=$BUILD/userland-asan
	args+=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG"
		"-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" -DADVEE_SANITIZE=ON)
	;;
armhf|armel|armel-tests)
	dir=$BUILD/userland-$variant
	args+=("${shipped[@]}"
		-DCMAKE_TOOLCHAIN_FILE="$TOP/userland/cmake/$(cross_prefix "$arch" | sed 's/-$//').cmake"
		-DADVEE_ARM_SYSROOT="$("$TOP/scripts/fetch-arm-sysroot.sh" "$arch")")
	if [ "$variant" = "$arch" ]; then
		args+=(-DADVEE_BUILD_TESTS=OFF)
	else
		# The tests are listed when CTest runs them (in the guest), not by
		# running the ARM binaries at build time.
		args+=(-DGTest_DIR="$("$TOP/scripts/fetch-arm-sysroot.sh" "$arch" gtest)/usr/lib/$(cross_prefix "$arch" | sed 's/-$//')/cmake/GTest"
			-DCMAKE_GTEST_DISCOVER_TESTS_DISCOVERY_MODE=PRE_TEST)
	fi ;;
*) die "unknown userland variant $variant" ;;
esac
prefix_map="-ffile-prefix-map=$TOP/="
args+=("-DCMAKE_C_FLAGS=$prefix_map" "-DCMAKE_CXX_FLAGS=$prefix_map")
ccache_dir=${ADVEE_CCACHE:-$ADVEE_MACHINE_CACHE/ccache}
if [ "$ccache_dir" != off ]; then
	if ! command -v ccache >/dev/null; then
		say "userland ($variant): no ccache on this machine: every file is compiled"
	elif ! mkdir -p "$ccache_dir" 2>/dev/null || [ ! -w "$ccache_dir" ]; then
		say "userland ($variant): compiler cache $ccache_dir not writable (set ADVEE_CCACHE): every file is compiled"
	else
		export CCACHE_DIR=$ccache_dir CCACHE_BASEDIR=$TOP CCACHE_NOHASHDIR=1
		export CCACHE_MAXSIZE=${CCACHE_MAXSIZE:-4G}
		# This build's own statistics (other builds may share the cache now).
		export CCACHE_STATSLOG=$dir.ccache-stats
		rm -f "$CCACHE_STATSLOG"
		args+=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
	fi
fi
say "userland ($variant) in $dir"
mkdir -p "$BUILD"
log=$dir.log
# A toolchain file is read once, when the cache is created (its *_INIT
# flags then stay in CMakeCache.txt): start the cache again when the
# toolchain or the configure arguments changed since.
stamp=$(printf '%s\n' "${args[@]}" | cat - "$TOP"/userland/cmake/*.cmake | sha256sum | cut -c1-16)
if [ -f "$dir/CMakeCache.txt" ] && [ "$(cat "$dir/.advee-configure" 2>/dev/null)" != "$stamp" ]; then
	rm -rf "$dir/CMakeCache.txt" "$dir/CMakeFiles"
fi
# The sanitizer build serves the unit tests only: what CTest runs (the
# target advee_test_binaries of userland/CMakeLists.txt), not every program.
targets=()
case $variant in asan|*-tests) targets=(advee_test_binaries) ;; esac
if ! { cmake -B "$dir" "${args[@]}" && ninja -C "$dir" "${targets[@]}"; } >"$log" 2>&1; then
	tail -40 "$log" >&2
	die "userland build ($variant) failed; full log: $log"
fi
echo "$stamp" >"$dir/.advee-configure"
if [ -n "${CCACHE_STATSLOG:-}" ]; then
	# One result line per compilation in the statistics log.
	hits=$(grep -cE '^(direct|preprocessed)_cache_hit$' "$CCACHE_STATSLOG" 2>/dev/null) || :
	misses=$(grep -cx 'cache_miss' "$CCACHE_STATSLOG" 2>/dev/null) || :
	say "userland ($variant): ${hits:-0} compilations from the compiler cache, ${misses:-0} compiled ($CCACHE_DIR)"
fi

# Cross builds: every ELF file must be for the target's ABI (file(1) and the
# ARM build attributes): armel = ARMv5TE soft float, ld-linux.so.3 (the
# TS-7800); armhf = ARMv7 hard float (VFP argument registers), ld-linux-armhf.so.3.
check_abi() {	# check_abi FILE: empty output when it fits $variant
	local f=$1 desc attrs
	desc=$(file -b "$f")
	attrs=$(readelf -A "$f" 2>/dev/null)
	case $desc in *"ELF 32-bit LSB"*"ARM, EABI5"*) ;; *) echo "$f: $desc"; return ;; esac
	case $arch in
	armhf)
		case $desc in *executable*) [[ $desc == *ld-linux-armhf.so.3* ]] || echo "$f: not the armhf loader: $desc" ;; esac
		grep -q 'Tag_ABI_VFP_args: VFP registers' <<<"$attrs" || echo "$f: not hard float"
		;;
	armel)
		case $desc in *executable*) [[ $desc == *ld-linux.so.3* ]] || echo "$f: not the armel loader: $desc" ;; esac
		grep -q 'Tag_ABI_VFP_args' <<<"$attrs" && echo "$f: hard-float calling convention in an armel build"
		grep -q 'Tag_CPU_arch: v5TE' <<<"$attrs" || echo "$f: not ARMv5TE: $(grep Tag_CPU_arch: <<<"$attrs")"
		;;
	esac
}
case $arch in
armhf|armel)
	n=0 bad=
	while IFS= read -r -d '' f; do
		head -c 4 "$f" | grep -q 'ELF' || continue
		n=$((n + 1))
		out=$(check_abi "$f")
		[ -z "$out" ] || bad+=$'\n'$out
	done < <(find "$dir" -type f \( -perm -u+x -o -name '*.so*' \) -not -path '*/CMakeFiles/*' -print0)
	[ -z "$bad" ] || die "userland ($variant): wrong ABI: $bad"
	[ "$n" -gt 0 ] || die "userland ($variant): no ELF file to check in $dir"
	say "userland ($variant): $n ELF files, all $(case $arch in armhf) echo ARMv7 hard float ;; armel) echo ARMv5TE soft float ;; esac)"
	;;
esac
