#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Every attribute of the max6615 driver reads the value computed by hand from
# the BR-FAN1 register image (lib.sh), including 1/8 degree fractions, the
# 0 and 255 degree ends, a stalled tach and the status flags.
. "$(dirname "$0")/lib.sh"
trap cleanup_all EXIT

tap_header

stub_load 0x18 || { tap_diag "cannot load i2c-stub"; exit 1; }
image_load || { tap_diag "cannot preload the register image"; exit 1; }
modprobe max6615 || { tap_diag "cannot load max6615"; exit 1; }
tap_ok "auto-detection binds max6615 at 0x18" driver_bound
H=$(hwmon_dir)
[ -n "$H" ] || { tap_diag "no hwmon directory under $(client_dir)"; exit 1; }

tap_is "name" "$(cat "$H/name")" max6615

# attr NAME WANT: read one attribute and compare.
attr() { tap_is "$1 = $2" "$(cat "$H/$1" 2>&1)" "$2"; }

attr temp1_input 39625
attr temp2_input 45125
attr temp1_crit 70000
attr temp2_crit 80000
attr temp1_crit_alarm 0
attr temp2_crit_alarm 0
attr temp1_offset 2000
attr temp2_offset -4000
attr temp1_type 4
attr temp2_type 4
attr temp1_auto_point1_temp 35000
attr temp2_auto_point1_temp 40000
attr fan1_input 975
attr fan2_input 900
attr fan1_min 406
attr fan2_min 0
attr fan1_fault 0
attr fan2_fault 0
attr fan1_enable 1
attr fan2_enable 1
attr pwm1 51
attr pwm2 51
attr pwm1_enable 2
attr pwm2_enable 1
attr pwm1_auto_channels_temp 1
attr pwm2_auto_channels_temp 2
attr pwm1_freq 33
attr pwm2_freq 33
attr pwm1_auto_point1_pwm 51
attr pwm2_auto_point1_pwm 64
attr pwm1_auto_point2_pwm 255
attr pwm2_auto_point2_pwm 213

# Volatile registers change under the driver: no stale cache.
reg_set 0x00 0x00; reg_set 0x1e 0x00
attr temp1_input 0
reg_set 0x01 0xff; reg_set 0x1f 0xe0
attr temp2_input 255875
reg_set 0x1e 0x20
reg_set 0x00 0x19
attr temp1_input 25125
reg_set 0x18 0xff
attr fan1_input 0
reg_set 0x19 0x01
attr fan2_input 58500
reg_set 0x05 0x80
attr temp1_crit_alarm 1
attr temp2_crit_alarm 0
reg_set 0x05 0x40
attr temp2_crit_alarm 1
reg_set 0x1c 0x40
attr fan1_fault 0
attr fan2_fault 1
# tach 2 disabled (FAN_STATUS bit 4): fan2_enable 0 and no reading (ABI: ENODATA)
reg_set 0x1c 0x10
attr fan2_enable 0
tap_is "fan2_input of a disabled tach fails with ENODATA" \
	"$(cat "$H/fan2_input" 2>&1 | sed 's/.*: //')" "No data available"
# the automatic target duty is the chip's: re-read, scaled (0x78 = 120/240 -> 128)
reg_set 0x0b 0x78
attr pwm1 128
reg_set 0x0b 0xf5
attr pwm1 255


# CONFIG bit 1: channel 2 measures the die (a diode) instead of thermistor 2.
# CONFIG is cached: change it while unbound, the rebind starts a new cache.
echo "$(client_name)" >/sys/bus/i2c/drivers/max6615/unbind
reg_set 0x02 0x1a
echo "$(client_name)" >/sys/bus/i2c/drivers/max6615/bind
H=$(hwmon_dir)
attr temp2_type 3
attr temp1_type 4

tap_done
