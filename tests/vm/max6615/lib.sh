# SPDX-License-Identifier: GPL-2.0
# Helpers of the max6615 VM suite (sourced, not a test program): an i2c-stub
# chip preloaded with the register image of a BR-FAN1 board in the robot's
# computer box, and access to the hwmon attributes of the bound driver.
# i2c-stub is plain memory: status bits stay as written, POR resets nothing.

. "$VMTEST_REPO/tests/lib/tap.sh"
. "$VMTEST_REPO/tests/lib/wait.sh"

# The BR-FAN1 image, "register value" per line. Hand-computed readings:
#   temp1 = 39 + 5/8 = 39.625 C, temp2 = 45 + 1/8 = 45.125 C
#   crit 70 / 80 C, offsets +2 / -4 C (17h nibbles 1 and E), fan-start 35 / 40 C
#   fan1: count 60 -> 58500/60 = 975 RPM, limit 144 -> 406 RPM (406.25)
#   fan2: count 65 -> 900 RPM, limit FFh -> detection off -> fan2_min 0
#   pwm1 automatic (FAN_CONFIG bit 5: fan1 follows temp1, bit 7: 10 C hysteresis),
#   pwm2 manual; target duties 48/240 -> pwm 51; start 48 -> 51, 60 -> 64;
#   max 240 -> 255, 200 -> 213 (212.5 rounds up); PWM_FREQ 40h -> 33 Hz
BRFAN1_IMAGE="
0x00 0x27
0x01 0x2d
0x02 0x18
0x03 0x46
0x04 0x50
0x05 0x00
0x06 0x00
0x07 0x30
0x08 0x3c
0x09 0xf0
0x0a 0xc8
0x0b 0x30
0x0c 0x30
0x0d 0x30
0x0e 0x30
0x0f 0x23
0x10 0x28
0x11 0xa0
0x12 0xb4
0x13 0x55
0x14 0x40
0x17 0x1e
0x18 0x3c
0x19 0x41
0x1a 0x90
0x1b 0xff
0x1c 0x00
0x1e 0xa0
0x1f 0x20
0xfd 0x01
0xfe 0x68
0xff 0x4d
"

STUB_BUS=
CHIP_ADDR=0x18
# i2c-dev gives i2cset/i2cget their /dev/i2c-N; unloaded again if we loaded it.
I2C_DEV_LOADED_BY_US=0

# stub_load ADDR[,ADDR...]: load i2c-stub with a chip at each ADDR (up to
# ten, one module load for all of them) and find its bus number; CHIP_ADDR,
# the chip the helpers below talk to, is the first.
stub_load() {
	CHIP_ADDR=${1%%,*}
	LAST_DUMP=
	modprobe i2c-stub chip_addr="$1" || return 1
	STUB_BUS=
	for a in /sys/bus/i2c/devices/i2c-*; do
		if grep -q '^SMBus stub driver' "$a/name" 2>/dev/null; then
			STUB_BUS=${a##*/i2c-}
		fi
	done
	[ -n "$STUB_BUS" ] || return 1
	if ! grep -q '^i2c_dev ' /proc/modules; then
		modprobe i2c-dev || return 1
		I2C_DEV_LOADED_BY_US=1
	fi
	# devtmpfs creates the node asynchronously
	wait_until 20 test -c "/dev/i2c-$STUB_BUS"
}

# image_load [IMAGE]: write a register image ("reg value" lines) into the stub.
image_load() {
	LAST_DUMP=
	echo "${1:-$BRFAN1_IMAGE}" | while read -r reg val; do
		[ -n "$reg" ] || continue
		i2cset -y -f "$STUB_BUS" "$CHIP_ADDR" "$reg" "$val" || return 1
	done
}

# reg_get REG: the register as the chip holds it, e.g. 0x1e.
reg_get() { i2cget -y -f "$STUB_BUS" "$CHIP_ADDR" "$1"; }
# reg_set REG VALUE: change the chip behind the driver (volatile registers only,
# the driver caches the others).
reg_set() { LAST_DUMP=; i2cset -y -f "$STUB_BUS" "$CHIP_ADDR" "$1" "$2"; }

client_name() { printf '%s-%04x' "$STUB_BUS" "$CHIP_ADDR"; }
client_dir() { echo "/sys/bus/i2c/devices/$(client_name)"; }

# hwmon_dir: the hwmon directory of the bound chip (empty when unbound).
hwmon_dir() {
	for h in "$(client_dir)"/hwmon/hwmon*; do
		[ -d "$h" ] && echo "$h"
	done
}

# driver_bound: the client exists and the max6615 driver is bound to it.
driver_bound() {
	[ "$(basename "$(readlink "$(client_dir)/driver" 2>/dev/null)")" = max6615 ]
}

# Each check below runs on the debug kernel, where every process a shell
# starts costs a tenth of a second or more: the helpers set variables in this
# shell instead of printing into $(...), and parse with bash builtins.
ATTR_ERR=${VMTEST_SCRATCH:-/tmp}/max6615-attr.err
DUMP_OUT=${VMTEST_SCRATCH:-/tmp}/max6615-dump.txt

# attr_write FILE VALUE: write VALUE; WRITE_RES is "ok" or the error text
# (e.g. "Invalid argument").
attr_write() {
	WRITE_RES=
	{ printf '%s\n' "$2" >"$1"; } 2>"$ATTR_ERR"
	read -r WRITE_RES <"$ATTR_ERR" || true
	if [ -z "$WRITE_RES" ]; then
		WRITE_RES=ok
	else
		WRITE_RES=${WRITE_RES##*: }
	fi
}

# dump_regs: DUMP = registers 00h..1Fh as 32 hex bytes ("27 2d 18 ..."),
# one read each.
dump_regs() {
	local -a w
	local i
	DUMP=
	i2cdump -y -f -r 0x00-0x1f "$STUB_BUS" "$CHIP_ADDR" b >"$DUMP_OUT" || return 1
	while read -r -a w; do
		case ${w[0]:-} in
		00: | 10:) for ((i = 1; i <= 16; i++)); do DUMP+="${w[i]} "; done ;;
		esac
	done <"$DUMP_OUT"
}

# dump_with REG VALUE DUMP: DUMP_WITH = DUMP with register REG replaced by
# VALUE (hex).
dump_with() {
	local -a r
	read -r -a r <<<"$3"
	printf -v "r[$(($1))]" '%02x' $(($2))
	printf -v DUMP_WITH '%s ' "${r[@]}"
}

# LAST_DUMP: the registers as the previous expect_write/expect_reject left
# them, the "before" of the next one (two dumps per check cost half of this
# suite's time on the debug kernel). Whatever changes the chip on purpose
# (reg_set, image_load, stub_load, a test's own writes: clear it there)
# empties it. A change nobody asked for in between (say, a driver write on
# an attribute read) then shows as a failure of the next check.
LAST_DUMP=

# write_dumped ATTR VALUE: the registers before (BEFORE), the write
# (WRITE_RES) and the registers after it (DUMP, also the next LAST_DUMP).
write_dumped() {
	[ -n "$LAST_DUMP" ] || { dump_regs; LAST_DUMP=$DUMP; }
	BEFORE=$LAST_DUMP
	attr_write "$H/$1" "$2"
	dump_regs
	LAST_DUMP=$DUMP
}

# expect_write ATTR VALUE REG NEWVAL: the write succeeds and changes exactly
# register REG to NEWVAL, nothing else (H = the hwmon directory).
expect_write() {
	write_dumped "$1" "$2"
	dump_with "$3" "$4" "$BEFORE"
	tap_is "$1 <- $2 sets reg $3 to $4 and nothing else" "$WRITE_RES $DUMP" \
		"ok $DUMP_WITH"
}

# expect_reject ATTR VALUE ERRTEXT: the write fails with ERRTEXT and no
# register changes.
expect_reject() {
	write_dumped "$1" "$2"
	tap_is "$1 <- $2 is rejected ($3), registers unchanged" "$WRITE_RES $DUMP" \
		"$3 $BEFORE"
}

# --- SMBus transactions through the i2c tracepoints (tracefs) ---------------
TRACEFS=/sys/kernel/tracing
TRACEFS_MOUNTED_BY_US=0
TRACE_ACTIVE=0

# trace_setup: mount tracefs if needed, enable the smbus_read/smbus_write
# events for the stub chip and the regmap cache-hit event of its regmap.
trace_setup() {
	if [ ! -e "$TRACEFS/trace" ]; then
		mount -t tracefs nodev "$TRACEFS" || return 1
		TRACEFS_MOUNTED_BY_US=1
	fi
	TRACE_ACTIVE=1
	echo 0 >"$TRACEFS/tracing_on"
	for ev in smbus/smbus_read smbus/smbus_write; do
		echo "adapter_nr == $STUB_BUS && addr == $((CHIP_ADDR))" \
			>"$TRACEFS/events/$ev/filter" || return 1
		echo 1 >"$TRACEFS/events/$ev/enable" || return 1
	done
	echo "name == \"$(client_name)\"" \
		>"$TRACEFS/events/regmap/regmap_reg_read_cache/filter" || return 1
	echo 1 >"$TRACEFS/events/regmap/regmap_reg_read_cache/enable" || return 1
	: >"$TRACEFS/trace"
}

trace_teardown() {
	echo 0 >"$TRACEFS/tracing_on" 2>/dev/null
	for ev in smbus/smbus_read smbus/smbus_write regmap/regmap_reg_read_cache; do
		echo 0 >"$TRACEFS/events/$ev/enable" 2>/dev/null
		echo 0 >"$TRACEFS/events/$ev/filter" 2>/dev/null
	done
	: >"$TRACEFS/trace" 2>/dev/null
	[ "$TRACEFS_MOUNTED_BY_US" = 1 ] && umount "$TRACEFS"
	TRACEFS_MOUNTED_BY_US=0
	TRACE_ACTIVE=0
	return 0
}

# trace_run CMD...: run CMD with tracing on; the events land in TRACE_LOG.
TRACE_LOG=
trace_run() {
	: >"$TRACEFS/trace"
	echo 1 >"$TRACEFS/tracing_on"
	"$@"
	_rc=$?
	echo 0 >"$TRACEFS/tracing_on"
	TRACE_LOG=$(grep -v '^#' "$TRACEFS/trace")
	return $_rc
}

# trace_count EVENT: events of that name in TRACE_LOG.
trace_count() { printf '%s\n' "$TRACE_LOG" | grep -c " $1: "; }
# trace_data_writes: SMBus writes that carry data (the core's address probe
# is a QUICK command, no register write).
trace_data_writes() {
	printf '%s\n' "$TRACE_LOG" | grep ' smbus_write: ' | grep -vc ' QUICK'
}
# trace_read_regs: the registers (hex, no 0x) of the SMBus reads in TRACE_LOG.
trace_read_regs() {
	printf '%s\n' "$TRACE_LOG" | grep ' smbus_read: ' | sed -n 's/.* c=\([0-9a-f]*\) .*/\1/p'
}

# The driver's volatile registers (spec): everything else may be cached.
VOLATILE_REGS="0 1 5 b c d e 16 18 19 1c 1e 1f"
is_volatile() {
	for _v in $VOLATILE_REGS; do [ "$_v" = "$1" ] && return 0; done
	return 1
}

# tap_header / tap_done: TAP with the plan printed last (points counted as run).
tap_header() { echo "TAP version 13"; }
tap_done() {
	echo "1..$TAP_N"
	[ "$TAP_N" -gt 0 ] && [ "$TAP_FAILED" -eq 0 ]
}

# cleanup_modules: unload the driver and the stub (between steps of a test).
cleanup_modules() {
	modprobe -r max6615 2>/dev/null
	modprobe -r i2c-stub 2>/dev/null
	return 0
}

# cleanup_all: also undo the tracing and i2c-dev (the EXIT trap of a test).
cleanup_all() {
	[ "$TRACE_ACTIVE" = 1 ] && trace_teardown
	cleanup_modules
	[ "$I2C_DEV_LOADED_BY_US" = 1 ] && modprobe -r i2c-dev 2>/dev/null
	return 0
}
