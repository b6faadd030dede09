#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Load/unload and up/down cycles, unbind/bind through sysfs, and removing the
# bus (the simulator) under a running interface: no warning, no leak, the
# card works again afterwards.
. "$(dirname "$0")/lib.sh"
. "$VMTEST_REPO/tests/lib/wait.sh"
tap_require_module ts-can1
trap cleanup_all EXIT

tap_plan 6
debugfs_mount || exit 1
modprobe ts-can1-sim || exit 1

# Cycles: a leaked reference or allocation shows on the first (kmemleak, the
# module refusing to unload); a few more show it is not a first-time path.
# 20 of each took two minutes of the debug lane for no more coverage.
CYCLES=6
ok=1
for i in $(seq $CYCLES); do
	modprobe ts-can1 || ok=0
	[ -n "$(can_iface)" ] || ok=0
	modprobe -r ts-can1 || ok=0
done
tap_ok "$CYCLES load/unload cycles of ts-can1" test "$ok" = 1

modprobe ts-can1
IF=$(can_iface)
ip link set "$IF" type can bitrate 500000 loopback on
ok=1
for i in $(seq $CYCLES); do
	ip link set "$IF" up || ok=0
	cansend "$IF" "100#$(printf '%02X' "$i")" || ok=0
	ip link set "$IF" down || ok=0
done
tap_ok "$CYCLES up/send/down cycles" test "$ok" = 1

ok=1
for i in $(seq $CYCLES); do
	echo ts-can1 >/sys/bus/platform/drivers/ts-can1/unbind || ok=0
	[ -z "$(can_iface)" ] || ok=0
	echo ts-can1 >/sys/bus/platform/drivers/ts-can1/bind || ok=0
	[ -n "$(can_iface)" ] || ok=0
done
tap_ok "$CYCLES unbind/bind cycles" test "$ok" = 1

IF=$(can_iface)
ip link set "$IF" type can bitrate 1000000 loopback on
ip link set "$IF" up
rx0=$(cat "/sys/class/net/$IF/statistics/rx_packets")
cansend "$IF" 321#01
rx_count() { echo $(($(cat "/sys/class/net/$IF/statistics/rx_packets") - rx0)); }
rx_seen() { [ "$(rx_count)" -ge 1 ]; }
wait_until 20 rx_seen
tap_is "frames still round-trip after rebinding" "$(rx_count)" 1

# The bus goes away under an interface that is up.
modprobe -r ts-can1-sim
tap_ok "removing the bus removes the interface" test -z "$(can_iface)"
tap_ok "ts-can1 unloads afterwards" modprobe -r ts-can1
tap_finish
