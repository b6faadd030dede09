#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Thesis 6.5 and issue 8 safety: heartbeat loss of a drive -> the master
# quick-stops the propulsion; no motion command for 1 s -> quick stop; a dead
# master -> the drives stop on their own (they consume its heartbeat); EMCY
# from a drive is reported.
. "$(dirname "$0")/common.inc"
canopen_setup
tap_plan 7

start_sim epos -n 1 -p epos || exit 1
start_sim icla -n 2 -p icla || exit 1

# 1. Heartbeat loss of the IclA.
"$BIN/canopen-scenario" -i "$IF" hb-loss >"$SCR/hb.log" 2>&1 &
SC=$!
PIDS+=($SC)
wait_line "$SCR/hb.log" "streaming" 60 && kill -USR2 "$PID_icla"
wait "$SC"
rc=$?
sed 's/^/# /' "$SCR/hb.log"
tap_is "heartbeat loss scenario" "$rc" 0
tap_ok "master reported the lost heartbeat" grep -q "icla: heartbeat lost" "$SCR/hb.log"
tap_ok "EPOS is in quick stop active" wait_line "$SCR/epos.log" "node 1 state quick stop active" 5
kill -USR2 "$PID_icla"  # heartbeat back on

# 2. Motion command timeout.
"$BIN/canopen-scenario" -i "$IF" cmd-timeout >"$SCR/cmd.log" 2>&1
rc=$?
sed 's/^/# /' "$SCR/cmd.log"
tap_is "command timeout scenario (quick stop >= 1 s after the last command)" "$rc" 0

# 3. The master dies (SIGKILL) while driving; EMCY on the way.
"$BIN/canopen-scenario" -i "$IF" stream >"$SCR/stream.log" 2>&1 &
SC=$!
PIDS+=($SC)
wait_line "$SCR/stream.log" "streaming" 60
lines=$(wc -l <"$SCR/epos.log")
kill -9 "$SC"
wait "$SC" 2>/dev/null
tap_ok "drive quick-stops on its own when the master heartbeat stops" \
	wait_line "$SCR/epos.log" 'state quick stop active' 5 "$lines"

"$BIN/canopen-scenario" -i "$IF" stream >"$SCR/emcy.log" 2>&1 &
SC=$!
PIDS+=($SC)
wait_line "$SCR/emcy.log" "streaming" 60 && kill -USR1 "$PID_epos"
tap_ok "EMCY 0x4210 from the EPOS is reported" wait_line "$SCR/emcy.log" "node 1 EMCY 0x4210 \\(temperature\\)" 10
tap_ok "and its fault" wait_line "$SCR/emcy.log" "epos: drive entered fault" 10
kill "$SC"
wait "$SC" 2>/dev/null

tap_finish
