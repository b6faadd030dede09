#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# bench/dio-i2c.sh: cost of the bit-banged SMBus on the simulated TS-7800
# DIO header, against i2c-stub (no bus at all) as the reference measured in
# the same run. Needs the project's modules, so it runs inside the VM:
# `make bench TEST=dio-i2c` (tests/vm/dio-i2c/bench.sh calls this).
# Prints (no pass/fail on timing):
#   - SMBus byte-read latency: 256 reads in one i2cdump, per read, and the
#     ratio to the nominal 100 kHz bus time of one byte-data read (39 SCL
#     periods = 390 us) and to the same read on i2c-stub;
#   - one `sensors` run of the MAX6615: wall time and CPU time (user + sys,
#     the bit-banging busy-waits in the kernel on the caller's behalf), and
#     their ratios to the i2c-stub run, and the share of the bus in it.
# Wall and CPU of a sensors run come from GNU time (10 ms resolution).
#   DIO_BENCH_RUNS  sensors runs averaged per bus (default 10)
set -euo pipefail
RUNS=${DIO_BENCH_RUNS:-10}
CONF=$(cd "$(dirname "$0")/.." && pwd)/i2c-max6615/advee-max6615.conf
i2cdev_ours=0 dbgfs_ours=0
cleanup() {
	modprobe -r max6615 2>/dev/null || true
	modprobe -r i2c-stub ts7800_dio_i2c 2>/dev/null || true
	[ $i2cdev_ours = 1 ] && { modprobe -r i2c-dev 2>/dev/null || true; }
	modprobe -r ts7800_sim 2>/dev/null || true
	modprobe -r ts7800_dio ts_uart ts7800_fpga 2>/dev/null || true
	[ $dbgfs_ours = 1 ] && { umount /sys/kernel/debug || true; }
	return 0	# an EXIT trap's status would become the script's
}
trap cleanup EXIT

now_ns() { date +%s%N; }
# bus_of NAME-PREFIX: number of the i2c adapter whose name starts so
bus_of() {
	for a in /sys/bus/i2c/devices/i2c-*; do
		grep -q "^$1" "$a/name" 2>/dev/null && { echo "${a##*/i2c-}"; return; }
	done
}

[ -n "$(ls -A /sys/kernel/debug 2>/dev/null)" ] || { mount -t debugfs none /sys/kernel/debug; dbgfs_ours=1; }
grep -q '^i2c_dev ' /proc/modules || { modprobe i2c-dev; i2cdev_ours=1; }
modprobe ts7800_dio
modprobe ts7800_sim
modprobe ts7800_dio_i2c
modprobe i2c-stub chip_addr=0x18
for _ in $(seq 100); do
	DIO=$(bus_of "TS-7800 DIO I2C"); STUB=$(bus_of "SMBus stub")
	[ -n "$DIO" ] && [ -n "$STUB" ] && [ -c /dev/i2c-$DIO ] && [ -c /dev/i2c-$STUB ] && break
	sleep 0.1
done
# The stub gets the simulated chip's register image (00h-1Fh, FDh-FFh), so
# that max6615 binds there too and `sensors` shows the same on both buses.
SIMCHIP=/sys/kernel/debug/ts7800-sim/max6615
echo 1500 >"$SIMCHIP/fan1_rpm"; echo 900 >"$SIMCHIP/fan2_rpm"
for r in $(seq 0 31) 253 254 255; do
	v=$(awk -v r="$r" 'NR == int(r / 16) + 1 { print $(r % 16 + 1) }' "$SIMCHIP/regs")
	i2cset -y "$STUB" 0x18 "$r" "0x$v"
done

# byte_read_us BUS: microseconds per SMBus byte read, 256 in one process
byte_read_us() {
	t0=$(now_ns)
	i2cdump -y "$1" 0x18 b >/dev/null
	echo $(( ($(now_ns) - t0) / 256 / 1000 ))
}
# The fastest of 5 alternating runs per bus: the noise of this shared
# machine (other VMs) only ever adds time.
min() { [ -z "$1" ] || [ "$2" -lt "$1" ] && echo "$2" || echo "$1"; }
dio_us= stub_us=
for _ in 1 2 3 4 5; do
	dio_us=$(min "$dio_us" "$(byte_read_us "$DIO")")
	stub_us=$(min "$stub_us" "$(byte_read_us "$STUB")")
done
echo "SMBus byte read (fastest of 5 x 256): DIO bit-bang $dio_us us, i2c-stub $stub_us us"
awk -v d="$dio_us" -v s="$stub_us" 'BEGIN {
	printf "  ratio DIO / nominal 100 kHz bus time (390 us): %.2f\n", d / 390
	printf "  ratio DIO / i2c-stub: %.2f\n", d / (s ? s : 1) }'

modprobe max6615
DCHIP=max6615-i2c-$DIO-18 SCHIP=max6615-i2c-$STUB-18
sensors -c "$CONF" "$DCHIP" >/dev/null	# fill the driver's register caches
sensors -c "$CONF" "$SCHIP" >/dev/null
# Alternate the two buses run by run, so that the noise of this shared
# machine hits both alike; GNU time reports each sensors process's own wall
# and CPU (user + sys, which includes the kernel's bit-banging on its behalf).
# run_cost CHIP: "wall_ms cpu_ms" of one sensors run
run_cost() {
	/usr/bin/time -f '%e %U %S' -o "$tfile" sensors -c "$CONF" "$1" >/dev/null
	awk '{ printf "%d %d\n", $1 * 1000, ($2 + $3) * 1000 }' "$tfile"
}
tfile=$(mktemp)
dwall= swall= dcpu=0 scpu=0 dsum=0 ssum=0
starts0=$(awk '/^starts/ { print $2 }' $SIMCHIP/bus)
for _ in $(seq "$RUNS"); do
	read -r w c <<<"$(run_cost "$DCHIP")"
	dwall=$(min "$dwall" "$w") dsum=$((dsum + w)) dcpu=$((dcpu + c))
	read -r w c <<<"$(run_cost "$SCHIP")"
	swall=$(min "$swall" "$w") ssum=$((ssum + w)) scpu=$((scpu + c))
done
rm -f "$tfile"
starts1=$(awk '/^starts/ { print $2 }' $SIMCHIP/bus)
# a byte-data read is a START and a repeated START
xfers=$(( (starts1 - starts0) / 2 / RUNS ))
dw=$dwall sw=$swall dc=$((dcpu / RUNS)) sc=$((scpu / RUNS))
dm=$((dsum / RUNS)) sm=$((ssum / RUNS))
echo "one sensors run (cache warm, $RUNS runs each, alternating): DIO wall fastest $dw ms mean $dm ms, CPU mean $dc ms; i2c-stub wall fastest $sw ms mean $sm ms, CPU mean $sc ms; $xfers SMBus reads per run"
awk -v dw="$dw" -v dc="$dc" -v sw="$sw" -v sc="$sc" -v x="$xfers" -v us="$dio_us" -v dm="$dm" 'BEGIN {
	printf "  ratio CPU / wall (means) on the DIO bus: %.2f\n", dc / (dm ? dm : 1)
	printf "  ratio DIO / i2c-stub: wall %.2f, CPU %.2f\n", dw / (sw ? sw : 1), dc / (sc ? sc : 1)
	printf "  bus time (reads x byte-read latency) / DIO sensors wall: %.2f\n", x * us / 1000 / (dw ? dw : 1) }'
