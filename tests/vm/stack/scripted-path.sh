#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Issue 11: the robot drives the demo's scripted path through the whole
# stack - advee-drive-script publishes LL_CMD_MOTION at 10 Hz, driver_canbus
# commands the simulated EPOS and IclA on vcan0, advee-robot-sim moves as they turn
# and feeds the simulated boards, driver_rs485 reads them through n_rs485 on
# the simulated TS-UARTs. After the path (14 m around the box of room.yaml):
# the odometry position estimate (LL_DATA_ODO integrated from the start pose)
# stays within 0.1 m and 1 degree of advee-robot-sim's ground truth
# (SIM_DATA_POSE); the ranges and beacon bearings the daemons publish match
# what advee-robot-sim's world model gives for the true end pose.
. "$(dirname "$0")/lib.sh"
stack_require canbus robot-can sim-pose

# Ranges: noise 0.01 m on each side, the pose printed to 0.1 mm.
RANGE_TOL=0.06
# Bearings: noise 0.3 degree on each side.
BEARING_TOL_DEG=1.5

tap_plan 9
if ! stack_up; then
	tap_diag "the stack did not come up"
	stack_logs 20
	exit 1
fi
tap_diag "modules: $STACK_MODULES; robot drives: $STACK_ROBOT_DRIVES"
OUT=$STACK_RUN/listen.txt
PATH_FILE=$ROBOTSIM_CONF/square-path.yaml
"$STACK_LISTEN" --seconds 120 LL_DATA_ODO LL_DATA_SRFS LL_DATA_BEACONS LL_DATA_DRIVES SIM_DATA_POSE LL_CMD_MOTION CM_DATA_ERROR >"$OUT" &
LISTEN=$!
wait_lcm_listening "$LISTEN" 20 || tap_diag "advee-stack-listen did not subscribe"
t_start=$(awk '{ print $1 }' /proc/uptime)
stack_drive "$PATH_FILE" --home --home-wait 3 --hold 3 --beacons 1,2,3,4,5,6,7,8
wait "$STACK_DRIVE_PID"
rc=$?
STACK_PIDS=${STACK_PIDS/$STACK_DRIVE_PID/}
tap_is "advee-drive-script played the path (exit 0)" "$rc" 0
sed 's/^/# /' "$STACK_RUN/drive-script.log"
# One more beacon scan, range poll and true pose at the end pose.
end=$(wc -l <"$OUT")
for ch in LL_DATA_BEACONS LL_DATA_SRFS SIM_DATA_POSE; do wait_line "$OUT" "^$ch " 10 "$end" >/dev/null; done
kill "$LISTEN"
wait "$LISTEN" 2>/dev/null
tap_diag "messages: $(awk '{ print $1 }' "$OUT" | sort | uniq -c | awk '{ printf "%s %s, ", $2, $1 }')"

# What went wrong on the way, if anything: the modules' errors, quick stops.
grep '^CM_DATA_ERROR ' "$OUT" | head -20 | sed 's/^/# /'
grep '^LL_DATA_DRIVES .*stopped=1' "$OUT" | head -3 | sed 's/^/# /'

stack_path_points "$OUT"

# What the world looks like from the true end pose, by advee-robot-sim's model.
world=$(stack_world_at "$x1" "$y1" "$h1")
printf '%s\n' "$world" | sed 's/^/# model at the end pose: /'
srfs=$(grep '^LL_DATA_SRFS ' "$OUT" | tail -1)
tap_diag "last LL_DATA_SRFS: $srfs"
bad=$(printf '%s\n' "$world" | awk -v msg="$srfs" -v tol="$RANGE_TOL" '
	BEGIN { n = split(msg, w, " "); for (i = 1; i <= n; i++) { split(w[i], kv, "="); got[kv[1]] = kv[2] } }
	$1 == "srf_m" {
		for (i = 2; i <= NF; i++) {
			id = "srf" (i - 2); g = got[id]; want = ($i == "-") ? -1 : $i
			if (g == "") { printf "%s missing ", id; continue }
			d = g - want; if (d < 0) d = -d
			if ((want < 0) != (g < 0) || d > tol) printf "%s=%s(model %s) ", id, g, $i
		}
	}')
tap_ok "the 16 ranges match the world at the true end pose (+-$RANGE_TOL m) ${bad:+: $bad}" test -z "$bad" -a -n "$srfs"

beacons=$(grep '^LL_DATA_BEACONS ' "$OUT" | tail -1)
tap_diag "last LL_DATA_BEACONS: $beacons"
bad=$(printf '%s\n' "$world" | awk -v msg="$beacons" -v tol="$BEARING_TOL_DEG" '
	BEGIN { n = split(msg, w, " "); for (i = 1; i <= n; i++) { split(w[i], kv, "="); if (kv[1] ~ /^b[0-9]+$/) got[substr(kv[1], 2)] = kv[2] } }
	$1 == "beacons" {
		for (i = 2; i <= NF; i++) {
			split($i, p, /@|deg/); id = p[1]; want = p[2]; seen[id] = 1; models++
			if (!(id in got)) { printf "beacon %s not reported ", id; continue }
			d = got[id] * 180 / 3.14159265358979 - want
			while (d > 180) d -= 360; while (d < -180) d += 360
			if (d < 0) d = -d
			if (d > tol) printf "b%s=%.2fdeg(model %s) ", id, got[id] * 180 / 3.14159265358979, want
		}
	}
	END {
		for (id in got) if (!(id in seen)) printf "beacon %s reported but not visible ", id
		if (models == 0) printf "the model sees no beacon at the end pose"
	}')
tap_ok "beacon ids and bearings match the world at the true end pose (+-$BEARING_TOL_DEG degrees)${bad:+: $bad}" test -z "$bad" -a -n "$beacons"

tap_finish
