#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# debug-kernel.sh: build the debug test kernel (KASAN, lockdep, kmemleak,
# UBSAN, KFENCE, DEBUG_OBJECTS, PREEMPT, gpio-sim) from Debian's linux-source-6.1
# once, and print the directory of the cached build. See docs/testing.md.
#
# The cache lives outside the repository (a fresh CI clone on the same machine
# reuses it), keyed by the source package version, the config fragment and the
# build recipe below:
#   ${ADVEE_KCACHE:-/var/cache/advee}/debug-kernel/
#     src/VERSION/linux-source-6.1/   the extracted sources (shared by all keys)
#     KEY/bzImage                     the kernel image
#     KEY/kver                        its release (uname -r)
#     KEY/modroot/lib/modules/KVER/   `make modules_install` output
#     KEY/build/                      the O= build tree (for M= module builds)
#     KEY/build.log, KEY/build-seconds, KEY/ready (written last)
# Environment: ADVEE_KCACHE, ADVEE_KNICE (nice level of the build, default 10).
set -euo pipefail
. "$(dirname "$0")/lib.sh"

# Bump when the steps below change what ends up in the cache.
recipe=1
fragment=$TOP/tests/harness/debug-kernel.config

tarball=$(ls /usr/src/linux-source-6.1.tar.* 2>/dev/null | head -1)
[ -n "$tarball" ] || die "debug kernel: linux-source-6.1 is not installed (run: make deps)"
srcver=$(dpkg-query -W -f='${Version}' linux-source-6.1 2>/dev/null) ||
	srcver=$(stat -c '%s-%Y' "$tarball")
key=$({ echo "recipe $recipe"; echo "source $srcver"; cat "$fragment"; } | sha256sum | cut -c1-16)
cache=${ADVEE_KCACHE:-/var/cache/advee}/debug-kernel
entry=$cache/$key

if [ -e "$entry/ready" ]; then
	echo "$entry"
	exit 0
fi

mkdir -p "$cache" || die "debug kernel: cannot create the cache $cache (set ADVEE_KCACHE)"
# One builder per key; a second caller waits and then reuses the result.
exec 8>"$cache/$key.lock"
if ! flock -n 8; then
	say "debug kernel $key is being built by another run; waiting for it"
	flock 8
fi
if [ -e "$entry/ready" ]; then
	echo "$entry"
	exit 0
fi

start=$(date +%s)
src=$cache/src/$srcver/linux-source-6.1
if [ ! -e "$src/.extracted" ]; then
	say "debug kernel: extracting $(basename "$tarball") to $cache/src/$srcver"
	rm -rf "$cache/src/$srcver"
	mkdir -p "$cache/src/$srcver"
	tar -xf "$tarball" -C "$cache/src/$srcver" || die "debug kernel: cannot extract $tarball"
	[ -f "$src/Makefile" ] || die "debug kernel: $tarball has no linux-source-6.1/ tree"
	: >"$src/.extracted"
fi

rm -rf "$entry"
mkdir -p "$entry/build"
log=$entry/build.log
nice=(nice -n "${ADVEE_KNICE:-10}")
kmake() { "${nice[@]}" make -C "$src" O="$entry/build" "$@"; }

say "debug kernel $key: configuring (tinyconfig + kvm_guest.config + $(basename "$fragment"))"
{
	kmake tinyconfig
	"$src/scripts/kconfig/merge_config.sh" -m -O "$entry/build" "$entry/build/.config" \
		"$src/kernel/configs/kvm_guest.config" "$fragment"
	kmake olddefconfig
} >"$log" 2>&1 || { tail -30 "$log" >&2; die "debug kernel: configuration failed (log: $log)"; }

# Kconfig drops a requested option silently when a dependency is missing: every
# line of the fragment must have survived.
lost=$(grep -E '^(CONFIG_[A-Z0-9_]+=|# CONFIG_[A-Z0-9_]+ is not set)' "$fragment" | while read -r want; do
	sym=$(echo "$want" | grep -oE 'CONFIG_[A-Z0-9_]+')
	have=$(grep -E "^($sym=|# $sym is not set)" "$entry/build/.config" || true)
	case $want in
	"# "*) [ -z "$have" ] || [ "$have" = "$want" ] || echo "  $want (got: $have)" ;;
	*) [ "$have" = "$want" ] || echo "  $want (got: ${have:-nothing})" ;;
	esac
done)
[ -z "$lost" ] || die "debug kernel: options of $fragment did not survive Kconfig:
$lost"

jobs=$(nproc)
say "debug kernel $key: building bzImage + modules with make -j$jobs (log: $log)"
# Progress: one line per 500 compiled files, with the time so far.
if ! kmake -j"$jobs" bzImage modules 2>&1 | tee -a "$log" |
	awk -v start="$start" '/^  CC/ && ++n % 500 == 0 {
		printf "==>   %d files compiled, %d s\n", n, systime() - start > "/dev/stderr"; fflush("/dev/stderr") }'; then
	grep -E 'error|Error' "$log" | head -20 >&2
	die "debug kernel: build failed (log: $log)"
fi
kver=$(kmake -s kernelrelease 2>/dev/null)
kmake INSTALL_MOD_PATH="$entry/modroot" modules_install >>"$log" 2>&1 ||
	die "debug kernel: modules_install failed (log: $log)"
cp "$entry/build/arch/x86/boot/bzImage" "$entry/bzImage"
echo "$kver" >"$entry/kver"
seconds=$(($(date +%s) - start))
echo "$seconds" >"$entry/build-seconds"
: >"$entry/ready"
say "debug kernel $kver built in ${seconds}s (cold, $jobs job(s)): $entry"
echo "$entry"
