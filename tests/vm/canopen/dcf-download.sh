#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# advee-canopenctl dcf (issue 23) against simulated drives as processes on vcan:
# a DCF made of the shipped EPOS EDS (heartbeat 150 ms, TPDO2 remapped) is
# downloaded with the identity checked first and the node started; its
# concise DCF, written without a bus, configures the node again after a
# reset; an IclA whose product code is not the EDS's is refused with both
# values and gets no download and no NMT command. Then the example program
# of docs/canopen.md, built against the staged install of the library
# (scripts/check.sh builds it before the lanes), reads a live node's
# identity.
. "$(dirname "$0")/common.inc"
canopen_setup
tap_plan 12

DATA=$VMTEST_REPO/userland/canopen/data
# ParameterValue KEY VALUE after the section's last line, as a DCF gives it.
awk -v vals='1017=150;1801sub1=$NODEID+0x40000280;1A01sub2=0x60640020;1A01sub0=2' '
	BEGIN { n = split(vals, kv, ";"); for (i = 1; i <= n; i++) { split(kv[i], p, "="); want["[" p[1] "]"] = p[2] } }
	/^\[/ { if (sec in want) print "ParameterValue=" want[sec]; sec = $0 }
	/^$/ && (sec in want) { print "ParameterValue=" want[sec]; delete want[sec] }
	{ print }
	END { if (sec in want) print "ParameterValue=" want[sec]; print "\n[DeviceComissioning]\nNodeID=1\nNodeName=epos" }
' "$DATA/epos-70-10.eds" >"$SCR/epos.dcf"
sed 's/^DefaultValue=0x00000065$/DefaultValue=0x00000066/' "$DATA/icla-d065.eds" >"$SCR/other-icla.eds"
start_sim epos -n 1 -p epos || exit 1
start_sim icla -n 2 -p icla --eds "$SCR/other-icla.eds" || exit 1
CTL=$BIN/advee-canopenctl
# read NODE OBJECT TYPE: the value alone (advee-canopenctl prints "150 (0x96)").
read_value() { "$CTL" -i "$IF" read "$@" | awk '{ print $1 }'; }

# 1. The DCF: identity checked, objects written, started.
"$CTL" -i "$IF" dcf download 1 "$SCR/epos.dcf" >"$SCR/dl.out" 2>&1
rc=$?
sed 's/^/# /' "$SCR/dl.out"
tap_is "dcf download 1 epos.dcf: exit 0" "$rc" 0
tap_ok "it reports the identity it checked and the start" \
	grep -q '^node 1 (epos): 6 objects written, identity checked (device type 0x00020192, vendor 0x000000FB, product 0x64200000, revision 0x00010000), started$' "$SCR/dl.out"
tap_is "node 1 reports 0x1017 = 150 and TPDO2 maps 0x6064" \
	"$(read_value 1 1017 u16) $(read_value 1 1A01:2 u32)" "150 1617166368"
wait_line "$SCR/epos.log" "node 1 nmt operational" 5 >/dev/null
tap_ok "node 1 is operational" grep -q "node 1 nmt operational" "$SCR/epos.log"

# 2. Its concise DCF, with no bus, then downloaded after a reset.
"$CTL" -i nosuchcan0 dcf concise 1 "$SCR/epos.dcf" "$SCR/epos.cdcf" >"$SCR/concise.out" 2>&1
tap_is "dcf concise writes 6 objects in 62 bytes, without a CAN interface" \
	"$(cat "$SCR/concise.out")" "$SCR/epos.cdcf: 6 objects, 62 bytes"
boots=$(grep -c "node 1 nmt pre-operational" "$SCR/epos.log")
"$CTL" -i "$IF" nmt reset-node 1
wait_lines "$SCR/epos.log" "node 1 nmt pre-operational" $((boots + 1)) 5 >/dev/null
before=$(read_value 1 1017 u16)
"$CTL" -i "$IF" dcf download --no-start 1 "$SCR/epos.cdcf" >"$SCR/cdl.out" 2>&1
rc=$?
sed 's/^/# /' "$SCR/cdl.out"
tap_is "after reset-node 0x1017 was back to its default (0)" "$before" 0
tap_is "dcf download --no-start of the concise DCF: exit 0, no identity, left pre-operational" \
	"$rc $(cat "$SCR/cdl.out")" \
	"0 node 1 (epos.cdcf): 6 objects written, identity not checked (a concise DCF has none), left pre-operational"
tap_is "node 1 reports 0x1017 = 150 again" "$(read_value 1 1017 u16)" 150

# 3. The wrong device: refused with both values, not touched.
start_candump
"$CTL" -i "$IF" dcf download 2 "$DATA/icla-d065.eds" >"$SCR/wrong.out" 2>&1
rc=$?
stop_candump
sed 's/^/# /' "$SCR/wrong.out"
tap_is "dcf download to the wrong device: exit 1" "$rc" 1
tap_ok "the refusal names the expected and the found product code" \
	grep -q "wrong device: 0x1018:2 product code expected 0x00000065, found 0x00000066" "$SCR/wrong.out"
# An SDO download request starts with 0x2n (CiA 301 ccs 1); NMT is 000#<cmd><node>.
tap_is "no SDO download and no NMT command to node 2" \
	"$(grep -c '^602#2' "$SCR/frames") $(grep -cE '^000#..(02|00)$' "$SCR/frames")" "0 0"

# 4. The example of docs/canopen.md, built against the installed library.
EX=$VMTEST_BUILD/canopen-example
out=$("$EX/cmake/read-identity" "$IF" 1 2>&1; echo "rc=$?")
out_pc=$("$EX/read-identity-pc" "$IF" 1 2>&1; echo "rc=$?")
printf '%s\n' "$out" | sed 's/^/# /'
tap_is "read-identity (CMake and pkg-config builds) reads node 1's identity" \
	"$(printf '%s\n' "$out" | tr -s ' \n' ' ')|$(printf '%s\n' "$out_pc" | tr -s ' \n' ' ')" \
	"vendor 0x000000FB product 0x64200000 revision 0x00010000 serial 0x00000001 rc=0 |vendor 0x000000FB product 0x64200000 revision 0x00010000 serial 0x00000001 rc=0 "

tap_finish
