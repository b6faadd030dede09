#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# The DIO header as a gpiochip, seen through libgpiod's tools: names from
# the header pins, reserved pins refused, open-drain outputs (0 pulls low, 1
# releases), inputs following outside devices, polled edge events.
. "$(dirname "$0")/lib.sh"
trap cleanup_all EXIT

tap_plan 16
sim_load || { tap_diag "cannot load ts7800_dio + ts7800_sim"; exit 1; }
tap_ok "gpiodetect lists the DIO chip with 16 lines" \
	sh -c "gpiodetect | grep -q '\[ts7800-dio\] (16 lines)'"

names=$(gpioinfo "$DIO_CHIP" | sed -n 's/.*line *[0-9]*: *"\([^"]*\)".*/\1/p' | tr '\n' ' ')
tap_is "line names are the header pins" "$names" \
	"DIO_1 DIO_2 DIO_3 DIO_4 DIO_5 DIO_6 DIO_7 DIO_8 DIO_9 DIO_10 DIO_11 DIO_12 DIO_13 DIO_14 DIO_15 DIO_16 "

refused=""
for pin in 2 6 10 12 14 16; do
	gpioget "$DIO_CHIP" $((pin - 1)) >/dev/null 2>&1 || refused="$refused $pin"
done
tap_is "power and SPI pins cannot be requested" "$refused" " 2 6 10 12 14 16"
free=""
for pin in 1 3 4 5 7 8 9 11 13 15; do
	gpioget "$DIO_CHIP" $((pin - 1)) >/dev/null 2>&1 && free="$free $pin"
done
tap_is "the other pins can" "$free" " 1 3 4 5 7 8 9 11 13 15"

# Input: released pins read their pull-up, an outside device pulls low.
tap_is "released DIO_4 reads 1" "$(gpioget "$DIO_CHIP" 3)" 1
echo 0x0008 >"$DIOFS/ext_low"
tap_is "DIO_4 pulled low outside reads 0" "$(gpioget "$DIO_CHIP" 3)" 0
echo 0 >"$DIOFS/ext_low"
tap_is "and 1 again when let go" "$(gpioget "$DIO_CHIP" 3)" 1

# Output: 0 pulls the pin low (the value stays latched after gpioset exits,
# as with any gpiochip), requesting it as an input releases it again.
gpioset "$DIO_CHIP" 7=0
tap_is "gpioset DIO_8=0 pulls the pin low" "$(pin_level 7)" 0
tap_ok "gpioinfo shows DIO_8 as an output" sh -c "gpioinfo $DIO_CHIP | grep '\"DIO_8\"' | grep -q output"
gpioset "$DIO_CHIP" 7=1
tap_is "gpioset DIO_8=1 releases it to the pull-up" "$(pin_level 7)" 1
gpioset "$DIO_CHIP" 7=0
tap_is "gpioget DIO_8 (input) releases it and reads 1" "$(gpioget "$DIO_CHIP" 7)" 1

# line_held_by LINE CONSUMER: gpioinfo names CONSUMER as the holder of LINE
line_held_by() { gpioinfo "$DIO_CHIP" | grep -q "\"$1\".*\"$2\""; }

# Held output: a line set by a running gpioset, its consumer visible.
gpioset --mode=signal "$DIO_CHIP" 8=0 &
setpid=$!
wait_until 5 line_held_by DIO_9 gpioset
tap_ok "gpioinfo names the consumer of a held line" sh -c "gpioinfo $DIO_CHIP | grep -q '\"DIO_9\".*\"gpioset\".*output'"
tap_is "while held, DIO_9 is low" "$(pin_level 8)" 0
kill "$setpid"; wait "$setpid" 2>/dev/null

# Edge events: the PAUSE input asserted then released through debugfs.
out=$VMTEST_SCRATCH/gpiomon.out
timeout 20 gpiomon --num-events=2 --format='%o %e' "$DIO_CHIP" $PAUSE_OFF >"$out" &
monpid=$!
wait_until 5 line_held_by DIO_5 gpiomon
sleep 0.2
echo 1 >"$DIOFS/pause"
sleep 0.3
echo 0 >"$DIOFS/pause"
wait "$monpid"; monrc=$?
tap_is "gpiomon exits after two events" "$monrc" 0
tap_is "PAUSE asserted then released: a falling then a rising edge on DIO_5" \
	"$(tr '\n' ' ' <"$out")" "$PAUSE_OFF 0 $PAUSE_OFF 1 "

# Only the requested edge, on the right line.
timeout 20 gpiomon --num-events=1 --rising-edge --format='%o %e' "$DIO_CHIP" $FANFAIL_OFF >"$out" &
monpid=$!
wait_until 5 line_held_by DIO_7 gpiomon
sleep 0.2
echo 1 >"$DIOFS/pause"		# another line: no event
echo 1 >"$DIOFS/fan_fail"	# falling: filtered out
sleep 0.3
echo 0 >"$DIOFS/fan_fail"	# rising: the event
wait "$monpid"; monrc=$?
echo 0 >"$DIOFS/pause"
tap_is "a rising-edge monitor on DIO_7 sees only its rising edge" \
	"$monrc:$(tr '\n' ' ' <"$out")" "0:$FANFAIL_OFF 1 "

tap_finish
