#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# debs-programs.sh [DIR]: over the file lists of the packages in DIR
# (build/debs, scripts/build-debs.sh): the programs they ship (/usr/bin,
# /usr/sbin, /usr/libexec/advee) are exactly those of the install manifest
# (docs/install.md), each has its man page (section 1 for /usr/bin, 8 for
# the daemons and the supervisor) and answers --version with "NAME VERSION",
# VERSION the package's; every name in /usr/bin and /usr/sbin starts with
# "advee-" (docs/command-line.md "Names") except the manifest's aliases,
# each a symlink to its program with that program's man page. Prints each
# problem; exits 1 on any.
set -euo pipefail
. "$(dirname "$0")/lib.sh"
. "$TOP/tests/lib/cli.sh"

dir=${1:-$BUILD/debs}
debs=("$dir"/*.deb)
[ -f "${debs[0]}" ] || die "no package in $dir (run scripts/build-debs.sh)"
root=$(mktemp -d)
trap 'rm -rf "$root"' EXIT
bad=0
problem() { echo "  $*"; bad=1; }
declare -A version
for deb in "${debs[@]}"; do
	dpkg-deb -x "$deb" "$root"
	while read -r f; do version[$f]=$(dpkg-deb -f "$deb" Version); done < <(
		dpkg-deb -c "$deb" | awk '{ print substr($6, 2) }' |
			grep -E '^/usr/(bin|sbin)/[^/]+$|^/usr/libexec/advee/[^/]+$' || true)
done
declare -A alias
while read -r a to; do alias[$a]=$to; done < <(cli_aliases)
shipped=$(printf '%s\n' "${!version[@]}" | sort)
manifest=$( (cli_programs; printf '%s\n' "${!alias[@]}") | sort)
[ "$shipped" = "$manifest" ] ||
	problem "the packages' programs differ from docs/install.md's (<: packages, >: manifest):" \
		"$(diff <(echo "$shipped") <(echo "$manifest") | grep '^[<>]' | tr '\n' ' ')"
n=0
for p in $shipped; do
	name=${p##*/}
	if [ -n "${alias[$p]:-}" ]; then
		to=${alias[$p]}
		[ "$(readlink "$root$p")" = "$to" ] || problem "$p: not a symlink to $to"
		[ "$(readlink "$root/usr/share/man/man1/$name.1.gz")" = "$to.1.gz" ] ||
			problem "$p: no man page usr/share/man/man1/$name.1.gz -> $to.1.gz"
		continue
	fi
	cli_name_ok "$p" || problem "$p: not named advee-* (docs/command-line.md \"Names\")"
	case $p in /usr/bin/*) sec=1 ;; *) sec=8 ;; esac
	[ -f "$root/usr/share/man/man$sec/$name.$sec.gz" ] || problem "$p: no man page usr/share/man/man$sec/$name.$sec.gz"
	got=$(timeout 10 "$root$p" --version 2>&1) || true
	[ "$got" = "$name ${version[$p]}" ] || problem "$p --version: '$got', want '$name ${version[$p]}'"
	n=$((n + 1))
done
say "$n programs in ${#debs[@]} packages: man page and --version checked"
exit $bad
