#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Issue 9: with the whole stack up (tests/vm/stack/lib.sh), one LCM
# subscriber sees every channel of advee/msgs/channels.hpp (kAllChannels):
# the periodic ones at their nominal rate (5 or more messages each, counted
# over the interval they span, +-50 %: tests/lib/lcm.sh rate_check), the
# aperiodic ones when something triggers them; and the values are
# those the simulators were set to: ranges and beacon bearings as advee-robot-sim's
# world gives them at the true pose, odometry speed 0 standing and 0.5 m/s
# driving (its distance against the truth), temperatures and fan speeds of the simulated MAX6615, the PSC1's
# outputs and currents (conf/boards.yaml), the drives enabled and following.
. "$(dirname "$0")/lib.sh"
stack_require canbus robot-can sim-pose

tap_plan 27
if ! stack_up; then
	tap_diag "the stack did not come up"
	stack_logs 20
	exit 1
fi
tap_diag "modules: $STACK_MODULES; robot drives: $STACK_ROBOT_DRIVES"
echo 1500 >"$SIMFS/max6615/fan1_rpm"
echo 900 >"$SIMFS/max6615/fan2_rpm"
ALL=$STACK_RUN/all.txt
"$STACK_LISTEN" --seconds 600 >"$ALL" &
LISTEN=$!
STACK_PIDS="$LISTEN $STACK_PIDS"
wait_lcm_listening "$LISTEN" 20 || tap_diag "advee-stack-listen did not subscribe"
# The planner stand-in, standing: homes the steering, names the beacons and
# sends standstill commands until stopped (without any, driver_canbus
# quick-stops the EPOS after 1 s, as it should).
printf 'path:\n  - {speed_mps: 0, steering_deg: 0, duration_s: 1}\n' >"$STACK_RUN/stand.yaml"
stack_drive "$STACK_RUN/stand.yaml" --home --home-wait 3 --stay --beacons 1,2,3,4,5,6,7,8
# The window starts once the steering is homed, the scanner has the ids
# and the fans have been read since they were set.
wait_line "$ALL" '^LL_DATA_DRIVES .* homed2=1' 30 >/dev/null
wait_line "$ALL" '^LL_DATA_BEACONS .* count=[1-9]' 20 >/dev/null
wait_line "$ALL" '^LL_DATA_FANS ' 20 >/dev/null
start=$(wc -l <"$ALL")

# --- periodic channels, the robot standing still -------------------------------
# Each rate is a count over the interval its messages span (rate_check in
# tests/lib/lcm.sh): the window lasts until every 1 Hz channel has 5.
OUT=$STACK_RUN/periodic.txt
PERIODIC="LL_DATA_SRFS LL_DATA_ODO LL_DATA_DRIVES LL_DATA_BEACONS LL_DATA_POWER LL_DATA_TEMPERATURE LL_DATA_FANS"
# window_full: 5 of each periodic channel and of each module's CM_DATA_STATE
# (one awk pass: under TCG every process started costs).
window_full() {
	awk -v from="$((start + 1))" -v want="$PERIODIC" -v mods="watchdog $STACK_MODULES" -v out="$OUT" '
		NR >= from { print >out; if ($1 == "CM_DATA_STATE") { for (i = 2; i <= NF; i++) if ($i ~ /^module=/) n[$i]++ } else n[$1]++ }
		END { k = split(want, c, " "); for (i = 1; i <= k; i++) if (n[c[i]] < 5) exit 1
			k = split(mods, m, " "); for (i = 1; i <= k; i++) if (n["module=" m[i]] < 5) exit 1 }' "$ALL"
}
wait_until 30 window_full || tap_diag "the window did not fill in 30 s"
kill "$STACK_DRIVE_PID"
wait "$STACK_DRIVE_PID"
temp_model="$(cat "$SIMFS/max6615/temp1") $(cat "$SIMFS/max6615/temp2")"
# The nominal rates are those of channels.hpp; the daemons' configurations
# (userland/*/conf) use them.
tap_rate "LL_DATA_SRFS at 4 Hz" "$OUT" LL_DATA_SRFS 4
tap_rate "LL_DATA_ODO at 4 Hz" "$OUT" LL_DATA_ODO 4
tap_rate "LL_DATA_DRIVES at 4 Hz" "$OUT" LL_DATA_DRIVES 4
tap_rate "LL_DATA_BEACONS at 1 Hz" "$OUT" LL_DATA_BEACONS 1
tap_rate "LL_DATA_POWER at 1 Hz" "$OUT" LL_DATA_POWER 1
tap_rate "LL_DATA_TEMPERATURE at 1 Hz" "$OUT" LL_DATA_TEMPERATURE 1
tap_rate "LL_DATA_FANS at 1 Hz" "$OUT" LL_DATA_FANS 1
off=
for m in watchdog $STACK_MODULES; do
	grep "^CM_DATA_STATE .* module=$m " "$OUT" >"$STACK_RUN/state.$m"
	r=$(rate_check "$STACK_RUN/state.$m" CM_DATA_STATE 1) || off="$off $m: $r;"
done
tap_ok "CM_DATA_STATE at 1 Hz from the supervisor and each of its modules${off:+ (off:$off)}" test -z "$off"

pose=$(grep '^SIM_DATA_POSE ' "$OUT" | tail -1)
x=$(field "$pose" x) y=$(field "$pose" y) h=$(field "$pose" heading)
world=$(stack_world_at "$x" "$y" "$h")
tap_diag "true pose: $pose"
printf '%s\n' "$world" | sed 's/^/# model: /'
srfs=$(grep '^LL_DATA_SRFS ' "$OUT" | tail -1)
tap_diag "$srfs"
bad=$(printf '%s\n' "$world" | awk -v msg="$srfs" '
	BEGIN { n = split(msg, w, " "); for (i = 1; i <= n; i++) { split(w[i], kv, "="); got[kv[1]] = kv[2] } }
	$1 == "srf_m" { for (i = 2; i <= NF; i++) { id = "srf" (i - 2); g = got[id]; want = ($i == "-") ? -1 : $i
		d = g - want; if (d < 0) d = -d; if (g == "" || (want < 0) != (g < 0) || d > 0.06) printf "%s=%s(model %s) ", id, g, $i } }
	$1 == "ir_m" { for (i = 2; i <= NF; i++) { id = "ir" (i - 2); g = got[id]; d = g - $i; if (d < 0) d = -d
		if (g == "" || d > 0.02) printf "%s=%s(model %s) ", id, g, $i } }')
tap_ok "LL_DATA_SRFS: 16 ultrasonic ranges (+-0.06 m) and 4 IR (+-0.02 m) as the world gives them${bad:+: $bad}" test -z "$bad" -a -n "$srfs"
beacons=$(grep '^LL_DATA_BEACONS ' "$OUT" | tail -1)
tap_diag "$beacons"
bad=$(printf '%s\n' "$world" | awk -v msg="$beacons" '
	BEGIN { n = split(msg, w, " "); for (i = 1; i <= n; i++) { split(w[i], kv, "="); if (kv[1] ~ /^b[0-9]+$/) got[substr(kv[1], 2)] = kv[2] } }
	$1 == "beacons" { for (i = 2; i <= NF; i++) { split($i, p, /@|deg/); seen[p[1]] = 1; models++
		if (!(p[1] in got)) { printf "beacon %s missing ", p[1]; continue }
		d = got[p[1]] * 180 / 3.14159265358979 - p[2]; while (d > 180) d -= 360; while (d < -180) d += 360
		if (d < 0) d = -d; if (d > 1.5) printf "b%s off by %.2f deg ", p[1], d } }
	END { for (id in got) if (!(id in seen)) printf "beacon %s not visible in the model ", id; if (!models) printf "no beacon in the model" }')
tap_ok "LL_DATA_BEACONS: the visible beacons at their true bearings (+-1.5 degrees)${bad:+: $bad}" test -z "$bad" -a -n "$beacons"
odo=$(grep '^LL_DATA_ODO ' "$OUT" | tail -1)
tap_diag "$odo"
tap_ok "LL_DATA_ODO standing: speed 0, yaw rate 0" test "$(field "$odo" speed) $(field "$odo" yaw)" = "0.0000 0.0000"
temps=$(grep '^LL_DATA_TEMPERATURE ' "$OUT" | tail -1)
tap_diag "$temps; MAX6615 model (millidegrees): $temp_model"
tap_ok "LL_DATA_TEMPERATURE: the MAX6615's temperatures as advee-robot-sim set them (+-0.25 C)" \
	awk -v a="$(field "$temps" temp1)" -v b="$(field "$temps" temp2)" -v m="$temp_model" 'BEGIN {
		split(m, t, " "); d1 = a - t[1] / 1000; d2 = b - t[2] / 1000
		exit !(a != "" && b != "" && d1 * d1 <= 0.0625 && d2 * d2 <= 0.0625) }'
fans=$(grep '^LL_DATA_FANS ' "$OUT" | tail -1)
tap_diag "$fans"
tap_ok "LL_DATA_FANS: fan1 1500 rpm, fan2 900 rpm as set (+-5 %)" \
	awk -v a="$(field "$fans" fan1)" -v b="$(field "$fans" fan2)" 'BEGIN { exit !(a >= 1425 && a <= 1575 && b >= 855 && b <= 945) }'
power=$(grep '^LL_DATA_POWER ' "$OUT" | tail -1)
tap_diag "$power"
tap_is "LL_DATA_POWER: outputs 0-3 on (0x0f), currents 1.5/0.8/0.4/0.2 A, no PAUSE (conf/boards.yaml)" \
	"$(field "$power" mask) $(field "$power" i0) $(field "$power" i1) $(field "$power" i2) $(field "$power" i3) $(field "$power" paused)" \
	"15 1.500 0.800 0.400 0.200 0"
drives=$(grep '^LL_DATA_DRIVES ' "$OUT" | tail -1)
tap_diag "$drives"
tap_is "LL_DATA_DRIVES: EPOS (node 1) and IclA (node 2) enabled, standing as commanded" \
	"$(field "$drives" node1) $(field "$drives" node2) $(field "$drives" speed)" \
	"operation_enabled operation_enabled 0.0000"

# --- aperiodic channels, triggered --------------------------------------------------
# Each trigger waits for what it causes (a message seen), not for a time.
OUT=$STACK_RUN/events.txt
start=$(wc -l <"$ALL")
# seen ERE [AFTER]: wait for a line after line AFTER (default: start) of the listener's output.
seen() { wait_line "$ALL" "$1" 15 "${2:-$start}" >/dev/null || tap_diag "not seen in 15 s: /$1/"; }
"$PROBE" active-beacons 1 2 3 >/dev/null
"$LCMCTL" state driver_rs485b PAUSE >/dev/null
seen '^CM_DATA_STATE .* module=driver_rs485b state=6 '
"$LCMCTL" state driver_rs485b RUN >/dev/null
"$PROBE" power output 5 on >/dev/null
"$PROBE" power output 9 on >/dev/null	# no such output: driver_power reports an error
stack_sim event psc1@0x01 pause 1 1 >/dev/null
seen '^LL_EVENT_STOP .* stop=1 '
stack_sim event psc1@0x01 pause 0 0 >/dev/null
aux_pid=$(grep '^CM_DATA_STATE .* module=driver_aux ' "$STACK_RUN/periodic.txt" | tail -1)
aux_pid=$(field "$aux_pid" pid)
kill -9 "$aux_pid"
printf 'path:\n  - {speed_mps: 0.5, steering_deg: 0, duration_s: 5}\n' >"$STACK_RUN/straight.yaml"
stack_drive "$STACK_RUN/straight.yaml" --home --home-wait 3 --hold 1
wait "$STACK_DRIVE_PID"
# Until the last effects are in: the supervisor's restart report, RUN again
# after the PAUSE, the output switched on, the robot standing after the path
# with its odometry published.
seen '^CM_DATA_MODULES .* target=driver_aux .* restarts=[1-9]'
seen "^CM_DATA_STATE .* module=driver_rs485b state=3 "
seen '^LL_DATA_POWER .* mask=47 '
seen '^LL_EVENT_STOP .* stop=0 '
seen '^CM_DATA_ERROR .* module=driver_power '
end=$(wc -l <"$ALL")
seen '^SIM_DATA_POSE .* speed=0\.0000 ' "$end"
seen '^LL_DATA_ODO .* speed=0\.0000 ' "$end"
kill "$LISTEN"
wait "$LISTEN" 2>/dev/null
tail -n +"$((start + 1))" "$ALL" >"$OUT"
tap_diag "messages: $(awk '{ print $1 }' "$OUT" | sort | uniq -c | awk '{ printf "%s %s, ", $2, $1 }')"
grep -m2 '^CM_DATA_ERROR ' "$OUT" | sed 's/^/# /'

line() { grep -m1 "^$1 .*$2" "$OUT"; }
tap_ok "LL_DATA_ACTIVE_BEACONS: ids 1,2,3" test -n "$(line LL_DATA_ACTIVE_BEACONS 'ids=1,2,3$')"
tap_ok "CM_CMD_STATE: driver_rs485b PAUSE (6) and RUN (3)" \
	test -n "$(line CM_CMD_STATE 'target=driver_rs485b state=6')" -a -n "$(line CM_CMD_STATE 'target=driver_rs485b state=3')"
tap_ok "driver_rs485b obeyed: announced PAUSE, then RUN again" \
	sh -c "grep '^CM_DATA_STATE .* module=driver_rs485b ' '$OUT' | awk '{ print \$4 }' | uniq | tr '\n' ' ' | grep -q 'state=6 state=3'"
tap_ok "LL_CMD_POWER: output 5 on" test -n "$(line LL_CMD_POWER 'action=0 output=5 on=1')"
tap_ok "LL_DATA_POWER shows output 5 switched on (0x2f)" test -n "$(line LL_DATA_POWER 'mask=47 ')"
tap_ok "CM_DATA_ERROR: driver_power reports the command for output 9" test -n "$(line CM_DATA_ERROR 'module=driver_power ')"
tap_ok "LL_EVENT_STOP: the PSC1's PAUSE pressed and released (stop=1, stop=0)" \
	test -n "$(line LL_EVENT_STOP 'stop=1')" -a -n "$(line LL_EVENT_STOP 'stop=0')"
tap_ok "CM_DATA_MODULES: the supervisor reports driver_aux's restart after kill -9" \
	test -n "$(grep '^CM_DATA_MODULES .* target=driver_aux ' "$OUT" | awk '$0 !~ / restarts=0$/' | head -1)"
tap_ok "LL_CMD_HOMING: steering (axis 0)" test -n "$(line LL_CMD_HOMING 'axis=0')"
tap_ok "LL_CMD_MOTION: 0.5 m/s from the drive script" test -n "$(line LL_CMD_MOTION 'speed=0.5000 ')"
# Driving straight at 0.5 m/s. Under TCG a reading's timestamp can lag its
# tick count (single samples of 0.28 and 1.6 m/s were seen at a constant
# 0.5 m/s) and the drives do not always reach the commanded speed at once,
# so the odometry is checked by the distance: the sum of speed x interval
# against the true distance (the ticks are exact), and shown per sample.
v=$(grep '^LL_DATA_ODO ' "$OUT" | tr ' ' '\n' | sed -n 's/^speed=//p' | awk '$1 > 0.1' | sort -g |
	awk '{ a[NR] = $1 } END { if (NR) printf "%.4f %d", (NR % 2 ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2), NR }')
tap_diag "odometry while moving: median speed, samples: $v"
d_odo=$(grep '^LL_DATA_ODO ' "$OUT" | tr ' ' '\n' | awk -F= '$1 == "interval" { i = $2 } $1 == "speed" { s = $2 } $1 == "yaw" { d += s * i } END { printf "%.3f", d }')
p0=$(grep -m1 '^SIM_DATA_POSE ' "$OUT") p1=$(grep '^SIM_DATA_POSE ' "$OUT" | tail -1)
d_true=$(awk -v a="$(field "$p0" x)" -v b="$(field "$p0" y)" -v c="$(field "$p1" x)" -v d="$(field "$p1" y)" 'BEGIN { printf "%.3f", sqrt((c-a)^2 + (d-b)^2) }')
tap_ok "LL_DATA_ODO distance $d_odo m = true distance $d_true m (+-2 %)" \
	awk -v a="$d_odo" -v b="$d_true" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(b > 1 && d <= 0.02 * b) }'
dv=$(grep '^LL_DATA_DRIVES ' "$OUT" | tr ' ' '\n' | sed -n 's/^speed=//p' | sort -g | tail -1)
tap_ok "LL_DATA_DRIVES: the EPOS turned at 0.5 m/s ($dv)" close_to "$dv" 0.5 0.01
tap_finish
