#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# The installed MAX6615 rule on the simulated TS-7800: when the DIO I2C
# adapter appears, udev declares the BR-FAN1 chip at 0x18 (new_device), so
# the max6615 driver binds it by its modalias, with no .detect involved
# (max6615 is not loaded when the rule runs); sensors then shows it with the
# installed /etc/sensors.d labels. Another I2C adapter gets no client.
. "$(dirname "$0")/lib.sh"
I2C_DEV_LOADED_BY_US=0
cleanup() {
	for c in /sys/bus/i2c/devices/*-0018; do
		[ -e "$c" ] || continue
		a=${c##*/}; echo 0x18 >"/sys/bus/i2c/devices/i2c-${a%-0018}/delete_device" 2>/dev/null
	done
	modprobe -r max6615 2>/dev/null
	modprobe -r ts7800_dio_i2c i2c-stub 2>/dev/null
	[ "$I2C_DEV_LOADED_BY_US" = 1 ] && modprobe -r i2c-dev 2>/dev/null
	modprobe -r ts7800_sim 2>/dev/null
	modprobe -r ts7800_dio ts_uart ts7800_fpga 2>/dev/null
	cleanup_mounts
}
trap cleanup EXIT

tap_plan 7
tap_ok "staging install (system files)" stage_system
tap_here "rules in place" make_live

# The simulated FPGA with its DIO header and the MAX6615 model on DIO_1/DIO_3.
if ! modprobe ts7800_dio || ! modprobe ts7800_sim || ! modprobe ts7800_dio_i2c; then
	tap_diag "cannot load ts7800_dio + ts7800_sim + ts7800_dio_i2c"; exit 1
fi
bus=
dio_bus() {
	for a in /sys/bus/i2c/devices/i2c-*; do
		grep -q '^TS-7800 DIO I2C' "$a/name" 2>/dev/null && bus=${a##*/i2c-}
	done
	[ -n "$bus" ]
}
wait_until 10 dio_bus
[ -n "$bus" ] || { tap_diag "no TS-7800 DIO I2C adapter"; exit 1; }
grep -q '^max6615 ' /proc/modules && { tap_diag "max6615 already loaded: the test would prove nothing"; exit 1; }

# udevadm test (systemd 252) writes the rule's sysfs attributes like udevd.
udev_test "/sys/bus/i2c/devices/i2c-$bus" | grep -i 'new_device\|max6615\|ATTR' | sed 's/^/#   /'
client=/sys/bus/i2c/devices/$bus-0018
tap_is "the rule declared the chip: client $bus-0018 named max6615" "$(cat "$client/name" 2>/dev/null)" max6615

# udevd would load the driver from the client's modalias; here: modprobe by it.
modalias=$(cat "$client/modalias" 2>/dev/null)
tap_ok "the client's modalias ($modalias) loads max6615" modprobe "$modalias"
wait_path "$client/driver" 5
tap_is "max6615 bound to the declared client" "$(basename "$(readlink "$client/driver" 2>/dev/null)")" max6615

if ! grep -q '^i2c_dev ' /proc/modules; then modprobe i2c-dev && I2C_DEV_LOADED_BY_US=1; fi
out=$(sensors -c "$DEST/etc/sensors.d/advee-max6615.conf" "max6615-i2c-$bus-18" 2>&1)
printf '%s\n' "$out" | sed 's/^/#   /'
tap_ok "sensors shows it with the installed labels" grep -q '^Computer box zone 1:' <<<"$out"

# Any other adapter (i2c-stub, class HWMON too): the rule leaves it alone.
modprobe i2c-stub chip_addr=0x18 || { tap_diag "cannot load i2c-stub"; exit 1; }
stub=
for a in /sys/bus/i2c/devices/i2c-*; do grep -q '^SMBus stub driver' "$a/name" 2>/dev/null && stub=${a##*/i2c-}; done
udev_test "/sys/bus/i2c/devices/i2c-$stub" >/dev/null
tap_is "another adapter (i2c-stub, i2c-$stub) gets no client from the rule" \
	"$(cat "/sys/bus/i2c/devices/$stub-0018/name" 2>/dev/null)" ""
tap_finish
