#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# install-manifest.sh DESTDIR KVER: compare a staging install with the file
# list of docs/install.md (the block between <!-- manifest:begin --> and
# <!-- manifest:end -->). A line is a path, <kver> stands for the kernel
# release, a * matches any characters (also /); "(when built)" after a path
# marks a file that comes with a component still being written. Prints every
# listed path that is missing and every installed file that is not listed;
# exits 1 on any.
set -euo pipefail
. "$(dirname "$0")/lib.sh"

dest=${1:?staging root}
kver=${2:?kernel release}
entries=$(sed -n '/<!-- manifest:begin -->/,/<!-- manifest:end -->/p' "$TOP/docs/install.md" |
	grep '^/' | sed "s/<kver>/$kver/g")
[ -n "$entries" ] || die "no manifest block in docs/install.md"

bad=0
files=$(cd "$dest" && find . \( -type f -o -type l \) | sed 's/^\.//' | sort)
# Every listed path is there (unless marked "(when built)").
while read -r path rest; do
	re=$(printf '%s' "$path" | sed 's/[].[^$\\]/\\&/g; s/\*/.*/g')
	if ! grep -qx "$re" <<<"$files"; then
		case $rest in
		*"(when built)"*) echo "not built yet: $path" ;;
		*) echo "missing: $path"; bad=1 ;;
		esac
	fi
done <<<"$entries"
# Every installed file is listed.
while read -r f; do
	[ -n "$f" ] || continue
	hit=0
	while read -r path _; do
		# shellcheck disable=SC2254 # the entry is a glob on purpose
		case $f in $path) hit=1; break ;; esac
	done <<<"$entries"
	[ $hit = 1 ] || { echo "not in docs/install.md: $f"; bad=1; }
done <<<"$files"
exit $bad
