# SPDX-License-Identifier: GPL-2.0
# Helpers of the modules VM suite (sourced): LCM over UDP multicast on the
# guest's loopback, the userland binaries, and the simulated BR-FAN1 of the
# dio-i2c suite (sim_load, adapter_load, chip_set, cleanup_all).

. "$VMTEST_REPO/tests/vm/dio-i2c/lib.sh"

UL=$VMTEST_BUILD/userland
WATCHDOG=$UL/watchdog/advee-watchdog
DRIVER_AUX=$UL/daemons/driver_aux/driver_aux
TEST_MODULE=$UL/module/advee-test-module
LCMCTL=$UL/module/advee-lcmctl
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
ROUTE_ADDED_BY_US=0
BG_PIDS=

# net_setup: loopback up with a multicast route (the guest has no other
# interface), so LCM's UDP multicast reaches every process in the guest.
net_setup() {
	ip link set lo up || return 1
	if ! ip route show table all | grep -q '^multicast\|224.0.0.0/4'; then
		ip route add 224.0.0.0/4 dev lo || return 1
		ROUTE_ADDED_BY_US=1
	fi
}

net_teardown() {
	[ "$ROUTE_ADDED_BY_US" = 1 ] && ip route del 224.0.0.0/4 dev lo 2>/dev/null
	ROUTE_ADDED_BY_US=0
	return 0
}

# bg CMD...: start CMD in the background, remembered for bg_kill_all.
bg() {
	"$@" &
	BG_PIDS="$BG_PIDS $!"
	LAST_BG=$!
}

# close_to VALUE WANT TOLERANCE: |VALUE - WANT| <= TOLERANCE (numbers).
close_to() { awk -v v="$1" -v w="$2" -v t="$3" 'BEGIN { d = v - w; if (d < 0) d = -d; exit !(v != "" && d <= t) }'; }

# wait_exit PID SECONDS: the exit status of a background process, 255 if it
# did not end in time.
wait_exit() {
	local i
	for ((i = 0; i < $2 * 10; i++)); do
		if ! kill -0 "$1" 2>/dev/null; then
			wait "$1"
			return $?
		fi
		sleep 0.1
	done
	return 255
}

bg_kill_all() {
	for p in $BG_PIDS; do
		kill "$p" 2>/dev/null
	done
	for p in $BG_PIDS; do
		wait "$p" 2>/dev/null
	done
	BG_PIDS=
	return 0
}

# echo_msgs COUNT TIMEOUT CHANNEL...: decoded messages, one per line.
echo_msgs() {
	_n=$1 _t=$2
	shift 2
	"$LCMCTL" echo --count "$_n" --timeout "$_t" "$@"
}

# field LINE KEY: the value of key=value in an echo line.
field() { printf '%s\n' "$1" | tr ' ' '\n' | sed -n "s/^$2=//p" | head -1; }

# first_other MODULE OLDPID: from echo lines on stdin, the first CM_DATA_STATE
# of MODULE sent by a pid other than OLDPID. A shell loop, not awk: mawk
# reads a pipe in blocks and would see the line only when the writer exits.
first_other() {
	while read -r _ch _mod _st _pid; do
		if [ "$_mod" = "module=$1" ] && [ "$_pid" != "pid=$2" ]; then
			echo "$_ch $_mod $_st $_pid"
			return 0
		fi
	done
	return 1
}

# state_pid MODULE STATE TIMEOUT: pid of the first announcement of MODULE in
# STATE within TIMEOUT seconds (empty if none).
state_pid() {
	"$LCMCTL" echo --timeout "$3" CM_DATA_STATE | while read -r _ch _mod _st _pid; do
		if [ "$_mod" = "module=$1" ] && [ "$_st" = "state=$2" ]; then
			echo "${_pid#pid=}"
			break
		fi
	done
}

# aux_config FILE RATE: driver_aux configuration for the simulated board.
aux_config() {
	cat >"$1" <<EOC
module: {name: driver_aux, print_severity: notice, send_severity: warning}
driver_aux:
  hwmon_name: max6615
  rate_hz: $2
  fan_fail: {line: DIO_7}
EOC
}

# board_up: simulated FPGA + DIO + I2C adapter + max6615 bound, known values.
board_up() {
	sim_load || return 1
	adapter_load || return 1
	chip_set temp1 31500
	chip_set temp2 44125
	chip_set fan1_rpm 1500
	chip_set fan2_rpm 900
	modprobe max6615 || return 1
	for _i in $(seq 50); do
		HWMON=$(grep -l '^max6615$' /sys/class/hwmon/hwmon*/name 2>/dev/null | head -1)
		[ -n "$HWMON" ] && HWMON=${HWMON%/name} && return 0
		sleep 0.1
	done
	return 1
}

modules_cleanup() {
	bg_kill_all
	net_teardown
	cleanup_all
}

now_ms() { echo $(( $(date +%s%N) / 1000000 )); }
