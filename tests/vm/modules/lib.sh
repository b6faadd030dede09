# SPDX-License-Identifier: GPL-2.0
# Helpers of the modules VM suite (sourced): LCM over UDP multicast on the
# guest's loopback (tests/lib/lcm.sh), the userland binaries, background
# processes and listeners, and the simulated BR-FAN1 of the dio-i2c suite
# (sim_load, adapter_load, chip_set, cleanup_all).

. "$VMTEST_REPO/tests/vm/dio-i2c/lib.sh"
. "$VMTEST_REPO/tests/lib/lcm.sh"

UL=$VMTEST_BUILD/userland
WATCHDOG=$UL/watchdog/advee-watchdog
DRIVER_AUX=$UL/daemons/driver_aux/driver_aux
TEST_MODULE=$UL/module/advee-test-module
LCMCTL=$UL/module/advee-lcmctl
PROBE=$UL/daemons/driver_rs485/advee-daemons-probe
BG_PIDS=
LISTEN_PID=

# bg CMD...: start CMD in the background, remembered for bg_kill_all.
bg() {
	"$@" &
	BG_PIDS="$BG_PIDS $!"
	LAST_BG=$!
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

# listen_bg FILE CHANNEL...: advee-daemons-probe listening (for at most 5
# minutes) in the background, one decoded line per message into FILE;
# returns once it has subscribed, with its pid in LISTEN_PID.
listen_bg() {
	local out=$1
	shift
	bg "$PROBE" listen 300 "$@" >"$out"
	LISTEN_PID=$LAST_BG
	wait_lcm_listening "$LISTEN_PID" 20 || { echo "# advee-daemons-probe listen did not subscribe within 20 s"; return 1; }
}
# listen_stop [PID]: end a listener (default: the last one started).
listen_stop() {
	kill "${1:-$LISTEN_PID}" 2>/dev/null
	wait "${1:-$LISTEN_PID}" 2>/dev/null
	return 0
}

# wait_state MODULE STATE SECONDS [PID]: MODULE (the instance PID) announced
# STATE on CM_DATA_STATE (3 RUN: it has subscribed to its channels and runs
# its loop; 6 PAUSE). Announcements come every second and on each change.
wait_state() {
	local out=$VMTEST_SCRATCH/wait_state.out rc outer=$LISTEN_PID
	listen_bg "$out" CM_DATA_STATE || return 1
	wait_line "$out" "^CM_DATA_STATE .* module=$1 state=$2 pid=${4:-[0-9]+}\$" "$3"
	rc=$?
	listen_stop
	LISTEN_PID=$outer
	return $rc
}

# echo_msgs COUNT TIMEOUT CHANNEL...: decoded messages, one per line.
echo_msgs() {
	_n=$1 _t=$2
	shift 2
	"$LCMCTL" echo --count "$_n" --timeout "$_t" "$@"
}

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
	wait_until 5 hwmon_found
}
hwmon_found() {
	HWMON=$(grep -l '^max6615$' /sys/class/hwmon/hwmon*/name 2>/dev/null | head -1)
	[ -n "$HWMON" ] && HWMON=${HWMON%/name}
}

modules_cleanup() {
	bg_kill_all
	lcm_net_down
	cleanup_all
}

now_ms() { echo $(( $(date +%s%N) / 1000000 )); }
