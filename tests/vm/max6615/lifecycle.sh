#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Unbind/rebind while a reader hammers the attributes, rmmod with an attribute
# file held open, and removing the adapter under the bound driver are clean:
# no hang, no kernel warning (the harness checks dmesg), readings correct again.
. "$(dirname "$0")/lib.sh"
trap 'kill "$reader" 2>/dev/null; exec 3<&- 2>/dev/null; cleanup_all' EXIT
reader=

tap_header
stub_load 0x18 || { tap_diag "cannot load i2c-stub"; exit 1; }
image_load || { tap_diag "cannot preload the register image"; exit 1; }
modprobe max6615 || { tap_diag "cannot load max6615"; exit 1; }
tap_ok "bound" driver_bound
DRV=/sys/bus/i2c/drivers/max6615
CLIENT=$(client_name)

# A reader loops over every attribute while the device comes and goes.
(
	while :; do
		for f in "$(client_dir)"/hwmon/hwmon*/*; do
			cat "$f" >/dev/null 2>&1
		done
	done
) &
reader=$!

ok=1
for i in $(seq 10); do
	echo "$CLIENT" >"$DRV/unbind" || ok=0
	[ -z "$(hwmon_dir)" ] || ok=0
	echo "$CLIENT" >"$DRV/bind" || ok=0
	driver_bound || ok=0
done
tap_ok "10 unbind/bind cycles under concurrent reads" test "$ok" = 1
kill "$reader"
wait "$reader" 2>/dev/null
reader=
H=$(hwmon_dir)
tap_is "temp1_input correct after rebinding" "$(cat "$H/temp1_input" 2>&1)" 39625
tap_is "pwm1_enable correct after rebinding" "$(cat "$H/pwm1_enable" 2>&1)" 2

# rmmod while an attribute file is open: removal must not wait for the file.
exec 3<"$H/temp1_input"
tap_ok "rmmod max6615 with temp1_input held open" timeout 30 modprobe -r max6615
tap_ok "the driver is gone" test ! -e "$DRV"
err=$(cat <&3 2>&1)
tap_is "reading the orphaned file fails with ENODEV" "${err##*: }" "No such device"
exec 3<&-

# Again, with a writable file open for writing.
modprobe max6615
tap_ok "bound again after reloading" driver_bound
H=$(hwmon_dir)
exec 3>"$H/pwm2"
tap_ok "rmmod max6615 with pwm2 held open for writing" timeout 30 modprobe -r max6615
err=$( { echo 100 >&3; } 2>&1)
tap_is "writing the orphaned file fails with ENODEV" "${err##*: }" "No such device"
exec 3>&-

# The adapter disappears under the bound driver.
modprobe max6615
tap_ok "bound before the adapter goes" driver_bound
H=$(hwmon_dir)
exec 3<"$H/fan1_input"
tap_ok "rmmod i2c-stub under the bound driver" timeout 30 modprobe -r i2c-stub
tap_ok "the client went with its adapter" test ! -e "$(client_dir)"
exec 3<&-
tap_ok "max6615 unloads afterwards" timeout 30 modprobe -r max6615

tap_done
