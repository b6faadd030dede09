#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# The CiA 302-2 style boot from device descriptions (issue 23): both
# simulated drives as processes, the IclA's dictionary built from an EDS
# whose product code is not the shipped one; the master boots both from the
# shipped EDS files. The IclA is refused with the expected and the found
# product code and gets no SDO download and no NMT command; the EPOS boots
# (identity checked first) and drives.
. "$(dirname "$0")/common.inc"
canopen_setup
tap_plan 6

DATA=$VMTEST_REPO/userland/canopen/data
sed 's/^DefaultValue=0x00000065$/DefaultValue=0x00000066/' "$DATA/icla-d065.eds" >"$SCR/other-icla.eds"
start_sim epos -n 1 -p epos || exit 1
start_sim icla -n 2 -p icla --eds "$SCR/other-icla.eds" || exit 1
start_candump
"$BIN/canopen-scenario" -i "$IF" --epos-dcf "$DATA/epos-70-10.eds" --icla-dcf "$DATA/icla-d065.eds" \
	dcf-refuse-icla >"$SCR/scenario.log" 2>&1
rc=$?
stop_candump
sed 's/^/# /' "$SCR/scenario.log"
tap_is "dcf-refuse-icla scenario passes every step" "$rc" 0
tap_ok "the refusal names the expected and the found product code" \
	grep -q "wrong device: 0x1018:2 product code expected 0x00000065, found 0x00000066" "$SCR/scenario.log"
# An SDO download request starts with 0x2n (CiA 301 ccs 1); NMT is 000#<cmd><node>.
tap_is "no SDO download to node 2" "$(grep -c '^602#2' "$SCR/frames")" 0
tap_is "no NMT command to node 2 (or to all nodes)" "$(grep -cE '^000#..(02|00)$' "$SCR/frames")" 0
tap_ok "the identity of node 1 was read (0x1018:2 upload)" grep -q '^601#4018100200000000' "$SCR/frames"
tap_ok "EPOS went through operation enabled" grep -q "node 1 state operation enabled" "$SCR/epos.log"

tap_finish
