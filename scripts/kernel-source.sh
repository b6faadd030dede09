#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# kernel-source.sh [PATH...]: extract parts of Debian's linux-source-6.1
# tarball (the sources of the kernel we run) into .cache/linux-source and print
# that directory. Used for checkpatch.pl and for building a modpost that knows
# ARM's struct layouts. Never committed.
set -euo pipefail
. "$(dirname "$0")/lib.sh"

tarball=$(ls /usr/src/linux-source-6.1.tar.* 2>/dev/null | head -1)
[ -n "$tarball" ] || die "linux-source-6.1 is not installed (run: make deps)"
dest=${ADVEE_CACHE:-$TOP/.cache}/linux-source
mkdir -p "$dest"
# The parts every tool of ours needs; callers may ask for more.
want=(scripts/mod scripts/checkpatch.pl scripts/spelling.txt scripts/const_structs.checkpatch
	include/linux/license.h "$@")
missing=()
for p in "${want[@]}"; do
	[ -e "$dest/$p" ] || missing+=("linux-source-6.1/$p")
done
if [ "${#missing[@]}" -gt 0 ]; then
	say "extracting ${#missing[@]} path(s) from $(basename "$tarball")"
	tar -xf "$tarball" -C "$dest" --strip-components=1 "${missing[@]}" ||
		die "cannot extract ${missing[*]} from $tarball"
fi
echo "$dest"
