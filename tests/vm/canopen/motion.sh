#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Both drives simulated as separate processes: boot (PDO read-back, TxPDO4
# switched on, heartbeats configured), enable, IclA homing on the switch,
# velocity move on the EPOS, position move on the IclA.
. "$(dirname "$0")/common.inc"
canopen_setup
tap_plan 4

start_sim epos -n 1 -p epos || exit 1
start_sim icla -n 2 -p icla --home-switch -2000 || exit 1
"$BIN/canopen-scenario" -i "$IF" motion >"$SCR/scenario.log" 2>&1
rc=$?
sed 's/^/# /' "$SCR/scenario.log"
tap_is "motion scenario passes every step" "$rc" 0
tap_is "every step ran and none failed (steps ok, not ok)" \
	"$([ "$(grep -c '^ok ' "$SCR/scenario.log")" -gt 0 ] && echo some) $(grep -c '^not ok' "$SCR/scenario.log")" "some 0"
tap_ok "EPOS went through operation enabled" grep -q "node 1 state operation enabled" "$SCR/epos.log"
tap_ok "IclA ended disabled" bash -c "grep 'node 2 state' '$SCR/icla.log' | tail -1 | grep -q 'switch on disabled'"

tap_finish
