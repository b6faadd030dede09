#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Writing every writable attribute of the max6615 driver lands the right bits
# in the right register and changes nothing else (whole 00h..1Fh dump compared
# with i2cdump), values clamp, pwm values read back unchanged, and bad input
# is rejected with the right errno without touching the chip.
. "$(dirname "$0")/lib.sh"
trap cleanup_all EXIT

tap_header
stub_load 0x18 || { tap_diag "cannot load i2c-stub"; exit 1; }
image_load || { tap_diag "cannot preload the register image"; exit 1; }
# Bits 4..0 of PWM_FREQ carry no function: set some to see them survive.
reg_set 0x14 0x4b
modprobe max6615 || { tap_diag "cannot load max6615"; exit 1; }
H=$(hwmon_dir)
[ -n "$H" ] || { tap_diag "max6615 did not bind at 0x18"; exit 1; }
config_before=$(reg_get 0x02)

attr() { tap_is "$1 reads $2" "$(cat "$H/$1" 2>&1)" "$2"; }

# OT limits: 1 C/LSB, rounded, clamped to 0..255 C
expect_write temp1_crit 85000 0x03 0x55
attr temp1_crit 85000
expect_write temp1_crit 85499 0x03 0x55
expect_write temp1_crit 85500 0x03 0x56
expect_write temp1_crit -5000 0x03 0x00
expect_write temp1_crit 300000 0x03 0xff
expect_write temp2_crit 60000 0x04 0x3c
attr temp2_crit 60000

# THERM_OFFSET 17h = 1Eh: channel 1 high nibble, channel 2 low nibble
expect_write temp1_offset -16000 0x17 0x8e
attr temp1_offset -16000
expect_write temp1_offset 14000 0x17 0x7e
expect_write temp1_offset 20000 0x17 0x7e
expect_write temp1_offset 3000 0x17 0x2e
attr temp1_offset 4000
expect_write temp2_offset 6000 0x17 0x23
attr temp2_offset 6000
expect_write temp2_offset -2000 0x17 0x2f
attr temp2_offset -2000

# fan-start temperatures
expect_write temp1_auto_point1_temp 42000 0x0f 0x2a
attr temp1_auto_point1_temp 42000
expect_write temp1_auto_point1_temp -1000 0x0f 0x00
expect_write temp2_auto_point1_temp 256000 0x10 0xff

# tach limits: count = 58500 / rpm; 0 turns fan-fail detection off (FFh)
expect_write fan1_min 1000 0x1a 0x3b
attr fan1_min 992
expect_write fan1_min 0 0x1a 0xff
attr fan1_min 0
expect_write fan1_min 100 0x1a 0xfe
expect_write fan2_min 100000 0x1b 0x01
attr fan2_min 58500

# FAN_STATUS: tach disable bits 5/4; the status bits 7/6 and bits 3..0 stay
reg_set 0x1c 0xc7
expect_write fan1_enable 0 0x1c 0xe7
expect_write fan2_enable 0 0x1c 0xf7
attr fan1_enable 0
expect_write fan1_enable 1 0x1c 0xd7
expect_write fan2_enable 1 0x1c 0xc7
attr fan2_enable 1
expect_reject fan1_enable 2 "Invalid argument"
reg_set 0x1c 0x00

# pwm2 is manual: target duty 0Ch in 1/240, every pwm value reads back
expect_write pwm2 128 0x0c 0x78
attr pwm2 128
expect_write pwm2 255 0x0c 0xf0
expect_write pwm2 300 0x0c 0xf0
expect_write pwm2 -5 0x0c 0x00
roundtrip_bad=
for v in $(seq 0 255); do
	echo "$v" >"$H/pwm2"
	read -r got <"$H/pwm2"
	[ "$got" = "$v" ] || roundtrip_bad="$roundtrip_bad $v->$got"
done
LAST_DUMP=
tap_is "every pwm2 value 0..255 reads back unchanged" "$roundtrip_bad" ""
# pwm1 is automatic: the chip owns its target duty
expect_reject pwm1 100 "Device or resource busy"

# start and max duty
expect_write pwm1_auto_point1_pwm 100 0x07 0x5e
attr pwm1_auto_point1_pwm 100
expect_write pwm2_auto_point1_pwm 0 0x08 0x00
expect_write pwm1_auto_point2_pwm 255 0x09 0xf0
expect_write pwm2_auto_point2_pwm 200 0x0a 0xbc
attr pwm2_auto_point2_pwm 200

# FAN_CONFIG 11h = A0h: bit 7 (hysteresis) must survive every change
expect_write pwm1_enable 1 0x11 0x80
attr pwm1_enable 1
expect_write pwm1 64 0x0b 0x3c
expect_write pwm1_enable 2 0x11 0xa0
attr pwm1_auto_channels_temp 1
expect_write pwm2_enable 2 0x11 0xa4
expect_write pwm2_auto_channels_temp 3 0x11 0xac
attr pwm2_auto_channels_temp 3
expect_write pwm2_enable 1 0x11 0xa0
attr pwm2_auto_channels_temp 3
expect_write pwm2_auto_channels_temp 1 0x11 0xa0
expect_write pwm2_enable 2 0x11 0xa8
expect_write pwm1_auto_channels_temp 2 0x11 0x98
attr pwm1_auto_channels_temp 2
expect_reject pwm1_enable 0 "Invalid argument"
expect_reject pwm1_enable 3 "Invalid argument"
expect_reject pwm2_auto_channels_temp 0 "Invalid argument"
expect_reject pwm2_auto_channels_temp 4 "Invalid argument"

# PWM_FREQ 14h is shared by both outputs; bits 4..0 survive
expect_write pwm1_freq 20 0x14 0x0b
attr pwm2_freq 20
expect_write pwm2_freq 50 0x14 0x8b
expect_write pwm1_freq 100 0x14 0xcb
expect_write pwm1_freq 35000 0x14 0xeb
attr pwm1_freq 35000
attr pwm2_freq 35000
expect_write pwm1_freq 40 0x14 0x4b
attr pwm1_freq 33
expect_write pwm1_freq 25000 0x14 0x6b
expect_write pwm1_freq -5 0x14 0x0b

# input that is not a number
expect_reject temp1_crit abc "Invalid argument"
expect_reject pwm1_auto_point1_pwm 12x "Invalid argument"
expect_reject temp2_auto_point1_temp "" "Invalid argument"

# read-only attributes stay read-only
expect_reject temp1_input 1000 "Permission denied"

tap_is "CONFIG (02h) was never written" "$(reg_get 0x02)" "$config_before"

tap_done
