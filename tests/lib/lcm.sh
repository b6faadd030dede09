# SPDX-License-Identifier: GPL-2.0
# lcm.sh - LCM on the guest's loopback for the user-space VM suites (source
# it; bash). docs/modules.md: LCM is UDP multicast; the guest has only the
# loopback, so it needs a multicast route there.
#
#   lcm_net_up / lcm_net_down   loopback up with the multicast route (removed
#                               again only if lcm_net_up added it)
#   wait_lcm_listening PID [SECONDS]   PID (or a child) has subscribed: its
#                               LCM receive socket is bound (default 10 s)
#   field LINE KEY              value of KEY=value in a decoded line
#   close_to VALUE WANT TOL     |VALUE - WANT| <= TOL (numbers)
#   rate_check FILE CHANNEL HZ  the rate of CHANNEL in a listener's output
#                               (lines "CHANNEL t=SECONDS ..."), see below
#   tap_rate DESC FILE CHANNEL HZ   rate_check as a TAP point
. "$VMTEST_REPO/tests/lib/wait.sh"

export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
LCM_PORT=7667
LCM_ROUTE_ADDED=0

lcm_net_up() {
	ip link set lo up || return 1
	if ! ip route show table all | grep -q '^multicast\|224.0.0.0/4'; then
		ip route add 224.0.0.0/4 dev lo || return 1
		LCM_ROUTE_ADDED=1
	fi
}

lcm_net_down() {
	[ "$LCM_ROUTE_ADDED" = 1 ] && ip route del 224.0.0.0/4 dev lo 2>/dev/null
	LCM_ROUTE_ADDED=0
	return 0
}

# LCM binds its receive socket when the first channel is subscribed; from
# then on every message sent reaches the process.
wait_lcm_listening() { wait_udp_bound "$1" "$LCM_PORT" "${2:-10}"; }

field() { printf '%s\n' "$1" | tr ' ' '\n' | sed -n "s/^$2=//p" | head -1; }

close_to() { awk -v v="$1" -v w="$2" -v t="$3" 'BEGIN { d = v - w; if (d < 0) d = -d; exit !(v != "" && d <= t) }'; }

# rate_check FILE CHANNEL HZ: a count over a measured interval. N messages of
# CHANNEL span N - 1 periods from the first receive time t= to the last;
# their rate must be HZ within -50 % / +50 %: a wrong rate (another
# configuration, a poll that takes too long, a double publish) fails, while
# TCG on a shared host, which stalls the whole guest for up to a second now
# and then, does not. At least 4 messages (3 periods) are needed. Prints
# "N messages, N-1 periods in T s = R Hz (want LO..HI)" for the TAP
# description and returns the verdict.
rate_check() {
	grep "^$2 " "$1" | sed -n 's/^[^ ]* t=\([0-9.]*\) .*/\1/p' | awk -v hz="$3" '
		NR == 1 { t0 = $1 } { t1 = $1; n++ }
		END {
			lo = hz * 0.5; hi = hz * 1.5
			if (n < 4 || t1 <= t0) { printf "%d messages: too few to measure (want >= 4 at %g Hz)\n", n, hz; exit 1 }
			r = (n - 1) / (t1 - t0)
			printf "%d messages, %d periods in %.2f s = %.2f Hz (want %g..%g)\n", n, n - 1, t1 - t0, r, lo, hi
			exit !(r >= lo && r <= hi)
		}'
}

tap_rate() {
	local r rc
	r=$(rate_check "$2" "$3" "$4")
	rc=$?
	tap_result "$rc" "$1: $r"
}
