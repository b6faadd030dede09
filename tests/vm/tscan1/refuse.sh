#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# What is not a working TS-CAN1 is refused cleanly: a wrong PLD ID, an empty
# bus, a card without an interrupt jumper and a card whose SJA1000 does not
# answer. The probe fails with -ENODEV (the device stays unbound, no
# interface), the reason is in dmesg, the PLD window is closed again and the
# driver unloads (the harness checks dmesg for warnings; the debug lane's
# kmemleak for leaks).
. "$(dirname "$0")/lib.sh"
tap_require_module ts-can1
trap cleanup_all EXIT

tap_plan 15

# refused CASE SIM-PARAMS...: load, check unbound and no interface, unload
refused() {
	_case=$1; shift
	card_load "$@" || { tap_diag "cannot load for $_case"; return 1; }
	tap_ok "$_case: device left unbound, no CAN interface" \
		sh -c "! test -e $DEV/driver && test -z \"\$(ls $DEV/net 2>/dev/null)\""
}

refused "wrong PLD ID" id1=0x12
tap_ok "wrong PLD ID: dmesg names the ID read" dmesg_has "not a TS-CAN1 at 0x150: ID 0x12 0xb9"
tap_ok "wrong PLD ID: probe ends with 'no TS-CAN1 card found'" dmesg_has "ts-can1 ts-can1: no TS-CAN1 card found"
tap_is "wrong PLD ID: SJA1000 window never opened" "$(sim_field mode)" 0x00
tap_ok "wrong PLD ID: ts-can1 and the simulator unload" card_unload

refused "second ID byte wrong" id2=0xb8
tap_ok "second ID byte wrong: refused by ID" dmesg_has "not a TS-CAN1 at 0x150: ID 0xf6 0xb8"
card_unload

refused "empty bus" present=0
tap_ok "empty bus: nothing but 'no TS-CAN1 card found' (0xff is no card)" \
	sh -c "dmesg | tail -n +$((DMESG_MARK + 1)) | grep -q 'no TS-CAN1 card found' && ! dmesg | tail -n +$((DMESG_MARK + 1)) | grep -q 'not a TS-CAN1'"
card_unload

refused "no IRQ jumper" jumpers=0
tap_ok "no IRQ jumper: dmesg asks for JP4/JP5" dmesg_has "TS-CAN1 0 at 0x150: no interrupt jumpered \(set JP4 and/or JP5\)"
card_unload

refused "SJA1000 not answering" sja_absent=1
tap_ok "SJA1000 not answering: every window tried, error logged" dmesg_has "TS-CAN1 0: no free SJA1000 window answers"
tap_is "SJA1000 not answering: PLD window closed again" "$(sim_field mode)" 0x00
tap_ok "SJA1000 not answering: unloads" card_unload
tap_finish
