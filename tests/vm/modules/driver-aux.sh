#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# driver_aux on the simulated BR-FAN1: LL_DATA_TEMPERATURE and LL_DATA_FANS
# carry what the simulator was set to, at the configured rate; a new
# temperature and a failing fan (fault + FAN_FAIL GPIO) show up; PAUSE stops
# the publishing and RUN resumes it; lcm-logger records a run that
# lcm-logplayer replays into a subscriber; a missing chip is exit code 0x21.
. "$(dirname "$0")/lib.sh"
trap modules_cleanup EXIT

tap_plan 16
lcm_net_up || { tap_diag "cannot set up loopback multicast"; exit 1; }
board_up || { tap_diag "cannot bring up the simulated board"; exit 1; }
CFG=$VMTEST_SCRATCH/driver_aux.yaml
aux_config "$CFG" 4

bg "$DRIVER_AUX" --config "$CFG"
AUX=$LAST_BG

t=$(echo_msgs 1 5 LL_DATA_TEMPERATURE)
tap_diag "$t"
tap_is "temp1 as the simulator was set (31.5 C)" "$(field "$t" temp1)" 31.500
tap_is "temp2 as the simulator was set (44.125 C)" "$(field "$t" temp2)" 44.125
tap_is "sender is driver_aux" "$(field "$t" module)" driver_aux
f=$(echo_msgs 1 5 LL_DATA_FANS)
tap_diag "$f"
tap_is "fan1 1500 RPM, fan2 900 RPM, no fault, fan-fail line released" \
	"$(field "$f" fan1) $(field "$f" fan2) $(field "$f" fan1_fault) $(field "$f" fan_fail)" "1500 900 0 0"

# Rate: 4 Hz configured; counted over the interval 9 messages span.
L=$VMTEST_SCRATCH/temperature.out
listen_bg "$L" LL_DATA_TEMPERATURE
wait_lines "$L" '^LL_DATA_TEMPERATURE ' 9 10 >/dev/null
listen_stop
tap_rate "LL_DATA_TEMPERATURE at the configured 4 Hz" "$L" LL_DATA_TEMPERATURE 4
s=$(echo_msgs 1 3 CM_DATA_STATE)
tap_is "announces RUN on CM_DATA_STATE" "$(field "$s" state)" RUN

listen_bg "$L" LL_DATA_TEMPERATURE
chip_set temp1 52250
wait_line "$L" '^LL_DATA_TEMPERATURE .* temp1=52\.250 ' 10 >/dev/null
tap_result $? "a new simulated temperature is published (52.25 C)"
listen_stop
chip_set temp1 31500

# Fan failure: tach limit 1000 RPM, fan1 slows to 500 RPM: the chip flags
# fan1 and pulls FAN_FAIL (DIO_7) low; driver_aux reports both and sends a
# warning on CM_DATA_ERROR.
E=$VMTEST_SCRATCH/fans-errors.out
bg "$LCMCTL" echo --timeout 60 LL_DATA_FANS CM_DATA_ERROR >"$E"
FE=$LAST_BG
wait_lcm_listening "$FE" 20
echo 1000 >"$HWMON/fan1_min"
chip_set fan1_rpm 500
wait_line "$E" '^LL_DATA_FANS .* fan1_fault=1 .* fan_fail=1' 20 >/dev/null
ok=$?
wait_line "$E" '^CM_DATA_ERROR ' 10 >/dev/null
kill "$FE"
f=$(grep '^LL_DATA_FANS ' "$E" | tail -1)
tap_diag "$f"
tap_result $ok "a failing fan shows as fan1_fault=1 and fan_fail=1 (GPIO DIO_7)"
e=$(grep -m1 '^CM_DATA_ERROR ' "$E")
tap_diag "$e"
tap_is "fan failure reported on CM_DATA_ERROR as a device warning" \
	"$(field "$e" module) $(field "$e" severity) $(field "$e" type)" "driver_aux 1 3"
chip_set fan1_rpm 1500

# PAUSE stops publishing, RUN resumes it.
"$LCMCTL" state driver_aux PAUSE
tap_ok "announces PAUSE" wait_state driver_aux 6 10 "$AUX"
listen_bg "$L" LL_DATA_TEMPERATURE
sleep 1.5	# an observation window (6 periods at 4 Hz), not a synchronisation
listen_stop
tap_is "no LL_DATA_TEMPERATURE in 1.5 s while PAUSEd" "$(grep -c '^LL_DATA_TEMPERATURE ' "$L")" 0
"$LCMCTL" state driver_aux RUN
n=$(echo_msgs 2 10 LL_DATA_TEMPERATURE | wc -l)
tap_is "RUN resumes publishing" "$n" 2

# lcm-logger records while 4 readings go by; lcm-logplayer replays them on
# another port into a subscriber, which sees the same readings.
LOG=$VMTEST_SCRATCH/run.lcmlog
bg lcm-logger -f "$LOG"
LOGGER=$LAST_BG
wait_lcm_listening "$LOGGER" 20
listen_bg "$L" LL_DATA_TEMPERATURE
wait_lines "$L" '^LL_DATA_TEMPERATURE ' 4 10 >/dev/null
listen_stop
kill "$LOGGER"; wait "$LOGGER" 2>/dev/null
REPLAY_URL="udpm://239.255.76.67:7668?ttl=0"
R=$VMTEST_SCRATCH/replay.out
bg "$LCMCTL" --url "$REPLAY_URL" echo --count 3 --timeout 20 LL_DATA_TEMPERATURE >"$R"
RE=$LAST_BG
wait_udp_bound "$RE" 7668 20
lcm-logplayer -l "$REPLAY_URL" "$LOG"
wait_exit "$RE" 20
r=$(cat "$R")
tap_diag "$r"
tap_is "the replay carries the recorded readings" \
	"$(printf '%s\n' "$r" | awk '{ print $3, $4 }' | sort -u)" "temp1=31.500 temp2=44.125"

# SIGTERM: TERMINATE, exit 0.
kill "$AUX"
wait "$AUX"
tap_is "SIGTERM ends driver_aux with exit code 0" "$?" 0
BG_PIDS=

# No chip: the documented exit code and a clear message.
modprobe -r max6615
out=$("$DRIVER_AUX" --config "$CFG" 2>&1)
rc=$?
tap_diag "$out"
tap_is "without the max6615 hwmon device: exit code 0x21 (device error 1)" "$rc" 33
tap_ok "the message names the missing device" grep -q "no hwmon device named 'max6615'" <<<"$out"
tap_finish
