#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Automatic mode of the simulated MAX6615, programmed and read over the
# bit-banged bus: the duty follows the programmed curve as the temperature
# rises and falls (tabulated), hysteresis keeps the fan on below the start
# temperature, and the instantaneous duty ramps at the programmed rate.
#
# Curve (fan 1 follows temp 1): start 30 C, start duty 48/240, max duty
# 192/240, step 5 -> 10/240 per 1 C step, hysteresis 5 C, ramp instant.
# The expectation below is the documented rule (docs/dio-i2c.md), computed
# here independently of the simulator.
. "$(dirname "$0")/lib.sh"
trap cleanup_all EXIT

tap_plan 6
sim_load || { tap_diag "cannot load ts7800_dio + ts7800_sim"; exit 1; }
adapter_load || { tap_diag "cannot load ts7800_dio_i2c"; exit 1; }
set_reg() { i2cset -y "$I2C_BUS" "$CHIP_ADDR" "$1" "$2"; }
get_reg() { printf '%d' "$(i2cget -y "$I2C_BUS" "$CHIP_ADDR" "$1")"; }

set_reg 0x12 0x00	# ramp: instant
set_reg 0x0f 30		# fan-start temperature 1
set_reg 0x07 48		# start duty 1
set_reg 0x09 192	# max duty 1
set_reg 0x13 0x50	# duty step fan 1 = 5
set_reg 0x11 0x20	# fan 1 follows temp 1; 5 C hysteresis, 1 C step

# expected T ON: the rule of docs/dio-i2c.md (ON = fan running before)
expected() {
	t=$1 on=$2
	if [ "$t" -ge 30 ] || { [ "$on" = 1 ] && [ $((t + 5)) -ge 30 ]; }; then
		d=$((48 + (t > 30 ? t - 30 : 0) * 10))
		[ $d -gt 192 ] && d=192
		echo $d
	else
		echo 0
	fi
}

table="" want="" on=0
for t in 20 26 29 30 31 33 36 40 44 45 50 44 36 30 29 27 25 24 20; do
	chip_set temp1 $((t * 1000))
	got=$(get_reg 0x0d)
	exp=$(expected $t $on)
	[ "$exp" -gt 0 ] && on=1 || on=0
	table="$table$t:$got "
	want="$want$t:$exp "
	tap_diag "$(printf 'temp %3d C  target %3d  duty %3d/240  expected %3d' "$t" "$(get_reg 0x0b)" "$got" "$exp")"
done
tap_is "duty follows the curve up and down (temp:duty)" "$table" "$want"

# MIN_DUTY (CONFIG bit 2): below the start temperature the start duty holds.
set_reg 0x02 0x1c
chip_set temp1 15000
tap_is "with MIN_DUTY the duty below the start temperature is the start duty" "$(get_reg 0x0d)" 48
set_reg 0x02 0x18

# Ramp: code 1 = 62.5 ms per 2/240 step; 0 -> 192 is 96 steps (6 s).
chip_set temp1 20000
set_reg 0x12 0x20
chip_set temp1 60000
t0=$(date +%s%N)
samples=""
prev=0 mono=1
while :; do
	d=$(get_reg 0x0d)
	samples="$samples $d"
	[ "$d" -lt "$prev" ] && mono=0
	prev=$d
	[ "$d" -ge 192 ] && break
	[ $(( ($(date +%s%N) - t0) / 1000000 )) -gt 20000 ] && break
	sleep 0.2
done
ms=$(( ($(date +%s%N) - t0) / 1000000 ))
# Between 0 and 192: the ramp's own steps. How many samples land there
# depends on how long one bit-banged read takes (0.1 s on a quiet x86_64
# guest, 2 s on the debug kernel under load), so one is the limit: the
# 6 s ramp leaves room for reads of up to 3 s.
between=0
for d in $samples; do
	[ "$d" -gt 0 ] && [ "$d" -lt 192 ] && between=$((between + 1))
done
tap_diag "ramp samples:$samples ($between in between, reached after $ms ms)"
tap_is "the ramp reaches the target" "$prev" 192
tap_ok "it rises step by step, never down, through values in between" \
	sh -c "[ $mono = 1 ] && [ $between -ge 1 ]"
tap_ok "not faster than the programmed rate (96 steps of 62.5 ms)" \
	sh -c "[ $ms -ge 5500 ]"
tap_is "the target register holds the curve value meanwhile" "$(get_reg 0x0b)" 192

tap_finish
