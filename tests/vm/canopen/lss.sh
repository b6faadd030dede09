#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# advee-canopenctl lss (CiA 305) against two simulated EPOS drives on vcan that
# start without node-ID (advee-canopen-sim-drive --unconfigured): identify, a
# fastscan that only lists them (vendor-ID and product code given), a
# fastscan that numbers them (they boot and answer SDO at their new
# node-IDs), set-id by identity on a configured node (new node-ID after NMT
# reset communication), set-id refused when two nodes would take it.
. "$(dirname "$0")/common.inc"
canopen_setup
tap_plan 9

start_sim a --unconfigured --serial 0x101 -p epos || exit 1
start_sim b --unconfigured --serial 0x102 -p epos || exit 1
# Two processes answer each fastscan step: the settle time covers the
# second one's answer under TCG.
ctl() { "$BIN/advee-canopenctl" -i "$IF" "$@"; }
lss() { ctl lss --answer-ms 300 --settle-ms 80 "$@"; }
id() { echo "vendor 0x000000FB product 0x64200000 revision 0x00010000 serial 0x$1${2:+ node-ID $2}"; }

tap_is "identify counts the two nodes without node-ID" "$(lss identify)" "2 nodes without node-ID answered"
tap_is "scan lists both, lowest address first" "$(lss scan --vendor FB --product 64200000)" "$(id 00000101; id 00000102)"
tap_is "scan --assign 20 numbers them" "$(lss scan --assign 20 --store)" "$(id 00000101 20; id 00000102 21)"
tap_ok "the first booted as node 20" wait_line "$SCR/a.log" "node 20 nmt pre-operational" 5
tap_is "node 21 answers SDO with its serial number" "$(ctl read 21 1018:4 u32)" "258 (0x102)"
out=$(lss scan 2>&1); rc=$?
tap_is "a second scan finds no node without node-ID" "$rc:$out" \
	"1:advee-canopenctl: lss scan: no node without node-ID answered"
tap_is "set-id by identity on node 21" "$(lss set-id 30 --identity FB:64200000:10000:102)" \
	"node-ID 30 configured (the node has 21 until its next NMT reset communication)"
ctl nmt reset-comm 21
tap_ok "after reset communication it boots as node 30" wait_line "$SCR/b.log" "node 30 nmt pre-operational" 5
out=$(lss set-id 40 2>&1); rc=$?
tap_is "set-id without identity refused with two nodes on the bus" "$rc:$out" \
	"1:advee-canopenctl: lss set-id: more than one node answered; name one with --identity: more than one slave answered (2 answers)"
