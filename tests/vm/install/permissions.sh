#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Who may touch the buses (issue 26 item 4): with the installed udev rules
# applied by a running udevd on the simulated TS-7800, only root and group
# advee open the robot's devices. For each one a user outside group advee
# (nobody, with the groups Debian hands out for serial ports and I2C: dialout,
# i2c, plugdev) is refused with EACCES, and the service user advee (group
# advee, no other groups: what its units run as) is let in, so no point passes
# because the device is closed to everyone:
#   - every FPGA UART /dev/ttyTSU* (a bus, the power controller's link, the
#     spare ports), read and write
#   - /dev/rs485/a, b, power, read and write, also with n_rs485 attached
#   - the DIO header's /dev/gpiochipN (ts7800-dio), read and write
#   - /dev/i2c-N of the DIO I2C adapter (i2c-dev), read and write
#   - each writable hwmon attribute of the MAX6615 (the driver's 0644 files),
#     write; uevent stays root's
# and the MAX6615's values stay readable by anyone (temp1_input, every
# attribute). One point shows what the rules cannot close (docs/install.md,
# section 10): CAN has no device node, and any user sends frames on a CAN
# interface (CAN_RAW needs no capability), here nobody on a vcan. An open is tried with dd (O_NONBLOCK: a tty without
# CLOCAL would wait for carrier), and its error must be strerror(EACCES),
# "Permission denied" (not EPERM's "Operation not permitted", nor ENOENT).
. "$(dirname "$0")/lib.sh"
. "$VMTEST_REPO/tests/lib/candump.sh"
export LC_ALL=C
VCAN=vcanperm
I2C_DEV_LOADED_BY_US=0
UDEVD_PID=
LDATTACH_PIDS=()
cleanup() {
	local p c a
	for p in "${LDATTACH_PIDS[@]}"; do kill "$p" 2>/dev/null && wait "$p" 2>/dev/null; done
	[ -n "$CANDUMP_PID" ] && kill "$CANDUMP_PID" 2>/dev/null && wait "$CANDUMP_PID" 2>/dev/null
	ip link del dev "$VCAN" 2>/dev/null
	modprobe -r vcan can_raw can 2>/dev/null
	if [ -n "$UDEVD_PID" ]; then
		udevadm control --exit 2>/dev/null || kill "$UDEVD_PID" 2>/dev/null
		wait "$UDEVD_PID" 2>/dev/null
	fi
	for c in /sys/bus/i2c/devices/*-0018; do
		[ -e "$c" ] || continue
		a=${c##*/}; echo 0x18 >"/sys/bus/i2c/devices/i2c-${a%-0018}/delete_device" 2>/dev/null
	done
	modprobe -r n_rs485 2>/dev/null
	modprobe -r max6615 2>/dev/null
	modprobe -r ts7800_dio_i2c 2>/dev/null
	[ "$I2C_DEV_LOADED_BY_US" = 1 ] && modprobe -r i2c-dev 2>/dev/null
	modprobe -r ts7800_sim 2>/dev/null
	modprobe -r ts7800_dio ts_uart ts7800_fpga 2>/dev/null
	rm -rf /dev/rs485
	cleanup_mounts
}
trap cleanup EXIT

# Setup; a failure here ends the program before its first point (it fails).
setup_fail() { tap_diag "setup: $*"; [ -s "$VMTEST_SCRATCH/setup.log" ] && sed 's/^/#   /' "$VMTEST_SCRATCH/setup.log"; exit 1; }
stage_system >"$VMTEST_SCRATCH/setup.log" 2>&1 || setup_fail "staging install (system files)"
make_live >>"$VMTEST_SCRATCH/setup.log" 2>&1 || setup_fail "group advee and the rules in /run/udev/rules.d"
getent passwd advee >/dev/null || setup_fail "no user advee after systemd-sysusers"

# udevd, as on the robot: it applies GROUP/MODE to the nodes and runs the
# rules' RUN programs (udevadm test runs none). Nothing is triggered: it
# handles the events of the modules loaded below only.
pgrep -x systemd-udevd >/dev/null && setup_fail "a udevd is already running: this program starts its own"
/lib/systemd/systemd-udevd >"$VMTEST_SCRATCH/udevd.log" 2>&1 &
UDEVD_PID=$!
wait_until 30 udevadm control --ping >/dev/null 2>&1 || setup_fail "udevd did not answer within 30 s"
tap_diag "udevd $UDEVD_PID with the installed rules ($(ls /run/udev/rules.d | tr '\n' ' '))"

# The simulated TS-7800: UARTs, the DIO header, its I2C bus with the MAX6615
# model on it (udevd declares the chip by 62-advee-max6615.rules and loads
# max6615 by the client's modalias), i2c-dev for /dev/i2c-N.
for m in ts_uart ts7800_dio ts7800_sim ts7800_dio_i2c; do
	modprobe "$m" 2>>"$VMTEST_SCRATCH/setup.log" || setup_fail "modprobe $m"
done
if ! grep -q '^i2c_dev ' /proc/modules; then
	modprobe i2c-dev 2>>"$VMTEST_SCRATCH/setup.log" || setup_fail "modprobe i2c-dev"
	I2C_DEV_LOADED_BY_US=1
fi
hwmon_dir() {
	local h
	for h in /sys/class/hwmon/hwmon*; do
		[ "$(cat "$h/name" 2>/dev/null)" = max6615 ] && { HWMON=$(readlink -f "$h"); return 0; }
	done
	return 1
}
dio_gpiochip() {
	local c
	for c in /sys/bus/gpio/devices/gpiochip*; do
		[ "$(basename "$(readlink -f "$c/..")")" = ts7800-dio ] && { GPIOCHIP=/dev/${c##*/}; return 0; }
	done
	return 1
}
dio_i2c_dev() {
	local d
	for d in /sys/class/i2c-dev/i2c-*; do
		grep -q '^TS-7800 DIO I2C' "$d/name" 2>/dev/null && { I2CDEV=/dev/${d##*/}; return 0; }
	done
	return 1
}
wait_until 60 hwmon_dir || setup_fail "no max6615 hwmon device within 60 s (udevd: rule 62 and the modalias)"
wait_until 10 dio_gpiochip || setup_fail "no gpiochip of ts7800-dio"
wait_until 10 dio_i2c_dev || setup_fail "no i2c-dev node of the TS-7800 DIO I2C adapter"
wait_path /dev/rs485/power 30 || setup_fail "no /dev/rs485/power"
udevadm settle --timeout=60 || setup_fail "udevadm settle: events still queued after 60 s"
TTYS=()
for t in /sys/class/tty/ttyTSU*; do TTYS+=("/dev/${t##*/}"); done
tap_diag "devices: ${TTYS[*]} $GPIOCHIP $I2CDEV $HWMON"

# The MAX6615's attributes, by the driver's modes (as root): writable ones
# (owner write bit; uevent aside: the kernel's, not the chip's) and read-only.
CONTROL=() READONLY=()
for f in "$HWMON"/*; do
	[ -f "$f" ] && [ ! -L "$f" ] || continue
	[ "${f##*/}" = uevent ] && continue
	if [ -n "$(find "$f" -maxdepth 0 -perm -u+w)" ]; then CONTROL+=("$f"); else READONLY+=("$f"); fi
done
tap_diag "max6615: ${#CONTROL[@]} writable attributes, ${#READONLY[@]} read-only"
[ "${#CONTROL[@]}" -gt 0 ] && [ "${#READONLY[@]}" -gt 0 ] || setup_fail "no hwmon attributes found"

# The two users. nobody gets dialout, i2c, plugdev where they exist.
extra=
for g in dialout i2c plugdev; do getent group "$g" >/dev/null && extra=${extra:+$extra,}$g; done
OTHER=(--reuid=nobody --regid=nogroup "--groups=${extra:-nogroup}")
SERVICE=(--reuid=advee --regid=advee --clear-groups)
tap_diag "other user: nobody, groups nogroup,$extra; service user: advee, group advee only"

# try WHO r|w PATH: "ok", or the error of the open (strerror), as WHO.
try() {
	local -n who=$1
	local out args
	case $2 in
	r) args=(if="$3" of=/dev/null count=0 iflag=nonblock) ;;
	w) args=(if=/dev/null of="$3" count=0 oflag=nonblock "conv=notrunc,nocreat") ;;
	esac
	if out=$(setpriv "${who[@]}" -- dd status=none "${args[@]}" 2>&1); then
		echo ok
	else
		echo "${out##*: }"
	fi
}
# check_node PATH: one point: refused to the other user for read and write
# with EACCES, open to the service user for both.
EACCES="Permission denied"
check_node() {
	local desc=$1 path=$2
	tap_is "$desc: $path: nobody refused (EACCES) read and write, advee opens both [$(stat -L -c '%U:%G %a' "$path")]" \
		"nobody r=$(try OTHER r "$path") w=$(try OTHER w "$path"); advee r=$(try SERVICE r "$path") w=$(try SERVICE w "$path")" \
		"nobody r=$EACCES w=$EACCES; advee r=ok w=ok"
}
# check_attr PATH: one point: write refused to the other user with EACCES,
# write-open for the service user.
check_attr() {
	tap_is "max6615 ${1##*/}: nobody refused (EACCES) write, advee opens it for write [$(stat -c '%U:%G %a' "$1")]" \
		"nobody w=$(try OTHER w "$1"); advee w=$(try SERVICE w "$1")" \
		"nobody w=$EACCES; advee w=ok"
}

tap_plan $((${#TTYS[@]} + 3 + 2 + 2 + ${#CONTROL[@]} + 5 + 1 + 1))

# UARTs: ttyTSU0..2 are buses a, b and the power controller's link; the
# others are spare FPGA ports.
for t in "${TTYS[@]}"; do
	case ${t##*/} in
	ttyTSU0) d="UART (bus a)" ;; ttyTSU1) d="UART (bus b)" ;;
	ttyTSU2) d="UART (power controller)" ;; *) d="UART (spare)" ;;
	esac
	check_node "$d" "$t"
done
for b in a b power; do check_node "RS-485 bus $b" "/dev/rs485/$b"; done

# With the line discipline attached (as advee-rs485-ldattach@.service does).
for t in ttyTSU0 ttyTSU2; do
	ldattach -d 29 "/dev/$t" >"$VMTEST_SCRATCH/ldattach-$t.log" 2>&1 &
	LDATTACH_PIDS+=($!)
done
attached() { [ "$(cat /sys/module/n_rs485/refcnt 2>/dev/null || echo 0)" -ge 2 ]; }
wait_until 20 attached || tap_diag "n_rs485 not attached to both within 20 s (refcnt $(cat /sys/module/n_rs485/refcnt 2>/dev/null))"
check_node "n_rs485 attached, bus a" /dev/rs485/a
check_node "n_rs485 attached, power controller" /dev/rs485/power

check_node "DIO header gpiochip (ts7800-dio)" "$GPIOCHIP"
check_node "DIO I2C bus (i2c-dev)" "$I2CDEV"

for f in "${CONTROL[@]}"; do check_attr "$f"; done

tap_is "max6615 uevent (the kernel's file, not a control): root's alone, advee refused too" \
	"$(try SERVICE w "$HWMON/uevent") $(stat -c '%U:%G %a' "$HWMON/uevent")" "$EACCES root:root 644"
bad=
for f in "${READONLY[@]}"; do
	[ "$(stat -c '%U:%G %a' "$f")" = "root:root 444" ] || bad="$bad ${f##*/}($(stat -c '%U:%G %a' "$f"))"
done
tap_is "max6615: the ${#READONLY[@]} read-only attributes stay root:root 0444" "${bad:-none}" none
bad=
for f in "${CONTROL[@]}" "${READONLY[@]}"; do
	[ "$(try OTHER r "$f")" = ok ] || bad="$bad ${f##*/}"
done
tap_is "max6615: every attribute readable by nobody" "${bad:-none}" none
v=$(setpriv "${OTHER[@]}" -- cat "$HWMON/temp1_input" 2>&1)
tap_ok "nobody reads temp1_input: '$v'" test -n "$v" -a "$v" -eq "$v"
cur=$(cat "$HWMON/pwm1_enable")
tap_ok "advee writes pwm1_enable (its value, $cur) as driver_aux's fan policy does" \
	setpriv "${SERVICE[@]}" -- sh -c 'echo "$1" >"$2"' _ "$cur" "$HWMON/pwm1_enable"

# CAN: no node for udev to guard. nobody's frame (an NMT "stop all nodes")
# reaches the bus: documented in docs/install.md, not prevented.
can_frame_as_nobody() {
	modprobe vcan && ip link add dev "$VCAN" type vcan && ip link set "$VCAN" up || return 1
	candump_start "$VCAN" "$VMTEST_SCRATCH/candump.log" || return 1
	setpriv "${OTHER[@]}" -- cansend "$VCAN" 000#0200 || return 1
	candump_stop
	grep -q " 000#0200\$" "$VMTEST_SCRATCH/candump.log"
}
# The rules as udevd read and ran them: no complaint about an advee rules
# file, no RUN program that failed (its chgrp/chmod).
udevd_complaints() {
	grep -E 'advee-[a-z0-9-]*\.rules|Process .* failed|[Ff]ailed to' "$VMTEST_SCRATCH/udevd.log"
}
tap_is "udevd: no warning about the advee rules, no failed RUN ($(wc -l <"$VMTEST_SCRATCH/udevd.log") log lines)" \
	"$(udevd_complaints)" ""

tap_here "CAN (not closed by the install): nobody sends NMT stop-all (000#0200) on $VCAN, CAN_RAW needs no privilege" \
	can_frame_as_nobody
tap_finish
