# SPDX-License-Identifier: GPL-2.0
# wait.sh - waiting for a condition with a deadline, for the project's shell
# tests (source it; bash and busybox sh). A test synchronises on what it
# needs (a file appeared, a line was logged, a process ended, a socket is
# open), never on a fixed `sleep`: under TCG on a shared host a fixed sleep is
# either too short (a flaky test) or much too long (a slow one).
# Deadlines are wall-clock seconds (decimals allowed), measured on
# /proc/uptime, so a slow condition check does not stretch them.
#
#   wait_until SECONDS CMD...       CMD succeeds (retried every 0.1 s)
#   wait_path PATH SECONDS          PATH exists
#   wait_line FILE ERE SECONDS [N]  a line of FILE (after its first N lines)
#                                   matches; on timeout the file's tail as
#                                   TAP diagnostics
#   wait_lines FILE ERE COUNT SECONDS   at least COUNT matching lines
#   wait_gone PID SECONDS           the process has ended (any parent)
#   wait_exit PID SECONDS           exit status of a child, 255 on timeout
#   pid_tree PID                    PID and its descendants, one per line
#   wait_udp_bound PID PORT SECONDS PID (or a descendant) holds a UDP socket
#                                   bound to PORT (an LCM subscriber)
#   uptime_cs                       sets UPTIME_CS: /proc/uptime in 1/100 s
#   nap SECONDS                     sleep without starting a process (bash)

# uptime_cs: UPTIME_CS = seconds since boot x 100 (no subshell: a fork costs
# tens of ms under TCG).
uptime_cs() {
	read -r _wait_up _wait_idle </proc/uptime
	UPTIME_CS=$((${_wait_up%.*} * 100 + 1${_wait_up#*.} - 100))
}

# nap SECONDS: sleep without starting a process where the shell allows it.
# An external sleep(1) costs about 45 ms of CPU per call under TCG (a guest
# polling every 0.1 s with it spent 9.6 CPU-s more in 30 s than with this),
# so every wait loop kept half a core busy, more under load and on the debug
# kernel. bash: a read with a timeout on a FIFO nobody writes to, opened
# read-write for that read only (no descriptor stays open for children to
# inherit); other shells, or without a FIFO: sleep(1).
nap() {
	if [ -n "${BASH_VERSION:-}" ]; then
		if [ -z "${_WAIT_NAP_FIFO:-}" ]; then
			_WAIT_NAP_FIFO=${VMTEST_SCRATCH:-${TMPDIR:-/tmp}}/.wait-nap.$$
			[ -p "$_WAIT_NAP_FIFO" ] || mkfifo "$_WAIT_NAP_FIFO" 2>/dev/null ||
				_WAIT_NAP_FIFO=none
		fi
		if [ "$_WAIT_NAP_FIFO" != none ]; then
			read -r -t "$1" _wait_nap <>"$_WAIT_NAP_FIFO" || :
			return 0
		fi
	fi
	sleep "$1"
}

# _wait_secs_cs SECONDS: "2", "0.5", "1.25" -> 1/100 s in _WAIT_CS.
_wait_secs_cs() {
	case $1 in
	*.*)
		_wait_f=${1#*.}00
		_wait_f=${_wait_f%"${_wait_f#??}"}
		_WAIT_CS=$((${1%%.*}0 / 10 * 100 + 1$_wait_f - 100))
		;;
	*) _WAIT_CS=$(($1 * 100)) ;;
	esac
}

wait_until() {
	local end
	_wait_secs_cs "$1"
	shift
	uptime_cs
	end=$((UPTIME_CS + _WAIT_CS))
	while :; do
		"$@" && return 0
		uptime_cs
		[ "$UPTIME_CS" -ge "$end" ] && return 1
		nap 0.1
	done
}

wait_path() { wait_until "$2" test -e "$1"; }

_wait_line_in() { tail -n +"$(($3 + 1))" "$1" 2>/dev/null | grep -qE -- "$2"; }
wait_line() {
	wait_until "$3" _wait_line_in "$1" "$2" "${4:-0}" && return 0
	echo "# timed out after $3 s waiting for /$2/ in $1${4:+ after line $4}:"
	tail -20 "$1" 2>/dev/null | sed 's/^/#   /'
	return 1
}

_wait_count() { [ "$(grep -cE -- "$2" "$1" 2>/dev/null)" -ge "$3" ]; }
wait_lines() {
	wait_until "$4" _wait_count "$1" "$2" "$3" && return 0
	echo "# timed out after $4 s waiting for $3 lines /$2/ in $1 (have $(grep -cE -- "$2" "$1" 2>/dev/null))"
	return 1
}

_wait_dead() { ! kill -0 "$1" 2>/dev/null; }
wait_gone() { wait_until "$2" _wait_dead "$1"; }

wait_exit() {
	wait_gone "$1" "$2" || return 255
	wait "$1"
}

pid_tree() {
	local c
	echo "$1"
	for c in $(pgrep -P "$1"); do pid_tree "$c"; done
}

# _wait_udp PID PORT: a socket of PID's tree is in /proc/net/udp with local
# port PORT (the receive socket LCM binds when a channel is subscribed).
_wait_udp() {
	local inodes p
	inodes=$(awk -v port="$(printf ':%04X' "$2")" '$2 ~ port "$" { printf "socket:[%s]\n", $10 }' /proc/net/udp)
	[ -n "$inodes" ] || return 1
	# The process itself first: its descendants cost a pgrep each.
	ls -l "/proc/$1/fd" 2>/dev/null | grep -qF "$inodes" && return 0
	for p in $(pid_tree "$1" | tail -n +2); do
		ls -l "/proc/$p/fd" 2>/dev/null | grep -qF "$inodes" && return 0
	done
	return 1
}
wait_udp_bound() { wait_until "$3" _wait_udp "$1" "$2"; }
