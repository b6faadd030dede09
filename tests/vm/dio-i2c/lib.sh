# SPDX-License-Identifier: GPL-2.0
# Helpers of the dio-i2c VM suite (sourced, not a test program): the
# simulated FPGA with its DIO header, the bit-banged adapter on two of its
# pins and the simulated MAX6615 behind it (debugfs of the simulator).

. "$VMTEST_REPO/tests/lib/tap.sh"
. "$VMTEST_REPO/tests/lib/wait.sh"

SIMFS=/sys/kernel/debug/ts7800-sim
CHIPFS=$SIMFS/max6615
DIOFS=$SIMFS/dio
DEBUGFS_MOUNTED_BY_US=0
I2C_DEV_LOADED_BY_US=0
DIO_CHIP=
I2C_BUS=
CHIP_ADDR=0x18

# Header pins of the simulator's defaults (ts7800-sim-dio.c) as line offsets.
SCL_OFF=0	# DIO_1
SDA_OFF=2	# DIO_3
PAUSE_OFF=4	# DIO_5
FANFAIL_OFF=6	# DIO_7

debugfs_mount() {
	[ -d /sys/kernel/debug/tracing ] || [ -n "$(ls -A /sys/kernel/debug 2>/dev/null)" ] && return 0
	mount -t debugfs none /sys/kernel/debug && DEBUGFS_MOUNTED_BY_US=1
}

# sim_load [PARAMS]: the DIO driver and the simulated FPGA; sets DIO_CHIP.
sim_load() {
	debugfs_mount || return 1
	modprobe ts7800_dio || return 1
	modprobe ts7800_sim "$@" || return 1
	wait_until 10 _dio_chip
}
_dio_chip() {	# sets DIO_CHIP once gpiolib lists the DIO header
	DIO_CHIP=$(gpiodetect 2>/dev/null | awk '/\[ts7800-dio\]/ { print $1 }')
	[ -n "$DIO_CHIP" ]
}

# adapter_load [PARAMS]: the bit-banged adapter and i2c-dev; sets I2C_BUS.
adapter_load() {
	modprobe ts7800_dio_i2c "$@" || return 1
	if ! grep -q '^i2c_dev ' /proc/modules; then
		modprobe i2c-dev || return 1
		I2C_DEV_LOADED_BY_US=1
	fi
	wait_until 10 _i2c_bus
}
_i2c_bus() {	# sets I2C_BUS once the adapter and its i2c-dev node are there
	local a
	for a in /sys/bus/i2c/devices/i2c-*; do
		grep -q '^TS-7800 DIO I2C' "$a/name" 2>/dev/null && I2C_BUS=${a##*/i2c-}
	done
	[ -n "$I2C_BUS" ] && [ -c "/dev/i2c-$I2C_BUS" ]
}

# chip_set FILE VALUE: a knob of the simulated MAX6615
chip_set() { echo "$2" >"$CHIPFS/$1"; }
# model_reg REG: the register as the model holds it (hex, no 0x)
model_reg() {
	awk -v r=$(($1)) 'NR == int(r / 16) + 1 { print $(r % 16 + 1) }' "$CHIPFS/regs"
}
# dio_levels: the DIO input register as the simulator computes it
dio_levels() { cat "$DIOFS/levels"; }
# pin_level OFFSET: 0/1 from the simulator's view of the pins
pin_level() { echo $(( ($(dio_levels) >> $1) & 1 )); }

cleanup_all() {
	modprobe -r max6615 2>/dev/null
	modprobe -r ts7800_dio_i2c 2>/dev/null
	[ "$I2C_DEV_LOADED_BY_US" = 1 ] && modprobe -r i2c-dev 2>/dev/null
	modprobe -r ts7800_sim 2>/dev/null
	modprobe -r ts7800_dio ts_uart ts7800_fpga 2>/dev/null
	[ "$DEBUGFS_MOUNTED_BY_US" = 1 ] && umount /sys/kernel/debug
	return 0
}
