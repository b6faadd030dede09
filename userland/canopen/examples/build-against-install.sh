#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
# build-against-install.sh BUILD STAGE LIBDIR CXX: install the development
# files of the build tree BUILD (component dev: libadvee-dev's libraries,
# headers, CMake package, pkg-config files) into STAGE (DESTDIR, prefix
# /usr) and build the example program of
# this directory against that staged install only, once with CMake
# (find_package(AdveeCanopen)) and once with pkg-config; both programs must
# start (usage error, exit 2: no CAN interface needed). The program is the
# one docs/canopen.md shows. LIBDIR is
# CMAKE_INSTALL_LIBDIR (lib/<multiarch>).
set -euo pipefail
build=${1:?build dir} stage=${2:?staging dir} libdir=${3:?libdir} cxx=${4:?compiler}
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$stage"
mkdir -p "$stage"
DESTDIR=$stage/root cmake --install "$build" --prefix /usr --component dev >"$stage/install.log"
root=$stage/root

# docs/canopen.md shows this program: the same code (without its head comment).
doc=$(cd "$here/../../.." && pwd)/docs/canopen.md
# shellcheck disable=SC2016 # sed scripts, not shell expansions
if ! diff <(sed -n '/^## Libraries$/,/^## Programs$/p' "$doc" | sed -n '/^```cpp$/,/^```$/p' | sed '1d;$d') \
	<(sed '/^\/\//d' "$here/read_identity.cpp"); then
	echo "docs/canopen.md (<) and examples/read_identity.cpp (>) show different programs"; exit 1
fi

echo "# CMake: find_package(AdveeCanopen) from $root/usr"
# Only the staged tree: no package registry, no system prefix for AdveeCanopen.
cmake -S "$here" -B "$stage/cmake" -G Ninja -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=Release \
	-DCMAKE_PREFIX_PATH="$root/usr" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF \
	-DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF -DCMAKE_FIND_USE_CMAKE_SYSTEM_PATH=OFF >"$stage/cmake.log"
grep -q "AdveeCanopen_DIR:PATH=$root/usr/$libdir/cmake/AdveeCanopen" "$stage/cmake/CMakeCache.txt" ||
	{ echo "AdveeCanopen not found in the staged install"; grep AdveeCanopen_DIR "$stage/cmake/CMakeCache.txt"; exit 1; }
cmake --build "$stage/cmake"
# The include directories came from the staged tree, not the sources.
src=$(cd "$here/../.." && pwd)
if grep -Fq -e "$src/canopen/include" -e "$src/common/include" "$stage/cmake/build.ninja"; then
	echo "the example was compiled with the source tree's headers"; exit 1
fi

echo "# pkg-config: advee-canopen-socketcan from $root/usr/$libdir/pkgconfig"
# The system-directory filter must not drop the staged -I$root/usr/include.
export PKG_CONFIG_LIBDIR=$root/usr/$libdir/pkgconfig PKG_CONFIG_SYSROOT_DIR=$root PKG_CONFIG_PATH=
export PKG_CONFIG_ALLOW_SYSTEM_CFLAGS=1 PKG_CONFIG_ALLOW_SYSTEM_LIBS=1
flags=$(pkg-config --cflags --libs advee-canopen-socketcan)
echo "pkg-config: $flags"
pkg-config --exists advee-canopen || { echo "advee-canopen.pc does not resolve"; exit 1; }
# shellcheck disable=SC2086 # the flags are words
"$cxx" -std=c++20 -O2 -o "$stage/read-identity-pc" "$here/read_identity.cpp" $flags

for prog in "$stage/cmake/read-identity" "$stage/read-identity-pc"; do
	set +e
	"$prog" >/dev/null 2>&1
	rc=$?
	set -e
	[ $rc = 2 ] || { echo "$prog without arguments: exit $rc, not 2"; exit 1; }
done
echo "ok: read-identity built against $root by CMake and by pkg-config"
