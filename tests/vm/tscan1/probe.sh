#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# The driver finds the card on the simulated PC/104 bus, reports its settings,
# programs the PLD and the SJA1000 as the board needs (rows A/B in bus
# function, window enabled, 8 MHz clock, CDR/OCR), and undoes it on unload;
# other jumper settings are found too.
. "$(dirname "$0")/lib.sh"
tap_require_module ts-can1
trap cleanup_all EXIT

tap_plan 17
card_load || { tap_diag "cannot load ts-can1-sim + ts-can1"; exit 1; }
IF=$(can_iface)
tap_ok "driver bound, CAN interface created ($IF)" test -n "$IF"
tap_ok "dmesg reports card 0, PLD 0x150, SJA1000 window 0x100, PC/104 IRQ6" \
	dmesg_has "TS-CAN1 0 \(PLD version 3\) at 0x150, SJA1000 at 0x100, PC/104 IRQ6 \(irq [0-9]+\), 8000000 Hz"
tap_is "PC/104 rows A/B switched to bus function" "$(sim_field rows) $(awk '/^rows/ { print $3 }' "$SIMSTATE")" \
	"0x55555555 0x55555555"
tap_is "PLD MODE: SJA1000 window 0 enabled" "$(sim_field mode)" 0x40
tap_is "PLD LED off after the probe" "$(sim_field led)" 0x00
tap_is "CDR: PeliCAN, comparator bypass, CLKOUT off" "$(sim_field cdr)" 0xc8
tap_is "OCR: TX0 push-pull, normal output mode" "$(sim_field ocr)" 0x1a
tap_is "SJA1000 left in reset mode while down" "$(sim_field mod)" 0x01
details=$(ip -details link show "$IF")
tap_ok "ip -details shows an 8 MHz CAN clock" grep -q "clock 8000000" <<<"$details"
tap_ok "sja1000 bit-timing constants" grep -q "sja1000: tseg1 1..16 tseg2 1..8 sjw 1..4 brp 1..64" <<<"$details"
modprobe -r ts-can1
tap_ok "interface gone after unload" test -z "$(can_iface)"
tap_is "PLD MODE 0 after unload: window closed" "$(sim_field mode)" 0x00
card_unload

# Card id 2 (PLD at 0x150 + 8 * 2 = 0x160), both jumpers: IRQ5.
card_load card_id=2 jumpers=0x30 || { tap_diag "cannot reload with card_id=2"; exit 1; }
tap_ok "card id 2 found at 0x160 on PC/104 IRQ5" \
	dmesg_has "TS-CAN1 2 \(PLD version 3\) at 0x160, SJA1000 at 0x100, PC/104 IRQ5"
tap_is "interface's dev_port is the card id" "$(cat "/sys/class/net/$(can_iface)/dev_port" 2>&1)" 2
card_unload
card_load jumpers=0x20 || { tap_diag "cannot reload with JP5"; exit 1; }
tap_ok "JP5 alone selects PC/104 IRQ7" dmesg_has "at 0x150, SJA1000 at 0x100, PC/104 IRQ7"
card_unload

# pld_ids restricts the scan: card 0 is not looked for.
debugfs_mount; dmesg_mark
modprobe ts-can1-sim && modprobe ts-can1 pld_ids=0xe
tap_ok "pld_ids=0xe skips card 0: no interface" test -z "$(can_iface)"
tap_ok "... and says so" dmesg_has "no TS-CAN1 card found"
tap_finish
