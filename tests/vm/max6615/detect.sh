#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Auto-detection finds the MAX6615 at each of its nine addresses, never binds
# to a chip whose revision, device or manufacturer ID differs (and says
# nothing about it), writes nothing to the chip while binding; explicit
# instantiation through new_device works for max6615 and max6616.
. "$(dirname "$0")/lib.sh"
trap cleanup_all EXIT

tap_header

# kmsg_lines: kernel log lines so far (to see what a step printed)
kmsg_lines() { dmesg | wc -l; }
# new_kmsg_since N: what the driver or the stub's bus logged after line N
# (other kernel chatter under a loaded host is not the driver's): the driver
# by name, the stub's bus, any client on it ("0-0019")
new_kmsg_since() {
	dmesg | tail -n +"$(($1 + 1))" | grep -E "max661[56]|i2c-$STUB_BUS|$STUB_BUS-00[0-9a-f]{2}"
}

# Detection needs the three ID registers only; the probe reads the rest as 0.
ID_IMAGE="
0xfd 0x01
0xfe 0x68
0xff 0x4d
"
# All nine addresses, and one outside them, on one stub (i2c-stub takes up to
# ten chips): one load of the driver probes them all, as it does on a bus
# with several fan controllers.
ADDRS="0x18 0x19 0x1a 0x29 0x2a 0x2b 0x4c 0x4d 0x4e"
stub_load "$(echo $ADDRS 0x2c | tr ' ' ,)" || { tap_diag "cannot load i2c-stub"; exit 1; }
for addr in $ADDRS 0x2c; do
	CHIP_ADDR=$addr image_load "$ID_IMAGE" || { tap_diag "cannot preload the IDs at $addr"; exit 1; }
done
modprobe max6615 || { tap_diag "cannot load max6615"; exit 1; }
for CHIP_ADDR in $ADDRS; do
	tap_ok "detected and bound at $CHIP_ADDR" driver_bound
done
# An address outside the nine is never probed.
CHIP_ADDR=0x2c
tap_ok "not instantiated at 0x2c (not a MAX6615 address)" test ! -e "$(client_dir)"
cleanup_modules

# Each ID register wrong on its own, one chip each: no device, no message.
BAD_IDS="0x18:0xfd:0x02 0x19:0xfe:0x69 0x1a:0xff:0x4e 0x29:0xfe:0x00"
stub_load 0x18,0x19,0x1a,0x29 || { tap_diag "cannot load i2c-stub"; exit 1; }
for bad in $BAD_IDS; do
	IFS=: read -r CHIP_ADDR reg val <<<"$bad"
	image_load "$ID_IMAGE" && reg_set "$reg" "$val"
done
before=$(kmsg_lines)
modprobe max6615
for bad in $BAD_IDS; do
	IFS=: read -r CHIP_ADDR reg val <<<"$bad"
	tap_ok "no device when register $reg reads $val (at $CHIP_ADDR)" test ! -e "$(client_dir)"
done
CHIP_ADDR=0x18
tap_is "detection of the four chips with a wrong ID is silent" "$(new_kmsg_since "$before")" ""
cleanup_modules

# Binding reads the IDs first and writes nothing, even to a chip that a
# user left in standby (CONFIG bit 7): the driver keeps the chip's settings.
stub_load 0x18 && image_load && reg_set 0x02 0x98
trace_setup || { tap_diag "cannot set up i2c tracing"; exit 1; }
before=$(kmsg_lines)
trace_run modprobe max6615
tap_ok "bound for the write check" driver_bound
tap_is "no SMBus data write while detecting and probing" "$(trace_data_writes)" 0
first3=$(trace_read_regs | head -3 | tr '\n' ' ')
tap_is "the first reads are the ID registers" "$first3" "ff fe fd "
tap_is "standby left as the user set it" "$(reg_get 0x02)" 0x98
tap_ok "the standby state is reported" sh -c "dmesg | tail -n +$((before + 1)) | grep -q 'standby'"
trace_teardown
cleanup_modules

# Explicit instantiation. Detection runs first while the stub is blank (no
# IDs, nothing binds), then the image goes in and user space declares the chip.
stub_load 0x18
modprobe max6615
tap_ok "a blank chip is not detected" test ! -e "$(client_dir)"
image_load
NEW=/sys/bus/i2c/devices/i2c-$STUB_BUS/new_device
DEL=/sys/bus/i2c/devices/i2c-$STUB_BUS/delete_device
for chip in max6615 max6616; do
	echo "$chip 0x18" >"$NEW"
	tap_ok "new_device $chip 0x18 binds" driver_bound
	H=$(hwmon_dir)
	tap_is "$chip: hwmon name" "$(cat "$H/name" 2>&1)" "$chip"
	tap_is "$chip: temp1_input" "$(cat "$H/temp1_input" 2>&1)" 39625
	echo 0x18 >"$DEL"
	tap_ok "delete_device removes $chip" test ! -e "$(client_dir)"
done
# Declared by hand but the IDs do not match: probe refuses, says why.
reg_set 0xfe 0x42
before=$(kmsg_lines)
echo "max6615 0x18" >"$NEW"
tap_ok "new_device on a wrong ID does not bind" test ! -e "$(client_dir)/driver"
tap_ok "the probe failure is logged" sh -c "dmesg | tail -n +$((before + 1)) | grep -q '$(client_name): .*no MAX6615/MAX6616'"
echo 0x18 >"$DEL"
cleanup_modules

tap_done
