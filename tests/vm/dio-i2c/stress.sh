#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Malformed bus sequences between transfers never wedge the adapter: an
# outside device toggles SCL/SDA at random (debugfs ext_low), or leaves the
# slave in the middle of a read holding SDA low; the next transfer recovers
# (nine clocks and a STOP when SDA is held) and reads the right value.
. "$(dirname "$0")/lib.sh"
trap cleanup_all EXIT

ROUNDS=20
TOGGLES=40

tap_plan 5
sim_load || { tap_diag "cannot load ts7800_dio + ts7800_sim"; exit 1; }
adapter_load || { tap_diag "cannot load ts7800_dio_i2c"; exit 1; }
SCL_LOW=$((1 << SCL_OFF))
SDA_LOW=$((1 << SDA_OFF))
ext() { echo "$1" >"$DIOFS/ext_low"; }
devid() { i2cget -y "$I2C_BUS" "$CHIP_ADDR" 0xfe 2>/dev/null; }

# 1. A read cut short after the address: the slave drives the first data
# bit of FEh (0x68: bit 7 = 0) and keeps SDA low.
devid >/dev/null	# register pointer = FEh
ext $SDA_LOW					# START
ext $((SDA_LOW | SCL_LOW))
for b in 0 0 1 1 0 0 0 1; do			# 0x18 << 1 | read
	v=$(( SCL_LOW | (b ? 0 : SDA_LOW) ))
	ext $v; ext $((v & ~SCL_LOW)); ext $v
done
ext $SCL_LOW; ext 0; ext $SCL_LOW		# ACK clock (the slave acks)
ext 0						# outside device lets go
tap_is "a cut-short read leaves SDA held low by the slave" "$(pin_level $SDA_OFF)" 0
DYNDBG=/sys/kernel/debug/dynamic_debug/control
echo 'module ts7800_dio_i2c +p' >"$DYNDBG"
dmesg_before=$(dmesg | wc -l)
tap_is "the next transfer recovers the bus and reads FEh = 0x68" "$(devid)" 0x68
tap_ok "the adapter ran its bus recovery for it (dynamic debug message)" \
	sh -c "dmesg | tail -n +$((dmesg_before + 1)) | grep -q 'SDA held low before a transfer: bus recovery'"

# 2. Random toggles of both lines between transfers.
ok=0 fails="" held=0
dmesg_before=$(dmesg | wc -l)
for r in $(seq $ROUNDS); do
	for _t in $(seq $TOGGLES); do
		ext $(( (RANDOM & 1 ? SCL_LOW : 0) | (RANDOM & 1 ? SDA_LOW : 0) ))
	done
	ext 0
	[ "$(pin_level $SDA_OFF)" = 0 ] && held=$((held + 1))
	v=$(devid)
	if [ "$v" = 0x68 ]; then ok=$((ok + 1)); else fails="$fails $r:$v"; fi
done
recoveries=$(dmesg | tail -n +$((dmesg_before + 1)) | grep -c 'bus recovery')
tap_diag "rounds that left SDA held low by the slave: $held of $ROUNDS; bus recoveries: $recoveries"
echo 'module ts7800_dio_i2c -p' >"$DYNDBG"
tap_is "after $ROUNDS rounds of $TOGGLES random toggles the next transfer works" "$ok$fails" "$ROUNDS"
tap_is "and the bus is idle afterwards" "$(pin_level $SCL_OFF)$(pin_level $SDA_OFF)" 11

tap_finish
