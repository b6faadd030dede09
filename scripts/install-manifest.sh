#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# install-manifest.sh DESTDIR KVER [TARGET]: compare a staging install with
# the file list of docs/install.md (the block between <!-- manifest:begin -->
# and <!-- manifest:end -->). A line is a path, <kver> stands for the kernel
# release, a * matches any characters (also /). Every path is required on
# every target (native, armhf, armel; default native) unless the line says
# "(not on TARGET...: why)": then it must be absent there; a line
# "(alias of NAME: why)" must be a symlink to NAME (docs/command-line.md
# "Names"). Prints every
# required path that is missing, every excluded one that is there and every
# installed file that is not listed; exits 1 on any.
set -euo pipefail
. "$(dirname "$0")/lib.sh"

dest=${1:?staging root}
kver=${2:?kernel release}
target=${3:-native}
case $target in native|armhf|armel) ;; *) die "install-manifest.sh: unknown target $target" ;; esac
entries=$(sed -n '/<!-- manifest:begin -->/,/<!-- manifest:end -->/p' "$TOP/docs/install.md" |
	grep '^/' | sed "s/<kver>/$kver/g")
[ -n "$entries" ] || die "no manifest block in docs/install.md"

bad=0
files=$(cd "$dest" && find . \( -type f -o -type l \) | sed 's/^\.//' | sort)
# Every listed path is there, unless excluded for this target.
while read -r path rest; do
	re=$(printf '%s' "$path" | sed 's/[].[^$\\]/\\&/g; s/\*/.*/g')
	excluded=0
	case $rest in
	'') ;;
	'(not on '*': '*')')
		for t in $(printf '%s' "$rest" | sed 's/^(not on \([^:]*\):.*/\1/'); do
			[ "$t" = "$target" ] && excluded=1
		done ;;
	'(alias of '*': '*')')
		to=$(printf '%s' "$rest" | sed 's/^(alias of \([^:]*\):.*/\1/')
		[ "$(readlink "$dest$path" 2>/dev/null)" = "$to" ] ||
			{ echo "not a symlink to $to: $path"; bad=1; } ;;
	*) echo "docs/install.md: '$path $rest': only '(not on TARGET...: why)' or '(alias of NAME: why)' may follow a path"; bad=1; continue ;;
	esac
	if grep -qx "$re" <<<"$files"; then
		[ $excluded = 1 ] && { echo "installed although not shipped on $target: $path $rest"; bad=1; }
	else
		[ $excluded = 1 ] || { echo "missing on $target: $path"; bad=1; }
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
