#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# End to end: the max6615 hwmon driver auto-detects the simulated chip on
# the bit-banged bus (adapter class HWMON), `sensors` shows its values, and
# changes made to the simulated board (temperature, fan speed, a failing fan)
# show up in `sensors`, in the alarm/fault flags and on the FAN_FAIL pin.
. "$(dirname "$0")/lib.sh"
trap cleanup_all EXIT

CONF=$VMTEST_REPO/i2c-max6615/advee-max6615.conf

tap_plan 11
sim_load || { tap_diag "cannot load ts7800_dio + ts7800_sim"; exit 1; }
adapter_load || { tap_diag "cannot load ts7800_dio_i2c"; exit 1; }
chip_set temp1 31500
chip_set temp2 44125
chip_set fan1_rpm 1500		# count 39 -> 58500 / 39 = 1500 RPM
chip_set fan2_rpm 900		# count 65 -> 900 RPM
modprobe max6615 || { tap_diag "cannot load max6615"; exit 1; }
CLIENT=/sys/bus/i2c/devices/$I2C_BUS-0018
tap_is "max6615 detected and bound at 0x18 on the DIO bus" \
	"$(basename "$(readlink "$CLIENT/driver" 2>/dev/null)")" max6615
CHIP=max6615-i2c-$I2C_BUS-18
H=$(ls -d "$CLIENT"/hwmon/hwmon* 2>/dev/null | head -1)

line() { printf '%s\n' "$out" | grep "^$1:"; }
has() {
	if printf '%s\n' "$2" | grep -Eq -- "$3"; then tap_result 0 "$1"; else
		tap_diag "no match for /$3/ in: $2"; tap_result 1 "$1"; fi
}
hasnt() {
	if printf '%s\n' "$2" | grep -Eq -- "$3"; then
		tap_diag "unexpected /$3/ in: $2"; tap_result 1 "$1"; else tap_result 0 "$1"; fi
}

out=$(sensors -c "$CONF" "$CHIP" 2>&1)
printf '%s\n' "$out" | sed 's/^/# /'
has "zone 1 reads 31.5 C" "$(line 'Computer box zone 1')" '\+31\.5.C'
has "zone 2 reads 44.1 C" "$(line 'Computer box zone 2')" '\+44\.1.C'
has "fan 1 reads 1500 RPM" "$(line 'Computer box fan 1')" ' 1500 RPM'
has "fan 2 reads 900 RPM" "$(line 'Computer box fan 2')" ' 900 RPM'
hasnt "no alarm or fault" "$out" 'ALARM|FAULT'

chip_set temp1 52250
raw=$(sensors -u -c "$CONF" "$CHIP" 2>&1)
has "a new simulated temperature is read: temp1_input 52.250" "$raw" 'temp1_input: 52\.250'

# Over-temperature: the crit limit written through hwmon, the OT status
# computed by the model, the alarm shown by sensors.
echo 50000 >"$H/temp1_crit"
out=$(sensors -c "$CONF" "$CHIP" 2>&1)
has "above the crit limit zone 1 shows ALARM" "$(line 'Computer box zone 1')" 'crit = \+50\.0.C.*ALARM'
hasnt "zone 2 (below its limit) does not" "$(line 'Computer box zone 2')" 'ALARM'

# Fan failure: fan1_min 1000 RPM (tach limit 58), the fan slows to 500 RPM
# (count 117): FAN_STATUS bit 7, fan1 FAULT, FAN_FAIL pin (DIO_7) low.
echo 1000 >"$H/fan1_min"
chip_set fan1_rpm 500
out=$(sensors -c "$CONF" "$CHIP" 2>&1)
printf '%s\n' "$out" | sed 's/^/# /'
has "a slow fan 1 shows FAULT" "$(line 'Computer box fan 1')" 'FAULT'
tap_is "and the FAN_FAIL output pulls DIO_7 low" "$(gpioget "$DIO_CHIP" $FANFAIL_OFF)" 0

tap_finish
