#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# `sensors` with the project's sensors.d file shows the BR-FAN1 chip with its
# computer-box labels, temperatures, crit limits and fans; the alarm and fault
# flags appear exactly when the status registers say so.
. "$(dirname "$0")/lib.sh"
trap cleanup_all EXIT

CONF=$VMTEST_REPO/i2c-max6615/advee-max6615.conf

tap_header
stub_load 0x18 || { tap_diag "cannot load i2c-stub"; exit 1; }
image_load || { tap_diag "cannot preload the register image"; exit 1; }
modprobe max6615 || { tap_diag "cannot load max6615"; exit 1; }
tap_ok "max6615 bound" driver_bound
CHIP=max6615-i2c-$STUB_BUS-18

out=$(sensors -c "$CONF" "$CHIP" 2>&1)
printf '%s\n' "$out" | sed 's/^/# /'

# line LABEL: the sensors line of one labelled channel
line() { printf '%s\n' "$out" | grep "^$1:"; }
# has DESC TEXT PATTERN: TEXT matches the extended regex PATTERN
has() {
	if printf '%s\n' "$2" | grep -Eq -- "$3"; then tap_result 0 "$1"; else
		tap_diag "no match for /$3/ in: $2"; tap_result 1 "$1"; fi
}
hasnt() {
	if printf '%s\n' "$2" | grep -Eq -- "$3"; then
		tap_diag "unexpected /$3/ in: $2"; tap_result 1 "$1"; else tap_result 0 "$1"; fi
}

has "chip header" "$out" "^$CHIP\$"
has "zone 1: 39.6 C, crit 70 C" "$(line 'Computer box zone 1')" '\+39\.6.C.*crit = \+70\.0.C'
has "zone 2: 45.1 C, crit 80 C" "$(line 'Computer box zone 2')" '\+45\.1.C.*crit = \+80\.0.C'
has "zone 1 is a thermistor" "$(line 'Computer box zone 1')" 'sensor = thermistor'
has "fan 1: 975 RPM, min 406 RPM" "$(line 'Computer box fan 1')" ' 975 RPM.*min = +406 RPM'
has "fan 2: 900 RPM" "$(line 'Computer box fan 2')" ' 900 RPM'
hasnt "no alarm or fault flag while the status registers are clear" "$out" 'ALARM|FAULT'

# exact values through the raw interface
raw=$(sensors -u -c "$CONF" "$CHIP" 2>&1)
has "temp1_input 39.625 (1/8 degree kept)" "$raw" 'temp1_input: 39\.625'
has "temp2_input 45.125" "$raw" 'temp2_input: 45\.125'
has "temp2_offset -4.000" "$raw" 'temp2_offset: -4\.000'

# OT status bit 7 (channel 1) and fan 2 failure (FAN_STATUS bit 6)
reg_set 0x05 0x80
reg_set 0x1c 0x40
out=$(sensors -c "$CONF" "$CHIP" 2>&1)
printf '%s\n' "$out" | sed 's/^/# /'
has "zone 1 shows the crit alarm" "$(line 'Computer box zone 1')" 'ALARM'
hasnt "zone 2 has no alarm" "$(line 'Computer box zone 2')" 'ALARM'
has "fan 2 shows the fault" "$(line 'Computer box fan 2')" 'FAULT'
hasnt "fan 1 has no fault" "$(line 'Computer box fan 1')" 'FAULT|ALARM'

# a stalled fan reads 0 RPM
reg_set 0x18 0xff
out=$(sensors -c "$CONF" "$CHIP" 2>&1)
has "stalled fan 1 shows 0 RPM" "$(line 'Computer box fan 1')" ' 0 RPM'

tap_done
