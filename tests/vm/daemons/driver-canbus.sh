#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# driver_canbus on vcan0 against two advee-canopen-sim-drive processes (EPOS node 1,
# IclA node 2), checked through LCM and candump: boot, LL_DATA_DRIVES at
# 4 Hz, LL_CMD_MOTION at 10 Hz moves the drives (actual speed within
# 0.01 m/s, steering within 0.001 rad), the 1 s command timeout as a
# quick-stop controlword to node 1 on candump 1.0-1.5 s after the last
# command, the homing gate and homing, LL_EVENT_STOP holds until released,
# PAUSE/RUN, a killed IclA simulator reported and booted again when it comes
# back (with the master's own EMCY 0x8130 and its reset), SIGTERM, and exit
# 0x22 when the drives do not answer; the master's
# own dictionary read over SDO (advee-canopenctl).
. "$(dirname "$0")/lib.sh"
. "$VMTEST_REPO/tests/lib/candump.sh"

canbus_up "$DRIVER_CANBUS" "$PROBE" "$LCMCTL"

tap_plan 24

# drives FILE KEY: KEY of the last LL_DATA_DRIVES line in FILE.
drives() { field "$(grep '^LL_DATA_DRIVES ' "$1" | tail -1)" "$2"; }
errors_numbered() { grep -c "^CM_DATA_ERROR .* number=$2 " "$1"; }

canbus_sims_up
canbus_config "$SCR/canbus.yaml"

candump_start "$IF" "$SCR/candump.log"
listen_bg "$SCR/boot.out" LL_DATA_DRIVES CM_DATA_ERROR
L=$LISTEN_PID
bg "$DRIVER_CANBUS" --config "$SCR/canbus.yaml" 2>"$SCR/canbus.err"
D=$LAST_BG
ENABLED='^LL_DATA_DRIVES .* node1=operation_enabled .* node2=operation_enabled '
wait_line "$SCR/boot.out" "$ENABLED" 30 >/dev/null
# The rate over 9 messages after both drives are enabled (start-up aside).
n0=$(grep -n -m1 -E "$ENABLED" "$SCR/boot.out" | cut -d: -f1)
wait_until 15 eval '[ "$(tail -n +"${n0:-1}" "$SCR/boot.out" | grep -c "^LL_DATA_DRIVES ")" -ge 9 ]'
wait_lines "$SCR/boot.out" ' number=10 ' 2 10 >/dev/null
listen_stop "$L"
tail -n +"${n0:-1}" "$SCR/boot.out" >"$SCR/boot-enabled.out"
n=$(grep -c '^LL_DATA_DRIVES ' "$SCR/boot.out")
tap_diag "$(grep '^LL_DATA_DRIVES ' "$SCR/boot.out" | tail -1)"
tap_is "both drives booted and enabled" "$(drives "$SCR/boot.out" node1) $(drives "$SCR/boot.out" node2)" \
	"operation_enabled operation_enabled"
tap_rate "LL_DATA_DRIVES at 4 Hz" "$SCR/boot-enabled.out" LL_DATA_DRIVES 4
tap_is "two boot notices (number 10)" "$(errors_numbered "$SCR/boot.out" 10)" 2
[ "$n" -ge 1 ] || sed 's/^/# canbus.err: /' "$SCR/canbus.err" | tail -20
tap_is "the master serves its dictionary as node 127: 0x1017 is its 100 ms heartbeat" \
	"$("$CANBIN/advee-canopenctl" -i "$IF" read 127 1017 u16 2>&1)" "100 (0x64)"

# 1. Motion at 10 Hz for 3.5 s, steering not homed yet; the listener runs
# on past the last command to see the timeout.
listen_bg "$SCR/move.out" LL_DATA_DRIVES CM_DATA_ERROR
"$PROBE" motion 0.5 0.1 10 3.5 >"$SCR/motion1.out"
# Until the quick stop's ramp has ended: the first reports after the
# timeout still show the speed coming down (0.4597 m/s in a fresh-clone run
# of 28 Nov under load).
wait_line "$SCR/move.out" '^LL_DATA_DRIVES .* speed=0.0000 .* reason=command_timeout ' 10 >/dev/null
wait_line "$SCR/move.out" ' number=2 ' 5 >/dev/null
listen_stop
candump_sync
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
listen_bg "$SCR/home.out" LL_DATA_DRIVES CM_DATA_ERROR
"$PROBE" homing
wait_line "$SCR/home.out" '^LL_DATA_DRIVES .* homed2=1' 15 >/dev/null
listen_stop
tap_is "LL_CMD_HOMING: steering homed (homed2=1, at 0 rad)" \
	"$(drives "$SCR/home.out" homed2) $(drives "$SCR/home.out" steering)" "1 0.0000"
listen_bg "$SCR/steer.out" LL_DATA_DRIVES
"$PROBE" motion 0.3 0.2 10 3 >/dev/null
listen_stop
tap_diag "$(grep '^LL_DATA_DRIVES ' "$SCR/steer.out" | tail -1)"
tap_ok "0.3 m/s again after the timeout: $(drives "$SCR/steer.out" speed)" close_to "$(drives "$SCR/steer.out" speed)" 0.3 0.01
tap_ok "steering 0.2 rad: $(drives "$SCR/steer.out" steering)" close_to "$(drives "$SCR/steer.out" steering)" 0.2 0.001

lines() { wc -l <"$1"; }
MOVING_03='^LL_DATA_DRIVES .* speed=0\.(29|30|31)[0-9]* .*stopped=0 '

# 4. LL_EVENT_STOP while commands keep coming at 10 Hz.
"$PROBE" motion 0.3 0.2 10 40 >/dev/null &
M=$!
listen_bg "$SCR/stop.out" LL_DATA_DRIVES CM_DATA_ERROR
L=$LISTEN_PID
wait_line "$SCR/stop.out" "$MOVING_03" 20 >/dev/null || tap_diag "not moving before the stop"
"$PROBE" stop on
wait_line "$SCR/stop.out" 'reason=LL_EVENT_STOP' 10 >/dev/null
sleep 1	# an observation window (4 periods, 10 commands), not a synchronisation
held=$(drives "$SCR/stop.out" reason)-$(drives "$SCR/stop.out" speed)
n=$(lines "$SCR/stop.out")
"$PROBE" stop off
tap_is "LL_EVENT_STOP stop=1: held with speed 0 although commands keep coming" "$held" "LL_EVENT_STOP-0.0000"
if wait_line "$SCR/stop.out" "$MOVING_03" 15 "$n" >/dev/null; then r=0; else r=1; fi
tap_is "after stop=0 the next commands move again (0.3 m/s)" "$r" 0
[ "$r" = 0 ] || { grep '^CM_DATA_ERROR ' "$SCR/stop.out"; tail -3 "$SCR/stop.out"; tail -8 "$SCR/epos.log"; } | sed 's/^/# /'

# 5. PAUSE / RUN of the module, commands still coming.
n=$(lines "$SCR/stop.out")
"$LCMCTL" state driver_canbus PAUSE
wait_line "$SCR/stop.out" 'reason=module_paused' 10 "$n" >/dev/null
sleep 1	# an observation window (4 periods, 10 commands), not a synchronisation
paused=$(drives "$SCR/stop.out" reason)-$(drives "$SCR/stop.out" speed)
n=$(lines "$SCR/stop.out")
"$LCMCTL" state driver_canbus RUN
tap_is "PAUSE: drives stopped, commands ignored" "$paused" "module_paused-0.0000"
if wait_line "$SCR/stop.out" "$MOVING_03" 15 "$n" >/dev/null; then r=0; else r=1; fi
tap_is "RUN: the commands move the drives again (0.3 m/s)" "$r" 0
[ "$r" = 0 ] || { grep '^CM_DATA_ERROR ' "$SCR/stop.out"; tail -3 "$SCR/stop.out"; } | sed 's/^/# /'
kill "$M" "$L" 2>/dev/null
wait "$M" "$L" 2>/dev/null

# 6. The IclA simulator killed, then started again (a fresh process sends
# its boot-up message like a drive that was power-cycled).
listen_bg "$SCR/kill.out" LL_DATA_DRIVES CM_DATA_ERROR
kill -9 "$SIM_icla"
wait "$SIM_icla" 2>/dev/null
wait_line "$SCR/kill.out" ' number=7 ' 10 >/dev/null
wait_line "$SCR/kill.out" '^LL_DATA_DRIVES .* node2=offline ' 10 >/dev/null
listen_stop
tap_diag "$(grep '^CM_DATA_ERROR .* number=7 ' "$SCR/kill.out" | head -1)"
tap_is "killed IclA: heartbeat lost reported (error number 7), node2 offline" \
	"$(errors_numbered "$SCR/kill.out" 7) $(drives "$SCR/kill.out" node2)" "1 offline"
listen_bg "$SCR/back.out" LL_DATA_DRIVES CM_DATA_ERROR
sim_drive icla -n 2 -p icla
wait_line "$SCR/back.out" ' number=10 ' 20 >/dev/null
wait_line "$SCR/back.out" '^LL_DATA_DRIVES .* node2=operation_enabled ' 20 "$(grep -n -m1 ' number=10 ' "$SCR/back.out" | cut -d: -f1)" >/dev/null
listen_stop
grep '^CM_DATA_ERROR ' "$SCR/back.out" | sed 's/^/# /'
tap_is "restarted IclA: reboot reported (9), booted again (10), enabled, not homed" \
	"$(errors_numbered "$SCR/back.out" 9) $(errors_numbered "$SCR/back.out" 10) $(drives "$SCR/back.out" node2) $(drives "$SCR/back.out" homed2)" \
	"1 1 operation_enabled 0"
# The master's own EMCY (node 127): heartbeat error 0x8130 with the error
# register's generic and communication bits, then the error reset.
candump_sync
master_emcy=$(grep -o ' 0FF#[0-9A-F]*' "$SCR/candump.log" | tr -d ' ' | tr '\n' ' ')
tap_is "the master's EMCY: 0x8130 while the IclA was lost, the reset when it was back" \
	"$master_emcy" "0FF#3081110000000000 0FF#0000000000000000 "

# 7. SIGTERM.
kill -TERM "$D"
wait_exit "$D" 10
tap_is "SIGTERM: exit 0" "$?" 0

# 8. Drives that do not answer at start-up: device error 2 (0x22).
kill "$SIM_icla" "$SIM_epos" 2>/dev/null
wait "$SIM_icla" "$SIM_epos" 2>/dev/null
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
