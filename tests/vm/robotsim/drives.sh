#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# robot-sim --can vcan0: the robot's simulated EPOS and IclA commanded by
# canopenctl as driver_canbus would. The IclA homes (0 = straight ahead) and
# turns the steering; the EPOS in profile velocity moves the robot at the
# commanded speed; driving into the east wall stops the robot at the wall
# and engages the PSC1's PAUSE, seen by rs485ctl watch on the power link; a
# quick stop releases it. The true pose comes from SIM_DATA_POSE.
. "$VMTEST_REPO/tests/vm/modules/lib.sh"
. "$VMTEST_REPO/tests/vm/rs485/common.inc"

RS=$VMTEST_BUILD/userland/robotsim
ROBOT_SIM=$RS/robot-sim
POSE=$RS/robot-sim-pose
CANOPENCTL=$VMTEST_BUILD/userland/canopen/canopenctl
RS485CTL=$VMTEST_BUILD/userland/rs485/rs485ctl
CONF=$VMTEST_REPO/userland/robotsim/conf
IF=vcan0

cleanup() {
	bg_kill_all
	ip link del "$IF" 2>/dev/null
	modprobe -r vcan can_raw can 2>/dev/null
	rs485_cleanup
	net_teardown
}
rs485_setup "$SIMBIN/rs485-sim" "$ROBOT_SIM" "$POSE" "$CANOPENCTL" "$RS485CTL"
trap cleanup EXIT
net_setup || { echo "Bail out! cannot set up loopback multicast"; exit 1; }
modprobe n_rs485 || { echo "Bail out! modprobe n_rs485"; exit 1; }
if ! modprobe vcan || ! ip link add dev "$IF" type vcan || ! ip link set up "$IF"; then
	echo "Bail out! cannot set up $IF"
	exit 1
fi
if ! start_sim "$VMTEST_REPO/tests/vm/daemons/boards.yaml"; then
	echo "Bail out! rs485-sim did not start"
	sed 's/^/# /' "$SCR/sim.err"
	exit 1
fi
tap_plan 12

ctl() { "$CANOPENCTL" -i "$IF" -t 1000 "$@"; }
# pose: one SIM_DATA_POSE line (the latest the robot published).
pose() { "$POSE" -n 1 -t 5; }
val() { printf '%s\n' "$1" | tr ' ' '\n' | sed -n "s/^$2=//p" | head -1; }
close_to() { awk -v v="$1" -v w="$2" -v t="$3" 'BEGIN { d = v - w; if (d < 0) d = -d; exit !(v != "" && d <= t) }'; }
# cond 'SHELL CONDITION': for tap_ok with && between checks.
cond() { eval "$1"; }
# wait_status NODE MASK SECONDS: until the statusword has every bit of MASK
# (canopenctl takes a second or so per call under TCG); prints the last one.
wait_status() {
	local i st
	for ((i = 0; i < $3; i++)); do
		st=$(ctl read "$1" 6041 u16)
		(( (${st%% *} & $2) == $2 )) && break
		sleep 1
	done
	echo "$st"
}
# wait_exit PID SECONDS: the exit status of a background process, 255 if it did not end in time.
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

# The example robot, 4 degrees left at power-on, 6.1 m from the east wall
# (front bumper at x = 3.9, wall at x = 10), heading east; nothing between.
sed -e 's/^start: .*/start: {x: 3.0, y: 2.0, heading_deg: 0}/' \
	-e 's/^\( *start_deg:\) 0 /\1 4 /' "$CONF/robot.yaml" >"$SCR/robot.yaml"
grep -q 'start_deg: 4 ' "$SCR/robot.yaml" || { echo "Bail out! robot.yaml has no drives.steering.start_deg"; exit 1; }

bg "$ROBOT_SIM" -m "$CONF/room.yaml" -r "$SCR/robot.yaml" --can "$IF" --rs485-control "$CTL" --lcm --print \
	>"$SCR/robot.out" 2>"$SCR/robot.err"
R=$LAST_BG
wait_for "$SCR/robot.out" "^drives on $IF" 20 || { sed 's/^/# robot.err: /' "$SCR/robot.err"; exit 1; }

p=$(pose)
tap_diag "at start: $p"
tap_ok "SIM_DATA_POSE: at (3, 2), steering 4 degrees before homing" \
	cond "close_to '$(val "$p" x)' 3 0.001 && close_to '$(val "$p" steering_deg)' 4 0.01"

# IclA (node 2): homing onto the switch at straight ahead (method 17, 2000 units/s).
ctl write 2 6060 i8 6
ctl write 2 6098 i8 17
ctl write 2 6099:1 u32 2000
ctl enable 2 >/dev/null
ctl write 2 6040 u16 0x1f
st=$(wait_status 2 0x1000 15)
p=$(pose)
tap_diag "homed: statusword $st; $p"
tap_ok "IclA homing attained (statusword bit 12)" test $((${st%% *} & 0x1000)) -ne 0
pos=$(ctl read 2 6064 i32 | cut -d' ' -f1)
tap_diag "0x6064 after homing: $pos"
tap_ok "steering 0 (straight ahead) after homing, 0x6064 near 0" \
	cond "close_to '$(val "$p" steering_deg)' 0 0.02 && close_to '$pos' 0 4"

# Profile position to 10 degrees left: 1745 units of 1/10000 rad.
ctl write 2 6060 i8 1
ctl write 2 6081 u32 3000
ctl write 2 6040 u16 0x0f
ctl write 2 607a i32 1745
ctl write 2 6040 u16 0x1f
sleep 1  # 1745 units at 3000 units/s
wait_status 2 0x0400 15 >/dev/null  # target reached
p=$(pose)
tap_diag "turned: $p"
tap_ok "steering follows the IclA: 10.0 degrees" close_to "$(val "$p" steering_deg)" 10 0.02
ctl write 2 6040 u16 0x0f
ctl write 2 607a i32 0
ctl write 2 6040 u16 0x1f
sleep 1
wait_status 2 0x0400 15 >/dev/null
p=$(pose)
tap_ok "and back to straight ahead" close_to "$(val "$p" steering_deg)" 0 0.02
h0=$(val "$p" heading_deg)

# The PSC1's events on the power link, from before the robot moves.
bg "$RS485CTL" -b /dev/ttyTSU2 watch -a 0x01 -t 60s >"$SCR/watch.out" 2>"$SCR/watch.err"

# EPOS (node 1): profile velocity, 993 rpm = 0.5 m/s.
ctl write 1 6060 i8 3
ctl write 1 60ff i32 993
ctl enable 1 >/dev/null
p1=$(pose)
sleep 2
p2=$(pose)
tap_diag "moving: $p1"
tap_diag "moving: $p2"
v=$(awk -v x1="$(val "$p1" x)" -v x2="$(val "$p2" x)" -v t1="$(val "$p1" t)" -v t2="$(val "$p2" t)" \
	'BEGIN { if (t2 > t1) printf "%.4f", (x2 - x1) / (t2 - t1) }')
tap_diag "speed from the true pose: $v m/s over $(awk -v a="$(val "$p1" t)" -v b="$(val "$p2" t)" 'BEGIN { print b - a }') s"
tap_ok "the robot moves east at the commanded 0.5 m/s (true pose, 1%; speed field 0.500; no contact yet)" \
	cond "close_to '$v' 0.5 0.005 && close_to '$(val "$p2" speed)' 0.5 0.001 && test '$(val "$p2" pause)' = 0"
tap_ok "straight: heading and y unchanged" \
	cond "close_to '$(val "$p2" heading_deg)' '$h0' 0.01 && close_to '$(val "$p2" y)' 2 0.001"

# Into the wall: 6.1 m in ~12 s; PAUSE engaged by the front bumper.
wait_for "$SCR/watch.out" "instr 0x40 .* 01 01" 40
tap_ok "PSC1 PAUSE event (engaged, front bumper) on the power link" grep -qE "instr 0x40 .* 01 01" "$SCR/watch.out"
sleep 1
p=$(pose)
tap_diag "at the wall: $p"
tap_ok "stopped at the wall: 9.0 < x <= 9.1 (front bumper at 10.0), speed 0, PAUSE engaged" \
	cond "awk -v x='$(val "$p" x)' 'BEGIN { exit !(x > 9.0 && x <= 9.1) }' && test '$(val "$p" speed) $(val "$p" engaged)' = '0.0000 1'"
sleep 1
p3=$(pose)
tap_is "still at the wall a second later (the drive still pushes)" "$(val "$p3" x) $(val "$p3" pause)" "$(val "$p" x) 1"

# driver_canbus answers LL_EVENT_STOP with a quick stop: the bumper frees, PAUSE releases.
ctl quick-stop 1 >/dev/null
wait_for "$SCR/watch.out" "instr 0x40 .* 00 00" 10
tap_ok "quick stop: PSC1 PAUSE released (event 00 00)" grep -qE "instr 0x40 .* 00 00" "$SCR/watch.out"
sed 's/^/# watch: /' "$SCR/watch.out"
kill "$R"
wait_exit "$R" 10
rc=$?
tap_is "robot-sim exits 0 on SIGTERM" "$rc" 0
[ "$rc" = 0 ] || sed 's/^/# robot.err: /' "$SCR/robot.err"
tap_finish
