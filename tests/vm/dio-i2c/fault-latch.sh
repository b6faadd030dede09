#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# A fan failure that the MAX6615 latched must reach user space even when the
# fan has recovered and another attribute read FAN_STATUS first (the
# simulated chip clears the fail bits on a read, as the datasheet's status
# registers may): the driver keeps the bit until fanN_fault has been read,
# as mainline hwmon drivers do. Reading it once reports the failure, the
# next read the current state.
. "$(dirname "$0")/lib.sh"
trap cleanup_all EXIT

tap_plan 7
sim_load || { tap_diag "cannot load ts7800_dio + ts7800_sim"; exit 1; }
adapter_load || { tap_diag "cannot load ts7800_dio_i2c"; exit 1; }
chip_set fan1_rpm 1500
chip_set fan2_rpm 900
modprobe max6615 || { tap_diag "cannot load max6615"; exit 1; }
CLIENT=/sys/bus/i2c/devices/$I2C_BUS-0018
H=$(ls -d "$CLIENT"/hwmon/hwmon* 2>/dev/null | head -1)
tap_ok "max6615 bound on the DIO bus" test -n "$H"

echo 1000 >"$H/fan1_min"
tap_is "fan1_fault is 0 while the fan runs" "$(cat "$H/fan1_fault")" 0
# The fan stalls briefly: the chip latches FAN_STATUS bit 7 ...
chip_set fan1_rpm 500
fan1_latched() { [ $((0x$(model_reg 0x1c) & 0x80)) -ne 0 ]; }
wait_until 5 fan1_latched
tap_ok "the simulated chip latched the failure" test $((0x$(model_reg 0x1c) & 0x80)) -ne 0
# ... and recovers before anybody looks.
chip_set fan1_rpm 1500
# Reading the speed (and the enable) reads FAN_STATUS: the chip clears the bit.
speed=$(cat "$H/fan1_input")
enable=$(cat "$H/fan1_enable")
tap_ok "fan1_input ($speed) and fan1_enable ($enable) read FAN_STATUS first" \
	test "$speed" = 1500 -a "$enable" = 1
tap_is "fan1_fault still reports the failure" "$(cat "$H/fan1_fault")" 1
tap_is "once seen, it shows the current state again" "$(cat "$H/fan1_fault")" 0
tap_is "fan2_fault was never set" "$(cat "$H/fan2_fault")" 0
tap_finish
