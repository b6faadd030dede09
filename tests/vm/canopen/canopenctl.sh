#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# advee-canopenctl against a simulated EPOS on vcan: typed SDO (expedited,
# segmented and block), a scan with identities, abort codes, SDO timeout with
# the abort on the bus, PDO dump and remap, NMT, CiA 402 status and power
# control, monitor, hb.
. "$(dirname "$0")/common.inc"
canopen_setup
tap_plan 23

start_sim epos -n 3 -p epos --sdo-abort 6060:00=08000022 || exit 1
start_sim slow -n 4 -p icla --sdo-delay-ms 800 || exit 1
ctl() { "$BIN/advee-canopenctl" -i "$IF" "$@"; }

tap_is "expedited read of the device type" "$(ctl read 3 1000 u32)" "131474 (0x20192)"
tap_is "segmented read of the device name" "$(ctl read 3 1008 str)" "EPOS 70/10 (simulated)"
ctl write 3 6081 u32 1234
tap_is "write then read back profile velocity" "$(ctl read 3 6081 u32)" "1234 (0x4D2)"
# 300 bytes: 43 segments, blocks of 7 on upload, the server's 16 on download.
long=$(printf '%02X' $(seq 0 255) $(seq 0 43))
start_candump
ctl block write 3 2000 hex "$long"
tap_is "block write then block read back 300 bytes" "$(ctl block -b 7 read 3 2000 hex)" "$long"
stop_candump
tap_ok "both went as block transfers with CRC (initiates C6 and A4, block size 7)" \
	bash -c "grep -q '^603#C60020002C010000$' '$SCR/frames' && grep -q '^603#A400200007' '$SCR/frames'"
tap_is "block read of the device name" "$(ctl block read 3 1008 str)" "EPOS 70/10 (simulated)"
tap_is "scan finds node 3 with its identity, not the silent nodes 1 and 2" "$(ctl -t 200 scan 1-3)" \
	"node 3: device type 0x00020192, vendor 0x000000FB, product 0x64200000, revision 0x00010000, serial 0x00000003"

out=$(ctl read 3 2222 2>&1); rc=$?
tap_is "missing object: exit 1 with the abort text" "$rc:$out" \
	"1:advee-canopenctl: read: object does not exist in the object dictionary (0x06020000)"
out=$(ctl write 3 6041 u16 1 2>&1); rc=$?
tap_is "read-only object refuses a write" "$rc:$out" \
	"1:advee-canopenctl: write: attempt to write a read-only object (0x06010002)"

out=$(ctl write 3 6060 i8 3 2>&1); rc=$?
tap_is "injected abort code reaches the tool" "$rc:$out" \
	"1:advee-canopenctl: write: data cannot be transferred or stored to the application because of the present device state (0x08000022)"

start_candump
out=$(ctl -t 200 read 4 1000 2>&1); rc=$?
stop_candump
tap_is "slow server: local timeout" "$rc:$out" "1:advee-canopenctl: read: SDO protocol timed out (0x05040000)"
tap_ok "the timeout sent abort 0x05040000 to the server" grep -qx "604#8000100000000405" "$SCR/frames"

ctl pdo 3 >"$SCR/pdo" 2>&1
tap_ok "PDO dump shows RPDO4 = controlword + target velocity" \
	grep -qx "RPDO4 0x503 type 255: 6040:00/16 60FF:00/32" "$SCR/pdo"
tap_ok "PDO dump shows TxPDO4 disabled by default" \
	grep -qx "TPDO4 0x483 (disabled) type 255: 6041:00/16 606C:00/32" "$SCR/pdo"
tap_is "pdo remap of TPDO4 (left disabled) reads back what was asked" \
	"$(ctl pdo remap 3 tpdo 4 6041:0/16 6064:0/32 --type 254 --disabled 2>&1)" \
	"TPDO4 0x483 (disabled) type 254: 6041:00/16 6064:00/32"

ctl nmt start 3
tap_ok "NMT start reaches the drive" wait_line "$SCR/epos.log" "node 3 nmt operational" 5
tap_is "status of a fresh drive" "$(ctl status 3)" "statusword 0x0240: switch on disabled, mode 0"
tap_is "enable walks to operation enabled" "$(ctl enable 3)" "operation enabled"
tap_is "quick stop" "$(ctl quick-stop 3)" "quick stop active"
tap_is "disable from quick stop" "$(ctl disable 3)" "switch on disabled"

ctl write 3 1017 u16 50
tap_ok "monitor decodes the drive's heartbeat" \
	bash -c "'$BIN/advee-canopenctl' -i '$IF' monitor 4 | grep -q 'heartbeat node 3 operational'"
tap_is "hb shows the drive's heartbeat with its state" "$(timeout 10 "$BIN/advee-canopenctl" -i "$IF" hb 1)" \
	"heartbeat node 3 operational"
ctl nmt reset-node all
tap_ok "reset node: boot-up seen by the drive log" wait_line "$SCR/epos.log" "node 3 nmt pre-operational" 5

tap_finish
