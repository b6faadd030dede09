#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# The installed udev rules on the simulated TS-7800's UARTs, as udev would
# apply them on "add": /dev/rs485/<bus> per the mapping file, group advee
# (from the installed sysusers.d file) and mode 0660, the systemd tag and the
# n_rs485 attach unit wanted; a UART outside the mapping gets none of it.
. "$(dirname "$0")/lib.sh"
cleanup() {
	modprobe -r ts7800_sim 2>/dev/null
	modprobe -r ts_uart ts7800_fpga 2>/dev/null
	rm -rf /dev/rs485
	cleanup_mounts
}
trap cleanup EXIT

tap_plan 13
tap_ok "staging install (system files)" stage_system
tap_here "group advee created by the installed sysusers.d file, rules in place" make_live
gid=$(getent group advee | cut -d: -f3)
tap_diag "advee gid: ${gid:-none}; udevd running: $(pgrep -x systemd-udevd >/dev/null && echo yes || echo no)"

if ! modprobe ts_uart || ! modprobe ts7800_sim; then tap_diag "cannot load ts_uart + ts7800_sim"; exit 1; fi
wait_path /sys/class/tty/ttyTSU2 5

# check_bus TTY BUS: one device, four points.
check_bus() {
	local out
	out=$(udev_test "/sys/class/tty/$1")
	printf '%s\n' "$out" | grep -Ei 'rs485|GROUP|MODE|SYSTEMD_WANTS|permissions' | sed 's/^/#   /'
	tap_is "$1: symlink /dev/rs485/$2" \
		"$(prop "$out" DEVLINKS | tr ' ' '\n' | grep '^/dev/rs485/')" "/dev/rs485/$2"
	tap_is "$1: n_rs485 attach unit wanted" \
		"$(prop "$out" SYSTEMD_WANTS)" "advee-rs485-ldattach@$1.service"
	if [ "$1" = ttyTSU0 ]; then
		tap_ok "$1: tagged for systemd (dev-$1.device binds the attach unit)" \
			grep -q ':systemd:' <<<"$(prop "$out" TAGS)"
		# udevadm test of systemd 252 applies the node's permissions and
		# links (on the guest's devtmpfs): what a user of the robot sees.
		tap_is "$1: /dev/$1 group advee, mode 0660" "$(stat -c '%G %a' "/dev/$1")" "advee 660"
		tap_is "$1: /dev/rs485/$2 points to it" "$(readlink -f "/dev/rs485/$2")" "/dev/$1"
	fi
}
check_bus ttyTSU0 a
check_bus ttyTSU1 b
check_bus ttyTSU2 power

# A serial port that is not a robot bus (the guest's console, ttyS0, is
# always there): none of it.
out=$(udev_test /sys/class/tty/ttyS0)
tap_is "ttyS0 (not in the mapping): no /dev/rs485 link" \
	"$(prop "$out" DEVLINKS | tr ' ' '\n' | grep -c '^/dev/rs485/')" 0
tap_ok "ttyS0: udev saw the device, and wants no attach unit" \
	test -n "$(prop "$out" DEVNAME)" -a -z "$(prop "$out" SYSTEMD_WANTS)"
tap_finish
