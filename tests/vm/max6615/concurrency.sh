#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Writers racing on the fields of one shared register lose no update: six
# processes hammer the two nibbles of THERM_OFFSET, the two tach-disable bits
# of FAN_STATUS and the two fans' fields of FAN_CONFIG at the same time; the
# registers end up holding exactly every writer's last value.
. "$(dirname "$0")/lib.sh"
trap 'kill $writers 2>/dev/null; cleanup_all' EXIT
writers=

tap_header
stub_load 0x18 || { tap_diag "cannot load i2c-stub"; exit 1; }
image_load || { tap_diag "cannot preload the register image"; exit 1; }
reg_set 0x1c 0xc3	# both fans failed, bits 1..0 set: must survive
modprobe max6615 || { tap_diag "cannot load max6615"; exit 1; }
H=$(hwmon_dir)
[ -n "$H" ] || { tap_diag "max6615 did not bind"; exit 1; }
echo 2 >"$H/pwm2_enable"

# hammer ATTR LAST VALUES...: write the values round-robin 60 times, then LAST.
hammer() {
	attr=$1 last=$2
	shift 2
	for _ in $(seq 60); do
		for v in "$@"; do echo "$v" >"$H/$attr"; done
	done
	echo "$last" >"$H/$attr"
}

hammer temp1_offset -6000 2000 -2000 14000 & writers="$writers $!"
hammer temp2_offset 8000 -16000 4000 0 & writers="$writers $!"
hammer fan1_enable 0 1 0 & writers="$writers $!"
hammer fan2_enable 1 0 1 & writers="$writers $!"
hammer pwm1_enable 2 1 2 & writers="$writers $!"
hammer pwm2_auto_channels_temp 3 1 2 & writers="$writers $!"
failed=0
for w in $writers; do wait "$w" || failed=1; done
writers=
tap_is "every write succeeded" "$failed" 0

tap_is "THERM_OFFSET holds both last offsets (-6 C, +8 C)" "$(reg_get 0x17)" 0xd4
tap_is "FAN_STATUS: fan1 tach off, fan2 on, status bits kept" "$(reg_get 0x1c)" 0xe3
tap_is "FAN_CONFIG: hysteresis kept, fan1 on temp1, fan2 on both" "$(reg_get 0x11)" 0xac
tap_is "temp1_offset reads back" "$(cat "$H/temp1_offset")" -6000
tap_is "temp2_offset reads back" "$(cat "$H/temp2_offset")" 8000
tap_is "pwm2_auto_channels_temp reads back" "$(cat "$H/pwm2_auto_channels_temp")" 3

tap_done
