# SPDX-License-Identifier: GPL-2.0
# Helpers of the daemons VM suite (sourced): LCM on the guest's loopback and
# the background-process helpers of the modules suite, the simulated FPGA
# and advee-rs485-sim of the rs485 suite, and the daemons' binaries.
. "$VMTEST_REPO/tests/vm/modules/lib.sh"
. "$VMTEST_REPO/tests/vm/rs485/common.inc"

DAEMONS=$VMTEST_BUILD/userland/daemons
DRIVER_RS485=$DAEMONS/driver_rs485/driver_rs485
DRIVER_POWER=$DAEMONS/driver_power/driver_power
DRIVER_CANBUS=$DAEMONS/driver_canbus/driver_canbus
RS485CTL=$LIBBIN/advee-rs485ctl
DSUITE=$VMTEST_REPO/tests/vm/daemons

daemons_cleanup() {
	bg_kill_all
	rs485_cleanup
	lcm_net_down
}

# daemons_rs485_up PROGRAM...: LCM route, simulated FPGA, advee-rs485-sim with
# the robot's boards (boards.yaml); bails out if anything is missing.
daemons_rs485_up() {
	rs485_setup "$SIMBIN/advee-rs485-sim" "$PROBE" "$LCMCTL" "$@"
	trap daemons_cleanup EXIT
	lcm_net_up || { echo "Bail out! cannot set up loopback multicast"; exit 1; }
	if ! start_sim "$DSUITE/boards.yaml"; then
		echo "Bail out! advee-rs485-sim did not start"
		sed 's/^/# /' "$SCR/sim.err"
		exit 1
	fi
}

# listen_for COUNT SECONDS CHANNEL...: decoded messages into $SCR/listen.out
# until COUNT of the first CHANNEL have come (at most SECONDS).
listen_for() {
	local n=$1 secs=$2 rc outer=$LISTEN_PID
	shift 2
	listen_bg "$SCR/listen.out" "$@" || return 1
	wait_lines "$SCR/listen.out" "^$1 " "$n" "$secs"
	rc=$?
	listen_stop
	LISTEN_PID=$outer
	return $rc
}
count() { grep -c "^$1 " "$SCR/listen.out"; }
last() { grep "^$1 " "$SCR/listen.out" | tail -1; }

# mean_field CHANNEL KEY: mean of KEY over the lines of CHANNEL in listen.out.
mean_field() {
	grep "^$1 " "$SCR/listen.out" | tr ' ' '\n' | sed -n "s/^$2=//p" |
		awk '{ s += $1; n++ } END { if (n) printf "%.4f\n", s / n }'
}

# The CAN side of the driver_canbus tests: vcan0 and advee-canopen-sim-drive.
CANBIN=$VMTEST_BUILD/userland/canopen
IF=vcan0
SIMS=()

canbus_cleanup() {
	bg_kill_all
	local p
	for p in "${SIMS[@]}" $CANDUMP_PID; do kill "$p" 2>/dev/null; done
	for p in "${SIMS[@]}"; do wait "$p" 2>/dev/null; done
	ip link del "$IF" 2>/dev/null
	modprobe -r vcan can_raw can 2>/dev/null
	lcm_net_down
	rm -rf "$SCR"
}

# canbus_up PROGRAM...: the programs and the simulator are built, LCM on
# loopback, vcan0 up (bails out otherwise); cleans up on exit.
canbus_up() {
	local b
	for b in "$@" "$CANBIN/advee-canopen-sim-drive"; do
		[ -x "$b" ] || { echo "Bail out! $b not built"; exit 1; }
	done
	trap canbus_cleanup EXIT
	lcm_net_up || { echo "Bail out! cannot set up loopback multicast"; exit 1; }
	modprobe vcan || { echo "Bail out! modprobe vcan"; exit 1; }
	ip link add dev "$IF" type vcan 2>/dev/null
	ip link set "$IF" txqueuelen 1000
	ip link set up "$IF" || { echo "Bail out! cannot bring $IF up"; exit 1; }
}

# sim_drive NAME ARGS...: a simulated drive; its pid in SIM_<NAME>.
sim_drive() {
	local name=$1
	shift
	"$CANBIN/advee-canopen-sim-drive" -i "$IF" "$@" >>"$SCR/$name.log" 2>&1 &
	SIMS+=($!)
	eval "SIM_$name=$!"
	wait_line "$SCR/$name.log" "ready on" 20 >/dev/null
}

# canbus_sims_up: the EPOS (node 1) and the IclA (node 2) simulators; bails out.
canbus_sims_up() {
	sim_drive epos -n 1 -p epos || { echo "Bail out! EPOS simulator"; exit 1; }
	sim_drive icla -n 2 -p icla || { echo "Bail out! IclA simulator"; exit 1; }
}

# canbus_config FILE: driver_canbus on $IF with heartbeats that have more
# slack than on the robot (300 ms / 500 ms there): a TCG guest on a busy host
# stalls for half a second now and then, and each stall would otherwise read
# as a lost drive or a lost master.
canbus_config() {
	cat >"$1" <<EOC
module: {name: driver_canbus, print_severity: notice, send_severity: notice}
driver_canbus:
  interface: $IF
  command_timeout_s: 1.0
  propulsion: {heartbeat_ms: 250, master_timeout_ms: 2000}
  steering: {heartbeat_ms: 250, master_timeout_ms: 2000}
EOC
}
