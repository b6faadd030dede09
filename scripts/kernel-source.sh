#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# kernel-source.sh [6.12] [PATH...]: extract parts of Debian's linux-source-6.1
# tarball (the sources of the kernel we run) into $ADVEE_CACHE/linux-source (lib.sh), or of
# bookworm-backports' linux-source-6.12 (fetch-bpo-kernel.sh) into
# $ADVEE_CACHE/linux-source-6.12, and print that directory. Used for checkpatch.pl,
# for the private headers ts7800-can checks its copy against and for
# building a modpost that knows ARM's struct layouts. Never committed.
set -euo pipefail
. "$(dirname "$0")/lib.sh"

series=6.1 dest=$ADVEE_CACHE/linux-source
if [ "${1:-}" = 6.12 ]; then
	series=6.12 dest=$dest-6.12
	tarball=$(ls "$("$TOP/scripts/fetch-bpo-kernel.sh")"/usr/src/linux-source-6.12.tar.* | head -1)
	shift
else
	tarball=$(ls /usr/src/linux-source-6.1.tar.* 2>/dev/null | head -1)
fi
[ -n "$tarball" ] || die "linux-source-$series is not installed (run: make deps)"
mkdir -p "$dest"
# The parts every tool of ours needs; callers may ask for more.
want=(scripts/mod scripts/checkpatch.pl scripts/spelling.txt scripts/const_structs.checkpatch
	include/linux/license.h "$@")
missing=()
for p in "${want[@]}"; do
	[ -e "$dest/$p" ] || missing+=("linux-source-$series/$p")
done
if [ "${#missing[@]}" -gt 0 ]; then
	say "extracting ${#missing[@]} path(s) from $(basename "$tarball")"
	tar -xf "$tarball" -C "$dest" --strip-components=1 "${missing[@]}" ||
		die "cannot extract ${missing[*]} from $tarball"
fi
echo "$dest"
