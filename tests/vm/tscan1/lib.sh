# SPDX-License-Identifier: GPL-2.0
# Helpers of the tscan1 VM suite (sourced, not a test program): the simulated
# PC/104 bus with a TS-CAN1 card (ts-can1-sim) and the ts-can1 driver.

. "$VMTEST_REPO/tests/lib/tap.sh"
. "$VMTEST_REPO/tests/lib/wait.sh"

SIMSTATE=/sys/kernel/debug/ts-can1-sim/state
DEV=/sys/bus/platform/devices/ts-can1
DEBUGFS_MOUNTED_BY_US=0
DMESG_MARK=0

debugfs_mount() {
	[ -d /sys/kernel/debug/tracing ] || [ -n "$(ls -A /sys/kernel/debug 2>/dev/null)" ] && return 0
	mount -t debugfs none /sys/kernel/debug && DEBUGFS_MOUNTED_BY_US=1
}

# The kernel lines logged since the last dmesg_mark.
dmesg_mark() { DMESG_MARK=$(dmesg | wc -l); }
dmesg_new() { dmesg | tail -n +$((DMESG_MARK + 1)); }
# dmesg_has REGEX: a line since the mark matches (extended regex)
dmesg_has() { dmesg_new | grep -Eq -- "$1"; }

# card_load [SIM PARAMS]: the simulated bus (with the given card settings),
# then the driver, which binds to the simulator's ts-can1 device.
card_load() {
	debugfs_mount || return 1
	dmesg_mark
	modprobe ts-can1-sim "$@" || return 1
	modprobe ts-can1 || return 1
}

card_unload() {
	modprobe -r ts-can1 2>/dev/null
	modprobe -r ts-can1-sim 2>/dev/null
	! grep -Eq '^(ts_can1|ts_can1_sim) ' /proc/modules
}

cleanup_all() {
	card_unload
	modprobe -r can-dev 2>/dev/null
	[ "$DEBUGFS_MOUNTED_BY_US" = 1 ] && umount /sys/kernel/debug
	return 0
}

# The CAN interface of the card (one card on the simulated bus), or nothing.
can_iface() { ls "$DEV/net" 2>/dev/null | head -1; }
driver_bound() { [ -e "$DEV/driver" ]; }

# sim_field KEY: the value after KEY in the simulator's state file
sim_field() { awk -v k="$1" '{ for (i = 1; i < NF; i++) if ($i == k) { print $(i + 1); exit } }' "$SIMSTATE"; }

# candump_ready PID: wait (up to 30 s) until the candump started as PID (or
# as a child of PID, e.g. under timeout) has bound its CAN socket to $IF:
# the CAN core then lists a receiver for $IF in /proc/net/can/rcvlist_all
# (candump with or without an identifier filter registers one there), and
# no frame sent afterwards can be missed. An open socket alone is not
# enough: on the debug kernel candump's bind() came well after socket().
# The caller has no other raw CAN socket on $IF at that moment.
candump_ready() {
	wait_until 30 _can_bound "$1" || return 1
}
_can_bound() {
	kill -0 "$1" 2>/dev/null || return 1
	grep -q "^ *$IF " /proc/net/can/rcvlist_all 2>/dev/null
}
