# SPDX-License-Identifier: GPL-2.0
# Helpers of the robotsim VM suite (sourced): vcan0, the simulated FPGA with
# advee-rs485-sim and the robot's boards (tests/vm/daemons/boards.yaml), LCM on the
# loopback, advee-robot-sim with its drives on vcan0, advee-canopenctl, the true pose.
. "$VMTEST_REPO/tests/vm/modules/lib.sh"
. "$VMTEST_REPO/tests/vm/rs485/common.inc"

RS=$VMTEST_BUILD/userland/robotsim
ROBOT_SIM=$RS/advee-robot-sim
POSE=$RS/advee-robot-sim-pose
CANOPENCTL=$VMTEST_BUILD/userland/canopen/advee-canopenctl
RS485CTL=$VMTEST_BUILD/userland/rs485/advee-rs485ctl
CONF=$VMTEST_REPO/userland/robotsim/conf
IF=vcan0

robotsim_cleanup() {
	bg_kill_all
	ip link del "$IF" 2>/dev/null
	modprobe -r vcan can_raw can 2>/dev/null
	rs485_cleanup
	lcm_net_down
}

# robotsim_up PROGRAM...: everything but advee-robot-sim; bails out if a program
# is missing or something does not come up.
robotsim_up() {
	rs485_setup "$SIMBIN/advee-rs485-sim" "$ROBOT_SIM" "$POSE" "$CANOPENCTL" "$@"
	trap robotsim_cleanup EXIT
	lcm_net_up || { echo "Bail out! cannot set up loopback multicast"; exit 1; }
	modprobe n_rs485 || { echo "Bail out! modprobe n_rs485"; exit 1; }
	if ! modprobe vcan || ! ip link add dev "$IF" type vcan || ! ip link set up "$IF"; then
		echo "Bail out! cannot set up $IF"
		exit 1
	fi
	if ! start_sim "$VMTEST_REPO/tests/vm/daemons/boards.yaml"; then
		echo "Bail out! advee-rs485-sim did not start"
		sed 's/^/# /' "$SCR/sim.err"
		exit 1
	fi
}

# robot_yaml X Y START_DEG: the example robot heading east at (X, Y), its
# steering START_DEG left at power-on, into $SCR/robot.yaml.
robot_yaml() {
	sed -e "s/^start: .*/start: {x: $1, y: $2, heading_deg: 0}/" \
		-e "s/^\( *start_deg:\) 0 /\1 $3 /" "$CONF/robot.yaml" >"$SCR/robot.yaml"
	grep -q "start_deg: $3 " "$SCR/robot.yaml" || { echo "Bail out! robot.yaml has no drives.steering.start_deg"; exit 1; }
}

# start_robot: advee-robot-sim on $SCR/robot.yaml with its drives on $IF, the
# sensors to advee-rs485-sim, the true pose on LCM; $R is its pid.
start_robot() {
	bg "$ROBOT_SIM" -m "$CONF/room.yaml" -r "$SCR/robot.yaml" --can "$IF" --rs485-control "$CTL" --lcm --print \
		>"$SCR/robot.out" 2>"$SCR/robot.err"
	R=$LAST_BG
	wait_line "$SCR/robot.out" "^drives on $IF" 20 || { sed 's/^/# robot.err: /' "$SCR/robot.err"; exit 1; }
}

ctl() { "$CANOPENCTL" -i "$IF" -t 1000 "$@"; }
# pose: one SIM_DATA_POSE line (the latest the robot published).
pose() { "$POSE" -n 1 -t 5; }
# cond 'SHELL CONDITION': for tap_ok with && between checks.
cond() { eval "$1"; }

# wait_status NODE MASK SECONDS: until the statusword has every bit of MASK
# (advee-canopenctl takes a second or so per call under TCG); prints the last one.
status_has() {
	STATUS=$(ctl read "$1" 6041 u16)
	(( (${STATUS%% *} & $2) == $2 ))
}
wait_status() {
	wait_until "$3" status_has "$1" "$2"
	echo "$STATUS"
}
# wait_position NODE UNITS SECONDS: until the drive's position (0x6064) is
# within 4 units of UNITS.
position_at() { close_to "$(ctl read "$1" 6064 i32 | cut -d' ' -f1)" "$2" 4; }
wait_position() { wait_until "$3" position_at "$1" "$2"; }

# at_wall: the latest true pose (in P) has the robot stopped at the east
# wall: 9.0 < x <= 9.1 (front bumper at 10.0), speed 0, PAUSE engaged.
at_wall() {
	P=$(pose)
	awk -v x="$(field "$P" x)" 'BEGIN { exit !(x > 9.0 && x <= 9.1) }' &&
		[ "$(field "$P" speed) $(field "$P" engaged)" = '0.0000 1' ]
}

# epos_velocity RPM: the EPOS (node 1) in profile velocity at RPM, enabled.
epos_velocity() {
	ctl write 1 6060 i8 3
	ctl write 1 60ff i32 "$1"
	ctl enable 1 >/dev/null
}

