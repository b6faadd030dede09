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
#     their ratios to the i2c-stub run.
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
# cpu_ticks PID: user + sys clock ticks of the finished children of PID
cpu_ticks() { awk '{ print $16 + $17 }' "/proc/$1/stat"; }

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
# the stub gets the chip's identity so max6615 binds there too
i2cset -y "$STUB" 0x18 0xfd 0x01; i2cset -y "$STUB" 0x18 0xfe 0x68; i2cset -y "$STUB" 0x18 0xff 0x4d
i2cset -y "$STUB" 0x18 0x1a 0xff; i2cset -y "$STUB" 0x18 0x1b 0xff

# byte_read_us BUS: microseconds per SMBus byte read, 256 in one process
byte_read_us() {
	t0=$(now_ns)
	i2cdump -y "$1" 0x18 b >/dev/null
	echo $(( ($(now_ns) - t0) / 256 / 1000 ))
}
dio_us=$(byte_read_us "$DIO")
stub_us=$(byte_read_us "$STUB")
echo "SMBus byte read: DIO bit-bang $dio_us us, i2c-stub $stub_us us"
awk -v d="$dio_us" -v s="$stub_us" 'BEGIN {
	printf "  ratio DIO / nominal 100 kHz bus time (390 us): %.2f\n", d / 390
	printf "  ratio DIO / i2c-stub: %.1f\n", d / (s ? s : 1) }'

modprobe max6615
hz=$(getconf CLK_TCK)
DCHIP=max6615-i2c-$DIO-18 SCHIP=max6615-i2c-$STUB-18
sensors -c "$CONF" "$DCHIP" >/dev/null	# fill the driver's register caches
sensors -c "$CONF" "$SCHIP" >/dev/null
# Alternate the two buses run by run, so that the noise of this shared
# machine hits both alike. CPU = user + sys ticks of the reaped sensors.
me=$BASHPID
dwall=0 dcpu=0 swall=0 scpu=0
starts0=$(awk '/^starts/ { print $2 }' /sys/kernel/debug/ts7800-sim/max6615/bus)
for _ in $(seq "$RUNS"); do
	c0=$(cpu_ticks "$me") t0=$(now_ns)
	sensors -c "$CONF" "$DCHIP" >/dev/null
	t1=$(now_ns) c1=$(cpu_ticks "$me")
	sensors -c "$CONF" "$SCHIP" >/dev/null
	t2=$(now_ns) c2=$(cpu_ticks "$me")
	dwall=$((dwall + t1 - t0)) dcpu=$((dcpu + c1 - c0))
	swall=$((swall + t2 - t1)) scpu=$((scpu + c2 - c1))
done
starts1=$(awk '/^starts/ { print $2 }' /sys/kernel/debug/ts7800-sim/max6615/bus)
# a byte-data read is a START and a repeated START
xfers=$(( (starts1 - starts0) / 2 / RUNS ))
dw=$((dwall / RUNS / 1000000)) sw=$((swall / RUNS / 1000000))
dc=$((dcpu * 1000 / hz / RUNS)) sc=$((scpu * 1000 / hz / RUNS))
echo "one sensors run (cache warm, $RUNS runs each, alternating): DIO wall $dw ms CPU $dc ms; i2c-stub wall $sw ms CPU $sc ms; $xfers SMBus reads per run"
awk -v dw="$dw" -v dc="$dc" -v sw="$sw" -v sc="$sc" -v x="$xfers" -v us="$dio_us" 'BEGIN {
	printf "  ratio CPU / wall on the DIO bus: %.2f (bit-banging busy-waits)\n", dc / (dw ? dw : 1)
	printf "  ratio DIO / i2c-stub: wall %.2f, CPU %.2f\n", dw / (sw ? sw : 1), dc / (sc ? sc : 1)
	printf "  bus time (reads x byte-read latency) / DIO sensors wall: %.2f\n", x * us / 1000 / (dw ? dw : 1) }'
