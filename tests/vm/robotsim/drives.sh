#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# advee-robot-sim --can vcan0: the robot's simulated EPOS and IclA commanded by
# advee-canopenctl as driver_canbus would. The IclA homes (0 = straight ahead) and
# turns the steering; the EPOS in profile velocity moves the robot at the
# commanded speed; driving into the east wall stops the robot at the wall
# and engages the PSC1's PAUSE, seen by advee-rs485ctl watch on the power link; a
# quick stop releases it. The true pose comes from SIM_DATA_POSE.
. "$(dirname "$0")/lib.sh"

robotsim_up "$RS485CTL"
tap_plan 12

# The example robot, 4 degrees left at power-on, 6.1 m from the east wall
# (front bumper at x = 3.9, wall at x = 10), heading east; nothing between.
robot_yaml 3.0 2.0 4
start_robot

p=$(pose)
tap_diag "at start: $p"
tap_ok "SIM_DATA_POSE: at (3, 2), steering 4 degrees before homing" \
	cond "close_to '$(field "$p" x)' 3 0.001 && close_to '$(field "$p" steering_deg)' 4 0.01"

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
	cond "close_to '$(field "$p" steering_deg)' 0 0.02 && close_to '$pos' 0 4"

# Profile position to 10 degrees left: 1745 units of 1/10000 rad.
ctl write 2 6060 i8 1
ctl write 2 6081 u32 3000
ctl write 2 6040 u16 0x0f
ctl write 2 607a i32 1745
ctl write 2 6040 u16 0x1f
wait_position 2 1745 15  # 1745 units at 3000 units/s
wait_status 2 0x0400 15 >/dev/null  # target reached
p=$(pose)
tap_diag "turned: $p"
tap_ok "steering follows the IclA: 10.0 degrees" close_to "$(field "$p" steering_deg)" 10 0.02
ctl write 2 6040 u16 0x0f
ctl write 2 607a i32 0
ctl write 2 6040 u16 0x1f
wait_position 2 0 15
wait_status 2 0x0400 15 >/dev/null
p=$(pose)
tap_ok "and back to straight ahead" close_to "$(field "$p" steering_deg)" 0 0.02
h0=$(field "$p" heading_deg)

# The PSC1's events on the power link, from before the robot moves.
bg "$RS485CTL" -b /dev/ttyTSU2 watch -a 0x01 -t 60s >"$SCR/watch.out" 2>"$SCR/watch.err"

# EPOS (node 1): profile velocity, 993 rpm = 0.5 m/s.
epos_velocity 993
p1=$(pose)
sleep 2	# the interval the speed is measured over (pose time stamps), not a synchronisation
p2=$(pose)
tap_diag "moving: $p1"
tap_diag "moving: $p2"
v=$(awk -v x1="$(field "$p1" x)" -v x2="$(field "$p2" x)" -v t1="$(field "$p1" t)" -v t2="$(field "$p2" t)" \
	'BEGIN { if (t2 > t1) printf "%.4f", (x2 - x1) / (t2 - t1) }')
tap_diag "speed from the true pose: $v m/s over $(awk -v a="$(field "$p1" t)" -v b="$(field "$p2" t)" 'BEGIN { print b - a }') s"
tap_ok "the robot moves east at the commanded 0.5 m/s (true pose, 1%; speed field 0.500; no contact yet)" \
	cond "close_to '$v' 0.5 0.005 && close_to '$(field "$p2" speed)' 0.5 0.001 && test '$(field "$p2" pause)' = 0"
tap_ok "straight: heading and y unchanged" \
	cond "close_to '$(field "$p2" heading_deg)' '$h0' 0.01 && close_to '$(field "$p2" y)' 2 0.001"

# Into the wall: 6.1 m in ~12 s; PAUSE engaged by the front bumper.
wait_line "$SCR/watch.out" "instr 0x40 .* 01 01" 40
tap_ok "PSC1 PAUSE event (engaged, front bumper) on the power link" grep -qE "instr 0x40 .* 01 01" "$SCR/watch.out"
wait_until 10 at_wall
r=$?
p=$P
tap_diag "at the wall: $p"
tap_result $r "stopped at the wall: 9.0 < x <= 9.1 (front bumper at 10.0), speed 0, PAUSE engaged"
sleep 1	# an observation window (10 poses), not a synchronisation
p3=$(pose)
tap_is "still at the wall a second later (the drive still pushes)" "$(field "$p3" x) $(field "$p3" pause)" "$(field "$p" x) 1"

# driver_canbus answers LL_EVENT_STOP with a quick stop: the bumper frees, PAUSE releases.
ctl quick-stop 1 >/dev/null
wait_line "$SCR/watch.out" "instr 0x40 .* 00 00" 10
tap_ok "quick stop: PSC1 PAUSE released (event 00 00)" grep -qE "instr 0x40 .* 00 00" "$SCR/watch.out"
sed 's/^/# watch: /' "$SCR/watch.out"
kill "$R"
wait_exit "$R" 10
rc=$?
tap_is "advee-robot-sim exits 0 on SIGTERM" "$rc" 0
[ "$rc" = 0 ] || sed 's/^/# robot.err: /' "$SCR/robot.err"
tap_finish
