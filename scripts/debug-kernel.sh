#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# debug-kernel.sh [SERIES]: build the debug test kernel once and print the
# directory of the cached build. See docs/testing.md ("The debug lane").
# SERIES (default $ADVEE_DEBUG_KERNEL, else 6.12-rt):
#   6.12-rt  Debian's linux-source-6.12 (bookworm-backports,
#            scripts/fetch-bpo-kernel.sh) with PREEMPT_RT, lockdep with raw
#            lock nesting, KASAN, KFENCE, kmemleak, UBSAN, DEBUG_OBJECTS,
#            gpio-sim: tests/harness/debug-kernel.config, then
#            debug-kernel-6.12-rt.config over it;
#   6.1      Debian 12's linux-source-6.1, PREEMPT, debug-kernel.config alone.
#
# The cache lives outside the repository (a fresh CI clone on the same machine
# reuses it), keyed by the source package version, the config fragments and
# the build recipe below:
#   ${ADVEE_KCACHE:-$ADVEE_MACHINE_CACHE}/debug-kernel/ (scripts/lib.sh)
#     src/VERSION/linux-source-SERIES/ the extracted sources (shared by all keys)
#     KEY/bzImage                     the kernel image
#     KEY/kver                        its release (uname -r)
#     KEY/modroot/lib/modules/KVER/   `make modules_install` output
#     KEY/build/                      the O= build tree (for M= module builds)
#     KEY/build.log, KEY/build-seconds, KEY/ready (written last)
# Environment: ADVEE_KCACHE, ADVEE_KNICE (nice level of the build, default 10),
# ADVEE_DEBUG_KERNEL.
set -euo pipefail
. "$(dirname "$0")/lib.sh"

# Bump when the steps below change what ends up in the cache.
recipe=1
fragments=("$TOP/tests/harness/debug-kernel.config")

case ${1:-${ADVEE_DEBUG_KERNEL:-6.12-rt}} in
6.12-rt)
	series=6.12
	fragments+=("$TOP/tests/harness/debug-kernel-6.12-rt.config")
	bpo=$("$TOP/scripts/fetch-bpo-kernel.sh")
	tarball=$(ls "$bpo"/usr/src/linux-source-6.12.tar.* 2>/dev/null | head -1)
	[ -n "$tarball" ] || die "debug kernel: no linux-source-6.12 in $bpo (scripts/fetch-bpo-kernel.sh)"
	# The version of the package fetch-bpo-kernel.sh unpacked it from.
	srcdeb=$(ls "$bpo"/../debs/linux-source-6.12_*.deb 2>/dev/null | head -1)
	srcver=$([ -z "$srcdeb" ] || dpkg-deb -f "$srcdeb" Version)
	;;
6.1)
	series=6.1
	tarball=$(ls /usr/src/linux-source-6.1.tar.* 2>/dev/null | head -1)
	[ -n "$tarball" ] || die "debug kernel: linux-source-6.1 is not installed (run: make deps)"
	srcver=$(dpkg-query -W -f='${Version}' linux-source-6.1 2>/dev/null || true)
	;;
*) die "debug kernel: unknown series '${1:-$ADVEE_DEBUG_KERNEL}' (6.12-rt or 6.1)" ;;
esac
[ -n "$srcver" ] || srcver=$(stat -c '%s-%Y' "$tarball")
key=$({ echo "recipe $recipe"; echo "source $srcver"; cat "${fragments[@]}"; } | sha256sum | cut -c1-16)
cache=${ADVEE_KCACHE:-$ADVEE_MACHINE_CACHE}/debug-kernel
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
src=$cache/src/$srcver/linux-source-$series
if [ ! -e "$src/.extracted" ]; then
	say "debug kernel: extracting $(basename "$tarball") to $cache/src/$srcver"
	rm -rf "$cache/src/$srcver"
	mkdir -p "$cache/src/$srcver"
	tar -xf "$tarball" -C "$cache/src/$srcver" || die "debug kernel: cannot extract $tarball"
	[ -f "$src/Makefile" ] || die "debug kernel: $tarball has no linux-source-$series/ tree"
	: >"$src/.extracted"
fi

rm -rf "$entry"
mkdir -p "$entry/build"
log=$entry/build.log
nice=(nice -n "${ADVEE_KNICE:-10}")
kmake() { "${nice[@]}" make -C "$src" O="$entry/build" "$@"; }

say "debug kernel $key: configuring linux-source-$series (tinyconfig + kvm_guest.config + ${fragments[*]##*/})"
{
	kmake tinyconfig
	"$src/scripts/kconfig/merge_config.sh" -m -O "$entry/build" "$entry/build/.config" \
		"$src/kernel/configs/kvm_guest.config" "${fragments[@]}"
	kmake olddefconfig
} >"$log" 2>&1 || { tail -30 "$log" >&2; die "debug kernel: configuration failed (log: $log)"; }

# Kconfig drops a requested option silently when a dependency is missing: every
# line of the fragments must have survived (for a symbol in several, the last).
lost=$(cat "${fragments[@]}" | grep -E '^(CONFIG_[A-Z0-9_]+=|# CONFIG_[A-Z0-9_]+ is not set)' |
	awk '{ sym = $0; sub(/^# /, "", sym); sub(/[= ].*/, "", sym); if (!(sym in last)) order[n++] = sym; last[sym] = $0 }
		END { for (i = 0; i < n; i++) print last[order[i]] }' | while read -r want; do
	sym=$(echo "$want" | grep -oE 'CONFIG_[A-Z0-9_]+')
	have=$(grep -E "^($sym=|# $sym is not set)" "$entry/build/.config" || true)
	case $want in
	"# "*) [ -z "$have" ] || [ "$have" = "$want" ] || echo "  $want (got: $have)" ;;
	*) [ "$have" = "$want" ] || echo "  $want (got: ${have:-nothing})" ;;
	esac
done)
[ -z "$lost" ] || die "debug kernel: options of ${fragments[*]##*/} did not survive Kconfig:
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
