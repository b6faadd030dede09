#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Runs bench/canopen.sh in the VM and shows its numbers as diagnostics. The
# test points check only that every measurement ran and that the master lost
# no frame under the cangen flood; timing is never asserted.
. "$(dirname "$0")/common.inc"
canopen_setup
tap_plan 4

"$VMTEST_REPO/bench/canopen.sh" >"$SCR/bench.log" 2>&1
rc=$?
sed 's/^/# /' "$SCR/bench.log"
tap_is "bench ran to the end" "$rc" 0
tap_ok "SDO round trips measured without SDO errors" grep -qx "sdo_errors 0" "$SCR/bench.log"
tap_ok "1000 PDO round trips measured" grep -qx "pdo_samples 1000" "$SCR/bench.log"
tap_ok "master missed no frame of the flood" grep -qx "flood_frames_missed_by_master 0" "$SCR/bench.log"

tap_finish
