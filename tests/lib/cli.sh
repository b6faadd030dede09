# SPDX-License-Identifier: GPL-2.0
# shellcheck shell=bash
# cli.sh - the command-line conventions of every installed program
# (docs/command-line.md, userland/common/include/advee/cli.hpp), as TAP
# points (source it after tests/lib/tap.sh):
#   cli_programs                 the programs of the install manifest
#                                (docs/install.md): /usr/bin, /usr/sbin and
#                                /usr/libexec/advee/NAME, one path a line; a
#                                new program cannot escape the checks;
#                                not the compatibility aliases
#   cli_aliases                  those aliases: "PATH TARGET" a line (the
#                                manifest's "(alias of TARGET: why)")
#   cli_name_ok PATH             whether PATH's name follows the naming rule
#                                (docs/command-line.md "Names"): in /usr/bin
#                                and /usr/sbin it starts with "advee-" and
#                                has no "_"; /usr/libexec/advee is the
#                                namespace of the daemons' thesis names
#   cli_check_alias ROOT PATH TARGET  2 points: ROOT/PATH is a symlink to
#                                TARGET and --version answers as TARGET
#   cli_version                  the version of the build (debian/changelog),
#                                read once (dpkg-parsechangelog is a Perl
#                                program: over a second a call under TCG)
#   cli_check ROOT PATH [TODO]   3 points for ROOT/PATH: a bad option exits 2
#                                naming the option on stderr, nothing on
#                                stdout; --version prints "NAME VERSION" and
#                                exits 0; --help exits 0 with text on stdout.
#                                TODO: the reason for "# TODO" on its points
#                                (a known defect, counted like a skip)

CLI_REPO=${CLI_REPO:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}

cli_manifest() { sed -n '/<!-- manifest:begin -->/,/<!-- manifest:end -->/p' "$CLI_REPO/docs/install.md"; }

cli_programs() {
	cli_manifest | awk '$2 != "(alias" && ($1 ~ "^/usr/(bin|sbin)/[^/*]+$" || $1 ~ "^/usr/libexec/advee/[^/*]+$") { print $1 }'
}

cli_aliases() {
	cli_manifest | awk '$2 == "(alias" && $3 == "of" { t = $4; sub(":$", "", t); print $1, t }'
}

cli_name_ok() {
	case $1 in
	/usr/bin/advee-* | /usr/sbin/advee-*) case ${1##*/} in *_*) return 1 ;; esac ;;
	/usr/libexec/advee/*) ;;
	*) return 1 ;;
	esac
}

cli_version() { dpkg-parsechangelog -l "$CLI_REPO/debian/changelog" -S Version; }
CLI_VERSION=	# cli_check's copy of it, read on its first call

# cli_run OUT ERR PROGRAM ARGS...: stdout and stderr into files, the status
# echoed; 10 s at most (a program that starts work on a bad option hangs).
cli_run() {
	local out=$1 err=$2 rc=0
	shift 2
	timeout 10 "$@" </dev/null >"$out" 2>"$err" || rc=$?
	echo "$rc"
}

# cli_result STATUS DESC TODO: a TAP point; with TODO, a failure is printed
# "not ok ... # TODO why" and not counted as one (tap_finish ignores it).
cli_result() {
	if [ "$1" != 0 ] && [ -n "$3" ]; then
		TAP_N=$((TAP_N + 1))
		printf 'not ok %d %s # TODO %s\n' "$TAP_N" "$2" "$3"
	else
		tap_result "$1" "$2${3:+ # TODO $3}"
	fi
}

cli_check_alias() {
	local root=$1 path=$2 target=$3 out
	tap_is "${path##*/}: a symlink to $target (compatibility alias)" "$(readlink "$root$path")" "$target"
	[ -n "$CLI_VERSION" ] || CLI_VERSION=$(cli_version)
	out=$(timeout 10 "$root$path" --version </dev/null 2>&1) || true
	tap_is "${path##*/} --version: the program it names" "$out" "$target $CLI_VERSION"
}

cli_check() {
	local root=$1 path=$2 todo=${3:-} name scratch rc want
	name=${path##*/}
	scratch=$(mktemp -d)
	# The option no program has; the message must name it.
	rc=$(cli_run "$scratch/out" "$scratch/err" "$root$path" --no-such-option-x9)
	if [ "$rc" = 2 ] && grep -q -- '--no-such-option-x9' "$scratch/err" && [ ! -s "$scratch/out" ]; then
		cli_result 0 "$name: a bad option exits 2 and names it on stderr" "$todo"
	else
		tap_diag "$name --no-such-option-x9: exit $rc; stderr: $(head -c 300 "$scratch/err" | tr '\n' ' ')"
		tap_diag "stdout: $(head -c 200 "$scratch/out" | tr '\n' ' ')"
		cli_result 1 "$name: a bad option exits 2 and names it on stderr" "$todo"
	fi
	[ -n "$CLI_VERSION" ] || CLI_VERSION=$(cli_version)
	want="$name $CLI_VERSION"
	rc=$(cli_run "$scratch/out" "$scratch/err" "$root$path" --version)
	if [ "$rc" = 0 ] && [ "$(cat "$scratch/out")" = "$want" ]; then
		cli_result 0 "$name --version: '$want', exit 0" "$todo"
	else
		tap_diag "$name --version: exit $rc; stdout: $(head -c 200 "$scratch/out" | tr '\n' ' ') stderr: $(head -c 200 "$scratch/err" | tr '\n' ' ')"
		cli_result 1 "$name --version: '$want', exit 0" "$todo"
	fi
	rc=$(cli_run "$scratch/out" "$scratch/err" "$root$path" --help)
	if [ "$rc" = 0 ] && grep -q -- '--version' "$scratch/out"; then
		cli_result 0 "$name --help: exit 0, the options (with --version) on stdout" "$todo"
	else
		tap_diag "$name --help: exit $rc; stderr: $(head -c 200 "$scratch/err" | tr '\n' ' ')"
		cli_result 1 "$name --help: exit 0, the options (with --version) on stdout" "$todo"
	fi
	rm -rf "$scratch"
}
