#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# driver_canbus on vcan0 against two canopen-sim-drive processes (EPOS node 1,
# IclA node 2), checked through LCM and candump: boot, LL_DATA_DRIVES at
# 4 Hz, LL_CMD_MOTION at 10 Hz moves the drives (actual speed within
# 0.01 m/s, steering within 0.001 rad), the 1 s command timeout as a
# quick-stop controlword to node 1 on candump 1.0-1.5 s after the last
# command, the homing gate and homing, LL_EVENT_STOP holds until released,
# PAUSE/RUN, a killed IclA simulator reported and booted again when it comes
# back, SIGTERM, and exit 0x22 when the drives do not answer.
. "$(dirname "$0")/lib.sh"

canbus_up "$DRIVER_CANBUS" "$PROBE" "$LCMCTL"

tap_plan 22

# drives FILE KEY: KEY of the last LL_DATA_DRIVES line in FILE.
drives() { field "$(grep '^LL_DATA_DRIVES ' "$1" | tail -1)" "$2"; }
errors_numbered() { grep -c "^CM_DATA_ERROR .* number=$2 " "$1"; }

sim_drive epos -n 1 -p epos || { echo "Bail out! EPOS simulator"; exit 1; }
sim_drive icla -n 2 -p icla || { echo "Bail out! IclA simulator"; exit 1; }

# Heartbeats with more slack than on the robot (300 ms / 500 ms there): a
# TCG guest on a busy host stalls for half a second now and then, and each
# stall would otherwise read as a lost drive or a lost master.
cat >"$SCR/canbus.yaml" <<EOC
module: {name: driver_canbus, print_severity: notice, send_severity: notice}
driver_canbus:
  interface: $IF
  command_timeout_s: 1.0
  propulsion: {heartbeat_ms: 250, master_timeout_ms: 2000}
  steering: {heartbeat_ms: 250, master_timeout_ms: 2000}
EOC

candump -L "$IF" >"$SCR/candump.log" 2>&1 &
SIMS+=($!)
"$PROBE" listen 8 LL_DATA_DRIVES CM_DATA_ERROR >"$SCR/boot.out" &
L=$!
sleep 0.5
bg "$DRIVER_CANBUS" --config "$SCR/canbus.yaml" 2>"$SCR/canbus.err"
D=$LAST_BG
wait "$L"
n=$(grep -c '^LL_DATA_DRIVES ' "$SCR/boot.out")
# The rate over the last 3 s of the window (the first seconds include start-up).
t_end=$(grep '^LL_DATA_DRIVES ' "$SCR/boot.out" | tail -1 | sed 's/.* t=\([0-9.]*\) .*/\1/')
n3=$(grep '^LL_DATA_DRIVES ' "$SCR/boot.out" | awk -v e="$t_end" '{ split($2, a, "="); if (a[2] > e - 3.0) n++ } END { print n + 0 }')
tap_diag "$(grep '^LL_DATA_DRIVES ' "$SCR/boot.out" | tail -1)"
tap_is "both drives booted and enabled" "$(drives "$SCR/boot.out" node1) $(drives "$SCR/boot.out" node2)" \
	"operation_enabled operation_enabled"
tap_ok "LL_DATA_DRIVES at 4 Hz (10..14 in the last 3 s; $n3)" test "$n3" -ge 10 -a "$n3" -le 14
tap_is "two boot notices (number 10)" "$(errors_numbered "$SCR/boot.out" 10)" 2
[ "$n" -ge 1 ] || sed 's/^/# canbus.err: /' "$SCR/canbus.err" | tail -20

# 1. Motion at 10 Hz for 3.5 s, steering not homed yet; the listener runs
# on past the last command to see the timeout.
"$PROBE" listen 7.5 LL_DATA_DRIVES CM_DATA_ERROR >"$SCR/move.out" &
L=$!
sleep 1  # the listener subscribes before the first command
"$PROBE" motion 0.5 0.1 10 3.5 >"$SCR/motion1.out"
wait "$L"
moving=$(grep '^LL_DATA_DRIVES .* stopped=0 ' "$SCR/move.out" | tail -1)
tap_diag "$moving"
v=$(field "$moving" speed)
tap_ok "0.5 m/s commanded: actual speed $v within 0.01 m/s" close_to "$v" 0.5 0.01
tap_ok "EPOS RPDO4: target velocity 993 rpm (0.5 m/s, 26:1, r 0.125 m)" grep -q '501#0F00E1030000' "$SCR/candump.log"
tap_is "steering refused until homed: one warning (number 4), no steering" \
	"$(errors_numbered "$SCR/move.out" 4) $(field "$moving" steering) $(field "$moving" homed2)" "1 0.0000 0"

# 2. The command timeout: quick stop to node 1 on candump 1.0-1.5 s after
# the last command (candump -L stamps are CLOCK_REALTIME like last_utime).
# A quick-stop controlword has bit 1 set, bits 2 and 7 clear: first byte
# 02, 03, 0A or 0B.
last_us=$(sed -n 's/^last_utime=//p' "$SCR/motion1.out")
qs=$(awk -v t="$last_us" '{ ts = substr($1, 2, length($1) - 2) * 1e6; split($3, f, "#");
	b = substr(f[2], 1, 2); if (f[1] == "501" && ts > t && (b == "02" || b == "03" || b == "0A" || b == "0B")) {
	printf "%.0f\n", (ts - t) / 1000; exit } }' "$SCR/candump.log")
tap_diag "quick stop to node 1 on candump ${qs:-never} ms after the last LL_CMD_MOTION"
tap_ok "quick stop visible on candump 1.0-1.5 s after the last command" \
	test -n "$qs" -a "${qs:-0}" -ge 1000 -a "${qs:-0}" -le 1500
tap_ok "EPOS simulator in quick stop active" grep -q "node 1 state quick stop active" "$SCR/epos.log"
tap_diag "$(grep '^LL_DATA_DRIVES ' "$SCR/move.out" | tail -1)"
tap_is "LL_DATA_DRIVES: stopped by the command timeout, speed 0" \
	"$(drives "$SCR/move.out" stopped) $(drives "$SCR/move.out" reason) $(drives "$SCR/move.out" speed)" \
	"1 command_timeout 0.0000"
tap_is "the timeout was reported once (warning number 2)" "$(grep -c 'number=2 severity=1' "$SCR/move.out")" 1

# 3. Homing, then steering follows.
"$PROBE" listen 6 LL_DATA_DRIVES CM_DATA_ERROR >"$SCR/home.out" &
L=$!
sleep 0.3
"$PROBE" homing
wait "$L"
tap_is "LL_CMD_HOMING: steering homed (homed2=1, at 0 rad)" \
	"$(drives "$SCR/home.out" homed2) $(drives "$SCR/home.out" steering)" "1 0.0000"
"$PROBE" listen 3 LL_DATA_DRIVES >"$SCR/steer.out" &
L=$!
"$PROBE" motion 0.3 0.2 10 3 >/dev/null
wait "$L"
tap_diag "$(grep '^LL_DATA_DRIVES ' "$SCR/steer.out" | tail -1)"
tap_ok "0.3 m/s again after the timeout: $(drives "$SCR/steer.out" speed)" close_to "$(drives "$SCR/steer.out" speed)" 0.3 0.01
tap_ok "steering 0.2 rad: $(drives "$SCR/steer.out" steering)" close_to "$(drives "$SCR/steer.out" steering)" 0.2 0.001

# after FILE LINE REGEX SECONDS: true once a line after line LINE of FILE
# matches (event-driven: a loaded TCG guest runs 2-3x slower than nominal).
after() {
	local i
	for ((i = 0; i < $4 * 10; i++)); do
		tail -n +"$(($2 + 1))" "$1" | grep -qE "$3" && return 0
		sleep 0.1
	done
	return 1
}
lines() { wc -l <"$1"; }
MOVING_03='^LL_DATA_DRIVES .* speed=0\.(29|30|31)[0-9]* .*stopped=0 '

# 4. LL_EVENT_STOP while commands keep coming at 10 Hz.
"$PROBE" motion 0.3 0.2 10 40 >/dev/null &
M=$!
"$PROBE" listen 40 LL_DATA_DRIVES CM_DATA_ERROR >"$SCR/stop.out" &
L=$!
after "$SCR/stop.out" 0 "$MOVING_03" 20 || tap_diag "not moving before the stop"
"$PROBE" stop on
after "$SCR/stop.out" 0 'reason=LL_EVENT_STOP' 10
sleep 2
held=$(drives "$SCR/stop.out" reason)-$(drives "$SCR/stop.out" speed)
n=$(lines "$SCR/stop.out")
"$PROBE" stop off
tap_is "LL_EVENT_STOP stop=1: held with speed 0 although commands keep coming" "$held" "LL_EVENT_STOP-0.0000"
if after "$SCR/stop.out" "$n" "$MOVING_03" 15; then r=0; else r=1; fi
tap_is "after stop=0 the next commands move again (0.3 m/s)" "$r" 0
[ "$r" = 0 ] || { grep '^CM_DATA_ERROR ' "$SCR/stop.out"; tail -3 "$SCR/stop.out"; tail -8 "$SCR/epos.log"; } | sed 's/^/# /'

# 5. PAUSE / RUN of the module, commands still coming.
n=$(lines "$SCR/stop.out")
"$LCMCTL" state driver_canbus PAUSE
after "$SCR/stop.out" "$n" 'reason=module_paused' 10
sleep 2
paused=$(drives "$SCR/stop.out" reason)-$(drives "$SCR/stop.out" speed)
n=$(lines "$SCR/stop.out")
"$LCMCTL" state driver_canbus RUN
tap_is "PAUSE: drives stopped, commands ignored" "$paused" "module_paused-0.0000"
if after "$SCR/stop.out" "$n" "$MOVING_03" 15; then r=0; else r=1; fi
tap_is "RUN: the commands move the drives again (0.3 m/s)" "$r" 0
[ "$r" = 0 ] || { grep '^CM_DATA_ERROR ' "$SCR/stop.out"; tail -3 "$SCR/stop.out"; } | sed 's/^/# /'
kill "$M" "$L" 2>/dev/null
wait "$M" "$L" 2>/dev/null

# 6. The IclA simulator killed, then started again (a fresh process sends
# its boot-up message like a drive that was power-cycled).
"$PROBE" listen 5 LL_DATA_DRIVES CM_DATA_ERROR >"$SCR/kill.out" &
L=$!
sleep 0.5
kill -9 "$SIM_icla"
wait "$SIM_icla" 2>/dev/null
wait "$L"
tap_diag "$(grep '^CM_DATA_ERROR .* number=7 ' "$SCR/kill.out" | head -1)"
tap_is "killed IclA: heartbeat lost reported (error number 7), node2 offline" \
	"$(errors_numbered "$SCR/kill.out" 7) $(drives "$SCR/kill.out" node2)" "1 offline"
"$PROBE" listen 10 LL_DATA_DRIVES CM_DATA_ERROR >"$SCR/back.out" &
L=$!
sleep 0.3
sim_drive icla -n 2 -p icla
wait "$L"
grep '^CM_DATA_ERROR ' "$SCR/back.out" | sed 's/^/# /'
tap_is "restarted IclA: reboot reported (9), booted again (10), enabled, not homed" \
	"$(errors_numbered "$SCR/back.out" 9) $(errors_numbered "$SCR/back.out" 10) $(drives "$SCR/back.out" node2) $(drives "$SCR/back.out" homed2)" \
	"1 1 operation_enabled 0"

# 7. SIGTERM.
kill -TERM "$D"
wait_exit "$D" 10
tap_is "SIGTERM: exit 0" "$?" 0

# 8. Drives that do not answer at start-up: device error 2 (0x22).
kill "$SIM_icla" "$SIM_epos" 2>/dev/null
wait "$SIM_icla" "$SIM_epos" 2>/dev/null
sleep 0.5
bg "$DRIVER_CANBUS" --config "$SCR/canbus.yaml" 2>"$SCR/noboot.err"
wait_exit "$LAST_BG" 20
rc=$?
tap_diag "$(tail -1 "$SCR/noboot.err")"
tap_is "no drives: exit 0x22 (34)" "$rc" 34
sed "s/interface: $IF/interface: nosuchcan0/" "$SCR/canbus.yaml" >"$SCR/noif.yaml"
bg "$DRIVER_CANBUS" --config "$SCR/noif.yaml" 2>"$SCR/noif.err"
wait_exit "$LAST_BG" 20
rc=$?
tap_diag "$(tail -1 "$SCR/noif.err")"
tap_is "no such interface: exit 0x21 (33)" "$rc" 33

# What the drives reported over the whole run (EMCY 0x8130 = the drive missed
# the master's heartbeat, e.g. when TCG stalls the daemon for 500 ms).
grep -h '^CM_DATA_ERROR .* number=5 ' "$SCR"/*.out | sed 's/^/# EMCY: /'
tap_finish
