#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Random sysfs writes to the DIO header's attributes (issue 26 item 2), with
# the values of tests/lib/sysfs-fuzz.sh (garbage, huge, negative, empty,
# longer than a page, partial writes) plus plausible ones:
# - the legacy GPIO attributes of the DIO gpiochip (CONFIG_GPIO_SYSFS: the
#   stock kernels; the debug kernel has no /sys/class/gpio, that point is a
#   listed skip there): export and unexport of the chip's lines and lines
#   around it, then direction, value, active_low and edge of the exported
#   ones. Clean: EINVAL, EBUSY (a reserved or taken line), EPERM (value of an
#   input), EIO (edge: the chip's lines have no interrupt, the gpio sysfs
#   code's own answer), ENOENT, ERANGE (a number beyond unsigned int);
# - the bit-banged I2C adapter's new_device and delete_device (random names
#   and addresses, garbage). Clean: EINVAL, EBUSY (an address in use),
#   ENOENT (no such client to delete).
# Every write succeeds or fails cleanly; afterwards the created clients and
# exported lines are removed, the lines read and drive the header and the
# bus reads the simulated MAX6615's identity.
# 1,000 writes per kind in make check, 10,000 with VMTEST_FUZZ_SCALE=full.
. "$(dirname "$0")/lib.sh"
. "$VMTEST_REPO/tests/lib/sysfs-fuzz.sh"

GPIOFS=/sys/class/gpio
# The DIO lines have names: an exported line's directory is its name
# (DIO_8), not gpioN. exported_lines sets LINES to the exported ones.
exported_lines() {
	local d
	LINES=()
	for d in "$GPIOFS"/*/value; do
		[ -e "$d" ] && LINES+=("${d%/value}")
	done
}
unexport_all() {
	local g
	for ((g = base; g < base + ngpio; g++)); do
		echo "$g" >"$GPIOFS/unexport"
	done 2>/dev/null
	exported_lines
	[ "${#LINES[@]}" = 0 ]
}
cleanup_fuzz() {
	local g
	if [ -n "${base:-}" ]; then
		unexport_all 2>/dev/null
	fi
	cleanup_all
}
trap cleanup_fuzz EXIT

n=$(fuzz_size 1000 10000) || exit 1
tap_plan 7
sim_load || { tap_diag "cannot load ts7800_dio + ts7800_sim"; exit 1; }
adapter_load || { tap_diag "cannot load ts7800_dio_i2c"; exit 1; }
A=/sys/bus/i2c/devices/i2c-$I2C_BUS
clients_before=$(cd /sys/bus/i2c/devices && echo "$I2C_BUS"-*)

# --- legacy GPIO attributes ------------------------------------------------------
base=
if [ -d "$GPIOFS" ]; then
	for c in "$GPIOFS"/gpiochip*; do
		[ "$(cat "$c/label")" = ts7800-dio ] && read -r base <"$c/base" && read -r ngpio <"$c/ngpio"
	done
fi
if [ -z "$base" ]; then
	tap_skip "gpio: legacy GPIO attributes fuzzed" "no $GPIOFS in this kernel (CONFIG_GPIO_SYSFS unset)"
	tap_skip "gpio: the lines work afterwards" "no $GPIOFS in this kernel (CONFIG_GPIO_SYSFS unset)"
else
	FZ_CLEAN_ERRNOS="Invalid argument|Numerical result out of range|Device or resource busy|Operation not permitted|Input/output error|No such file or directory"
	RANDOM=7800
	start=$SECONDS
	for ((k = 0; k < n; k++)); do
		case $((RANDOM % 6)) in
		0)	# export: the chip's lines, their neighbours, garbage
			f=$GPIOFS/export
			if ((RANDOM % 3)); then v=$((base - 2 + RANDOM % (ngpio + 4))); else fz_value; v=$FZ_VAL; fi ;;
		1)
			f=$GPIOFS/unexport
			if ((RANDOM % 3)); then v=$((base - 2 + RANDOM % (ngpio + 4))); else fz_value; v=$FZ_VAL; fi ;;
		*)	# an attribute of an exported line
			exported_lines
			if [ "${#LINES[@]}" = 0 ]; then
				f=$GPIOFS/export v=$((base + RANDOM % ngpio))
			else
				f=${LINES[RANDOM % ${#LINES[@]}]}
				case $((RANDOM % 4)) in
				0) f+=/direction; pl=(in out high low) ;;
				1) f+=/value; pl=(0 1) ;;
				2) f+=/active_low; pl=(0 1) ;;
				3) f+=/edge; pl=(none rising falling both) ;;
				esac
				if ((RANDOM % 2)); then v=${pl[RANDOM % ${#pl[@]}]}; else fz_value; v=$FZ_VAL; fi
			fi ;;
		esac
		fz_write "$f" "$v"
		fz_count "${f#"$GPIOFS"/}" "$v"
	done
	tap_diag "gpio: $n writes in $((SECONDS - start)) s: $FZ_OK accepted, $FZ_CLEAN refused cleanly, $FZ_BAD other"
	fz_report
	tap_ok "gpio: every write succeeded or failed cleanly, both seen" \
		test "$FZ_BAD" = 0 -a "$FZ_OK" -gt 0 -a "$FZ_CLEAN" -gt 0
	unexport_all
	exported_lines
	# DIO_8 (offset 7) through the character device after the fuzzing
	gpioset "$DIO_CHIP" 7=0
	l0=$(pin_level 7)
	gpioset "$DIO_CHIP" 7=1
	tap_is "gpio: every line unexported, DIO_8 drives low and releases" \
		"${#LINES[@]} $l0$(pin_level 7)" "0 01"
fi

# --- the adapter's new_device / delete_device ---------------------------------------
FZ_OK=0 FZ_CLEAN=0 FZ_BAD=0 FZ_BAD_LIST=
FZ_BY_RES=()
FZ_CLEAN_ERRNOS="Invalid argument|Device or resource busy|No such file or directory"
names=(dummy max6615 lm75 24c02 at24 "" x "$(printf '%060d' 1)")
RANDOM=7801
start=$SECONDS
for ((k = 0; k < n; k++)); do
	if ((RANDOM % 2)); then f=$A/new_device; else f=$A/delete_device; fi
	case $((RANDOM % 3)) in
	0) printf -v v '%s 0x%x' "${names[RANDOM % ${#names[@]}]}" $((RANDOM % 0x90)) ;;
	1) printf -v v '0x%x' $((RANDOM % 0x90)) ;;
	2) fz_value; v=$FZ_VAL ;;
	esac
	[ "${f##*/}" = new_device ] || [[ $v != *" "* ]] || v=${v##* }
	fz_write "$f" "$v"
	fz_count "${f##*/}" "$v"
done
tap_diag "i2c: $n writes in $((SECONDS - start)) s: $FZ_OK accepted, $FZ_CLEAN refused cleanly, $FZ_BAD other"
fz_report
tap_ok "i2c new_device/delete_device: every write succeeded or failed cleanly, both seen" \
	test "$FZ_BAD" = 0 -a "$FZ_OK" -gt 0 -a "$FZ_CLEAN" -gt 0
for c in /sys/bus/i2c/devices/"$I2C_BUS"-*; do
	[ -e "$c" ] || continue
	case " $clients_before " in *" ${c##*/} "*) continue ;; esac
	echo "0x${c##*-}" >"$A/delete_device"
done
tap_is "i2c: the created clients are gone" "$(cd /sys/bus/i2c/devices && echo "$I2C_BUS"-*)" "$clients_before"
tap_is "i2c: the bus still reads the MAX6615's identity (FD/FE/FF)" \
	"$(for r in 0xfd 0xfe 0xff; do i2cget -y "$I2C_BUS" "$CHIP_ADDR" $r; done | tr '\n' ' ')" "0x01 0x68 0x4d "
tap_is "the DIO chip still lists 16 lines" "$(gpiodetect | grep -c '\[ts7800-dio\] (16 lines)')" 1
tap_ok "the adapter is still bound" test -e "$A/name"
tap_finish
