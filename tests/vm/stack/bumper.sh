#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Issue 11: driving into a wall. The planner stand-in keeps commanding
# 0.8 m/s east from the start pose (2, 2) towards the east wall (x = 10 m);
# at the front bumper's contact advee-robot-sim raises PAUSE (BR-PSC1 PAUSE event,
# drive motor unpowered), driver_power publishes LL_EVENT_STOP, driver_canbus
# quick-stops the drives (LL_DATA_DRIVES stopped), and the robot stands at
# the wall (within 10 mm of where it touched; ground truth speed 0 at the
# end) although LL_CMD_MOTION still asks for 0.8 m/s; it never passes it.
. "$(dirname "$0")/lib.sh"
stack_require canbus robot-can sim-pose

tap_plan 7
if ! stack_up; then
	tap_diag "the stack did not come up"
	stack_logs 20
	exit 1
fi
OUT=$STACK_RUN/listen.txt
"$STACK_LISTEN" --seconds 60 SIM_DATA_POSE LL_EVENT_STOP LL_DATA_DRIVES LL_DATA_POWER LL_CMD_MOTION >"$OUT" &
LISTEN=$!
wait_lcm_listening "$LISTEN" 20 || tap_diag "advee-stack-listen did not subscribe"
# 8 m at 0.8 m/s would end at x = 11.6: the bumper (0.9 m ahead of the rear
# axle) touches the wall at x = 9.1 after about 9 s.
printf 'path:\n  - {speed_mps: 0.8, steering_deg: 0, duration_s: 13}\n' >"$STACK_RUN/wall.yaml"
stack_drive "$STACK_RUN/wall.yaml" --hold 1
wait "$STACK_DRIVE_PID"
# The robot's state after the last command: one more true pose.
wait_line "$OUT" '^SIM_DATA_POSE ' 10 "$(wc -l <"$OUT")" >/dev/null
kill "$LISTEN"
wait "$LISTEN" 2>/dev/null
tap_diag "messages: $(awk '{ print $1 }' "$OUT" | sort | uniq -c | awk '{ printf "%s %s, ", $2, $1 }')"

contact=$(grep -m1 '^SIM_DATA_POSE .* pause=1' "$OUT")
tap_diag "first pose with PAUSE: $contact"
sources=$(field "$contact" pause_sources)
tap_ok "advee-robot-sim: the front bumper touched the wall and raised PAUSE (source bit 0)" \
	test -n "$contact" -a "$(( ${sources:-0} & 1 ))" = 1
stop=$(grep -m1 '^LL_EVENT_STOP .*stop=1' "$OUT")
tap_diag "$stop"
tap_ok "driver_power published LL_EVENT_STOP (stop=1, source PSC1)" \
	test -n "$stop" -a "$(field "$stop" module) $(field "$stop" source)" = "driver_power 0"
tap_ok "LL_DATA_POWER reports PAUSE engaged" grep -q '^LL_DATA_POWER .* paused=1' "$OUT"
drives=$(grep -m1 '^LL_DATA_DRIVES .*stopped=1' "$OUT")
tap_diag "$drives"
tap_ok "driver_canbus quick-stopped the drives (LL_DATA_DRIVES stopped=1)" test -n "$drives"
xmax=$(grep '^SIM_DATA_POSE ' "$OUT" | tr ' ' '\n' | sed -n 's/^x=//p' | sort -g | tail -1)
tap_ok "the robot never passed the wall: largest true x $xmax m (<= 9.1)" awk -v x="$xmax" 'BEGIN { exit !(x != "" && x <= 9.1) }'
# From 0.5 s after the stop event to the end of the 0.8 m/s commands.
t_stop=$(field "$stop" t)
t_cmd_end=$(grep '^LL_CMD_MOTION .*speed=0.8000' "$OUT" | tail -1)
t_cmd_end=$(field "$t_cmd_end" t)
# Each released PAUSE lets driver_canbus follow the planner again, so the
# robot may creep a step into contact and PAUSE again (LL_EVENT_STOP
# repeats): it must stay where it touched, not drive on. The contact is
# found up to one simulation step (0.8 m/s x 10 ms = 8 mm) before the wall,
# hence 10 mm.
read -r moving total xspread < <(grep '^SIM_DATA_POSE ' "$OUT" | awk -v a="$t_stop" -v b="$t_cmd_end" -v xc="$(field "$contact" x)" '
	{ for (i = 1; i <= NF; i++) { split($i, kv, "="); f[kv[1]] = kv[2] } }
	f["t"] > a + 0.5 && f["t"] <= b { n++; if (f["speed"] > 0.001 || f["speed"] < -0.001) m++; d = f["x"] - xc; if (d < 0) d = -d; if (d > s) s = d }
	END { printf "%d %d %.4f\n", m, n, s }')
tap_diag "poses after the stop while 0.8 m/s was still commanded: $total, moving in $moving, farthest $xspread m from the contact point"
tap_ok "the robot stays at the wall (within 10 mm of the contact point) while LL_CMD_MOTION still asks for 0.8 m/s" \
	awk -v n="$total" -v s="$xspread" 'BEGIN { exit !(n >= 5 && s <= 0.010) }'
last=$(grep '^SIM_DATA_POSE ' "$OUT" | tail -1)
tap_ok "at the end the ground truth speed is 0 ($(field "$last" speed))" close_to "$(field "$last" speed)" 0 0.001
tap_finish
