# SPDX-License-Identifier: GPL-2.0
# tap.sh - TAP 13 helpers for the project's shell tests (source it).
# Works in bash and in POSIX sh (dash).
#   tap_plan N; tap_ok "desc" cmd args...; tap_is "desc" got want;
#   tap_skip "desc" "reason"; tap_diag "text"; tap_finish (use as the exit code)
#   tap_require_module MODULE (before tap_plan: skip the whole program without it)

TAP_N=0
TAP_FAILED=0
TAP_SKIPPED=0
TAP_PLANNED=0

# tap_require_module MODULE: when the running kernel cannot load MODULE (for
# example gpio-sim, which Debian's stock kernel lacks and the debug lane's
# kernel has), skip the whole program visibly: "1..0 # SKIP reason", exit 4.
tap_require_module() {
	modprobe -n -q "$1" 2>/dev/null && return 0
	printf 'TAP version 13\n1..0 # SKIP module %s is not available in kernel %s (it is in the debug lane: tests/harness/vm-debug.sh)\n' \
		"$1" "$(uname -r)"
	exit 4
}

tap_plan() { TAP_PLANNED=$1; printf 'TAP version 13\n1..%s\n' "$1"; }
tap_diag() { printf '# %s\n' "$*"; }

tap_result() {	# tap_result STATUS(0=ok) DESC
	TAP_N=$((TAP_N + 1))
	if [ "$1" -eq 0 ]; then
		printf 'ok %d %s\n' "$TAP_N" "$2"
	else
		printf 'not ok %d %s\n' "$TAP_N" "$2"
		TAP_FAILED=$((TAP_FAILED + 1))
	fi
	return "$1"
}

# tap_ok DESC CMD...: the command's exit status decides; its output is shown as diagnostics.
tap_ok() {
	_desc=$1; shift
	_out=$("$@" 2>&1); _rc=$?
	[ "$_rc" -ne 0 ] && [ -n "$_out" ] && printf '%s\n' "$_out" | sed 's/^/# /'
	tap_result "$_rc" "$_desc"
}

# tap_is DESC GOT WANT
tap_is() {
	if [ "$2" = "$3" ]; then
		tap_result 0 "$1"
	else
		printf '# got:  %s\n# want: %s\n' "$2" "$3"
		tap_result 1 "$1"
	fi
}

tap_skip() {
	TAP_N=$((TAP_N + 1)); TAP_SKIPPED=$((TAP_SKIPPED + 1))
	printf 'ok %d %s # SKIP %s\n' "$TAP_N" "$1" "$2"
}

tap_finish() {
	if [ "$TAP_PLANNED" -ne 0 ] && [ "$TAP_N" -ne "$TAP_PLANNED" ]; then
		tap_diag "planned $TAP_PLANNED tests but ran $TAP_N"
		return 1
	fi
	[ "$TAP_FAILED" -eq 0 ] || return 1
	[ "$TAP_N" -gt 0 ] && [ "$TAP_SKIPPED" -eq "$TAP_N" ] && return 4
	return 0
}

# fuzz_size CI FULL: print the size of a fuzz program for VMTEST_FUZZ_SCALE
# (ci, the default: CI; full: FULL; docs/testing.md); any other value fails.
fuzz_size() {
	case ${VMTEST_FUZZ_SCALE:-ci} in
	ci) echo "$1" ;;
	full) echo "$2" ;;
	*) echo "VMTEST_FUZZ_SCALE=$VMTEST_FUZZ_SCALE: ci or full" >&2; return 1 ;;
	esac
}
