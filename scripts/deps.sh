#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# deps.sh: install what this machine lacks to build and test the project
# (Debian 12). Idempotent: installs only missing packages, runs apt-get update
# only when something is missing, then fetches the ARM kernels into $ADVEE_CACHE (lib.sh).
# Packages are listed in scripts/packages.txt (one per line, # comments).
set -euo pipefail
. "$(dirname "$0")/lib.sh"

mapfile -t pkgs < <(sed 's/#.*//; /^[[:space:]]*$/d; s/[[:space:]]//g' "$TOP/scripts/packages.txt")
missing=()
for p in "${pkgs[@]}"; do
	dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done

if [ "${#missing[@]}" -gt 0 ]; then
	[ "$(id -u)" = 0 ] || die "missing packages (${missing[*]}): run as root or install them"
	say "installing ${#missing[@]} package(s): ${missing[*]}"
	export DEBIAN_FRONTEND=noninteractive
	# A stale index is the usual reason for a failed install: update once.
	apt-get update -q >/dev/null || say "apt-get update reported errors; trying the install anyway"
	apt-get install -y -q --no-install-recommends "${missing[@]}" >"${TMPDIR:-/tmp}/advee-apt.log" 2>&1 || {
		tail -20 "${TMPDIR:-/tmp}/advee-apt.log" >&2
		die "apt-get install failed (log: ${TMPDIR:-/tmp}/advee-apt.log)"
	}
else
	say "all ${#pkgs[@]} Debian packages present"
fi

# The dashboard's real-browser tests: puppeteer-core from npm (the versions
# of userland/web/tests/browser/package-lock.json), driving Debian's chromium.
# Node and npm: Debian's npm package unless a node with npm is there already.
if ! command -v npm >/dev/null; then
	[ "$(id -u)" = 0 ] || die "npm missing: run as root or apt-get install npm"
	apt-get install -y -q --no-install-recommends npm >"${TMPDIR:-/tmp}/advee-apt.log" 2>&1 ||
		die "apt-get install npm failed (log: ${TMPDIR:-/tmp}/advee-apt.log)"
fi
browser_tests=$TOP/userland/web/tests/browser
if ! cmp -s "$browser_tests/package-lock.json" "$browser_tests/node_modules/.advee-lock" 2>/dev/null; then
	say "npm ci: puppeteer-core for the dashboard's browser tests"
	(cd "$browser_tests" && PUPPETEER_SKIP_DOWNLOAD=1 npm ci --no-audit --no-fund --loglevel=error >/dev/null) ||
		die "npm ci in $browser_tests failed"
	cp "$browser_tests/package-lock.json" "$browser_tests/node_modules/.advee-lock"
fi

# The x86_64 VM lane boots the newest installed 6.1 amd64 kernel that has headers.
kver=$("$TOP/scripts/kver.sh")
[ "$kver" != none ] || die "no amd64 6.1 kernel with headers after install"

# The fetches below fill $ADVEE_CACHE, which the clones of this machine share:
# one deps.sh at a time does it, a second one then finds everything there.
mkdir -p "$ADVEE_CACHE"
exec 9>"$ADVEE_CACHE/.deps.lock"
flock 9

# ARM kernels for cross builds and the ARM VM lane (cached in $ADVEE_CACHE/arm).
arm_tree armhf armmp >/dev/null
arm_tree armel marvell >/dev/null
# The Debian armhf tools the ARM VM lane's shell programs call.
"$TOP/scripts/fetch-arm-userland.sh" armhf >/dev/null
# Debian's 6.12 amd64 kernels (stock and PREEMPT_RT) from bookworm-backports,
# with linux-source-6.12 (cached in $ADVEE_CACHE/bpo/amd64).
"$TOP/scripts/fetch-bpo-kernel.sh" >/dev/null
# checkpatch and modpost sources from linux-source-6.1 and -6.12 (cached in
# $ADVEE_CACHE/linux-source, linux-source-6.12).
"$TOP/scripts/kernel-source.sh" >/dev/null
"$TOP/scripts/kernel-source.sh" 6.12 >/dev/null
say "dependencies ready (x86_64 kernel $kver)"
