#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# The PC/104 I/O regmap's debugfs dump has no side effects and reads only the
# card's own addresses: the SJA1000 registers that clear when read (IR,
# ALC, ECC) are precious, and ports outside the four PLD blocks and the
# eight SJA1000 windows (other PC/104 cards) are not readable at all. The
# same for the FPGA regmap of the bus: only the PC/104 pin function rows.
. "$(dirname "$0")/lib.sh"
tap_require_module ts-can1
trap cleanup_all EXIT

tap_plan 6
card_load || { tap_diag "cannot load ts-can1-sim + ts-can1"; exit 1; }
IOMAP=$(ls -d /sys/kernel/debug/regmap/*pc104-io 2>/dev/null | head -1)
FPGAMAP=$(ls -d /sys/kernel/debug/regmap/*ts-can1-sim*fpga 2>/dev/null | head -1)
dump=$(cat "$IOMAP/registers" 2>/dev/null)
tap_ok "the PC/104 I/O regmap dump can be read ($IOMAP)" test -n "$dump"
ports=$(printf '%s\n' "$dump" | cut -d: -f1)

# owned PORT: in a PLD block (0x150..0x16f) or an SJA1000 window
owned() {
	local p=$(($1)) w
	[ "$p" -ge $((0x150)) ] && [ "$p" -lt $((0x170)) ] && return 0
	for w in 0x100 0x120 0x180 0x1a0 0x200 0x240 0x280 0x320; do
		[ "$p" -ge $((w)) ] && [ "$p" -lt $((w + 32)) ] && return 0
	done
	return 1
}
foreign=""
precious=""
for p in $ports; do
	owned "0x$p" || foreign="$foreign $p"
	for w in 0x100 0x120 0x180 0x1a0 0x200 0x240 0x280 0x320; do
		for r in 3 11 12; do
			[ $((0x$p)) -eq $((w + r)) ] && precious="$precious $p"
		done
	done
done
tap_is "no port outside the PLD blocks and SJA1000 windows is read" "${foreign:-none}" none
tap_is "no clear-on-read SJA1000 register (IR, ALC, ECC) is read" "${precious:-none}" none
tap_ok "the PLD ID registers are in the dump" sh -c "printf '%s\n' \"\$0\" | grep -q '^150: f6'" "$dump"

fdump=$(cat "$FPGAMAP/registers" 2>/dev/null)
tap_ok "the bus's FPGA regmap dump can be read ($FPGAMAP)" test -n "$fdump"
others=$(printf '%s\n' "$fdump" | cut -d: -f1 | while read -r r; do
	[ $((0x$r)) -ge $((0x30)) ] && [ $((0x$r)) -le $((0x3e)) ] || echo "$r"; done | wc -l)
tap_is "it lists only the PC/104 pin function rows (0x30..0x3e)" "$others" 0
tap_finish
