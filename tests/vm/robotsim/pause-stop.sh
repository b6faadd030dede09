#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# The bumper's way into the stack: advee-robot-sim drives into the east wall (its
# EPOS on vcan0 in profile velocity), the bumper engages the PAUSE line,
# the simulated BR-PSC1 sends its PAUSE event on the power link and
# driver_power publishes LL_EVENT_STOP; the quick stop driver_canbus would
# answer with (advee-canopenctl here) releases PAUSE and LL_EVENT_STOP stop=0
# follows. The robot never gets past the wall (advee-robot-sim's printed poses).
. "$(dirname "$0")/lib.sh"

DRIVER_POWER=$VMTEST_BUILD/userland/daemons/driver_power/driver_power
robotsim_up "$PROBE" "$DRIVER_POWER"
tap_plan 6

cat >"$SCR/power.yaml" <<EOC
module: {name: driver_power, print_severity: notice, send_severity: notice}
driver_power:
  bus: {device: /dev/ttyTSU2, timeout_ms: $TIMEOUT_MS, retries: 1}
  address: 0x01
  rate_hz: 1
  poweroff_command: ["false"]
  reboot_command: ["false"]
EOC
bg "$DRIVER_POWER" --config "$SCR/power.yaml" 2>"$SCR/power.err"
DP=$LAST_BG

# Front bumper 1.1 m from the east wall (x = 8.9 of 10), heading east.
robot_yaml 8.0 2.0 0
start_robot
wait_state driver_power 3 30 "$DP" >/dev/null || sed 's/^/# power.err: /' "$SCR/power.err"
listen_bg "$SCR/stop.out" LL_EVENT_STOP
epos_velocity 993  # 0.5 m/s: at the wall in 2.2 s
wait_line "$SCR/stop.out" '^LL_EVENT_STOP .* stop=1 ' 30
s1=$(grep '^LL_EVENT_STOP ' "$SCR/stop.out" | head -1)
tap_diag "$s1"
tap_is "bumper: LL_EVENT_STOP stop=1 from the PSC1 (source 0)" "$(field "$s1" stop) $(field "$s1" source)" "1 0"
wait_until 10 at_wall
r=$?
tap_diag "at the wall: $P"
tap_result $r "robot at the wall with PAUSE engaged, speed 0"
tap_is "EPOS still turning (nobody stopped it yet): 993 rpm" "$(ctl read 1 606c i32 | cut -d' ' -f1)" 993

ctl quick-stop 1 >/dev/null
wait_line "$SCR/stop.out" '^LL_EVENT_STOP .* stop=0 ' 15
s2=$(grep '^LL_EVENT_STOP ' "$SCR/stop.out" | sed -n 2p)
tap_diag "$s2"
tap_is "quick stop: PAUSE released, LL_EVENT_STOP stop=0" "$(field "$s2" stop)" 0
p=$(pose)
tap_is "released: PAUSE line off, robot still at the wall" "$(field "$p" engaged) $(field "$p" speed)" "0 0.0000"
maxx=$(awk '/^t=/ { for (i = 1; i <= NF; i++) if ($i ~ /^x=/ && !seen[NR]++) { sub(/x=/, "", $i); if ($i > m) m = $i } } END { print m }' "$SCR/robot.out")
tap_diag "largest x advee-robot-sim printed: $maxx"
tap_ok "never past the contact pose (x <= 9.1)" awk -v m="$maxx" 'BEGIN { exit !(m > 9.0 && m <= 9.1) }'
tap_finish
