#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Unbinding the PC/104 bus provider under a running interface (issue 18
# item 14). The bus device is a child that the provider creates with its
# interrupt mappings (ts7800_fpga_add_pc104(), the same helper for the FPGA
# core and the simulator): unbinding the provider's driver removes the
# device, and so unbinds ts-can1 and frees its interrupt, before the
# provider disposes of the mappings and its irq domain. Afterwards there is
# no CAN device left to unbind, the provider binds again with a working
# card, and the rmmod order provider-first is clean. On the debug lane the
# harness fails the program on any KASAN, lockdep or kmemleak report.
. "$(dirname "$0")/lib.sh"
. "$VMTEST_REPO/tests/lib/wait.sh"
tap_require_module ts-can1
CAND=
trap '[ -n "$CAND" ] && kill "$CAND" 2>/dev/null; cleanup_all' EXIT

SIMDRV=/sys/bus/platform/drivers/ts-can1-sim
CANDRV=/sys/bus/platform/drivers/ts-can1

# Interrupts of the provider's domain: /sys/kernel/irq/N of its chip.
provider_irqs() { grep -lx 'ts-can1-sim' /sys/kernel/irq/*/chip_name 2>/dev/null | wc -l; }

# up_and_listen: interface up with self reception and a candump on it.
up_and_listen() {
	IF=$(can_iface)
	[ -n "$IF" ] || return 1
	ip link set "$IF" type can bitrate 500000 loopback on &&
		ip link set "$IF" up || return 1
	candump "$IF" >"$VMTEST_SCRATCH/candump.txt" 2>&1 &
	CAND=$!
	candump_ready "$CAND"
}

rx_packets() { cat "/sys/class/net/$IF/statistics/rx_packets"; }
rx_above() { [ "$(rx_packets)" -gt "$1" ]; }
# round_trip ID: one frame comes back through the chip's receive path.
round_trip() {
	local rx0
	rx0=$(rx_packets)
	cansend "$IF" "$1#55" && wait_until 20 rx_above "$rx0"
}

tap_plan 10
card_load || { tap_diag "cannot load ts-can1-sim + ts-can1"; exit 1; }
up_and_listen || { tap_diag "cannot bring the interface up"; exit 1; }
tap_ok "interface $IF up with a listener, a frame round-trips" round_trip 101
nirq=$(provider_irqs)
tap_ok "the provider mapped its PC/104 interrupts ($nirq)" test "$nirq" -ge 3

# The provider goes first, with ts-can1 bound and its interrupt requested.
tap_ok "unbinding the bus provider's driver succeeds" sh -c "echo ts-can1-sim >$SIMDRV/unbind"
tap_ok "the ts-can1 device went with it" test ! -e "$DEV"
tap_ok "and its interface" test -z "$(can_iface)"
tap_is "the provider's interrupt mappings are disposed of" "$(provider_irqs)" 0
# Then the CAN device: there is none left to unbind.
tap_ok "unbinding ts-can1 afterwards finds no device" sh -c "! echo ts-can1 >$CANDRV/unbind 2>/dev/null"
kill "$CAND" 2>/dev/null
wait "$CAND" 2>/dev/null
CAND=

tap_ok "binding the provider again" sh -c "echo ts-can1-sim >$SIMDRV/bind"
wait_until 20 driver_bound
up_and_listen && round_trip 102
tap_ok "ts-can1 binds to the new bus device and a frame round-trips" test $? = 0

# rmmod order: the provider's module first, under the running interface.
tap_ok "removing the provider's module, then ts-can1" \
	sh -c 'modprobe -r ts-can1-sim && test ! -e /sys/bus/platform/devices/ts-can1 && modprobe -r ts-can1'
tap_finish
