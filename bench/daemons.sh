#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# bench/daemons.sh [x86_64|armel]: memory and CPU of every robot module and
# of the whole stack at the robot's polling rates (issue 9: < 8 MB in all,
# < 2 % of one core). Needs the project's modules and the simulated devices,
# so it runs inside the x86 VM: `make bench TEST=daemons` (tests/vm/daemons/
# bench.sh runs x86_64, bench-arm.sh armel).
#
# The stack is what the robot runs: advee-watchdog supervising driver_aux
# (1 Hz, the simulated MAX6615 and its fan-fail line), driver_rs485a (bus A,
# 4 Hz: two BR-SD1 + BR-SO1), driver_rs485b (bus B, 1 Hz: BR-SBS1),
# driver_power (1 Hz, BR-PSC1) and, once it is built, driver_canbus (vcan0,
# simulated EPOS node 1 + IclA node 2, LL_CMD_MOTION at 10 Hz), configured
# with the robot's files (userland/*/conf) on the simulated buses. After the
# modules announce RUN and SETTLE more seconds, bench/proc-usage.py samples
# them over WINDOW seconds while a listener counts each data channel (the
# rates the modules really ran at).
#
# armel: the TS-7800's cross-built binaries (build/userland-armel) under
# qemu-user, watchdog included (it starts each module as `qemu-arm BINARY`;
# QEMU_LD_PREFIX is a root of the cross toolchain's libc and the armel
# sysroot of scripts/fetch-arm-sysroot.sh). Each module is first tried on
# its own (all side by side) for up to TRY seconds: one that does not reach
# RUN (qemu-user passes on only the ioctls it knows) is reported with its
# error and left out of the stack; driver_aux, which fails only on its
# fan-fail GPIO line, is measured without that line.
#   DAEMONS_BENCH_SETTLE_S  (default 10)  DAEMONS_BENCH_WINDOW_S (default 30)
#   DAEMONS_BENCH_TRY_S     (default 60, armel)
set -uo pipefail
ARCH=${1:-x86_64}
SETTLE=${DAEMONS_BENCH_SETTLE_S:-10}
WINDOW=${DAEMONS_BENCH_WINDOW_S:-30}
TRY=${DAEMONS_BENCH_TRY_S:-60}
HERE=$(cd "$(dirname "$0")" && pwd)
: "${VMTEST_REPO:?run inside the VM (make bench TEST=daemons)}" "${VMTEST_BUILD:?}"
. "$VMTEST_REPO/tests/vm/daemons/lib.sh"

CONF=$VMTEST_REPO/userland
CAN_IF=vcan0
CAN_UP=0
MOTION_HZ=10
case $ARCH in
x86_64)
	B=$VMTEST_BUILD/userland
	RUN=()
	;;
armel)
	B=$VMTEST_BUILD/userland-armel
	SYSROOT=$VMTEST_REPO/.cache/arm/armel/sysroot
	RUN=(/usr/bin/qemu-arm)
	;;
*) echo "bench/daemons.sh: unknown architecture $ARCH (x86_64, armel)" >&2; exit 2 ;;
esac
WD_BIN=$B/watchdog/advee-watchdog
declare -A BIN=(
	[driver_aux]=$B/daemons/driver_aux/driver_aux
	[driver_rs485a]=$B/daemons/driver_rs485/driver_rs485
	[driver_rs485b]=$B/daemons/driver_rs485/driver_rs485
	[driver_power]=$B/daemons/driver_power/driver_power
	[driver_canbus]=$B/daemons/driver_canbus/driver_canbus
)
MODULES=(driver_aux driver_rs485a driver_rs485b driver_power driver_canbus)
# The channels each module publishes and their rate in the robot's configuration.
declare -A CHANNELS=(
	[driver_aux]="LL_DATA_TEMPERATURE:1 LL_DATA_FANS:1"
	[driver_rs485a]="LL_DATA_SRFS:4 LL_DATA_ODO:4"
	[driver_rs485b]="LL_DATA_BEACONS:1"
	[driver_power]="LL_DATA_POWER:1"
	[driver_canbus]="LL_DATA_DRIVES:4"
)

cleanup() {
	bg_kill_all
	if [ "$CAN_UP" = 1 ]; then
		ip link del "$CAN_IF" 2>/dev/null
		modprobe -r vcan can_raw can 2>/dev/null
	fi
	rs485_cleanup
	cleanup_all
	net_teardown
}

# armroot DIR: a root for qemu-arm -L: /lib holds the cross toolchain's
# libc/libstdc++ and the sysroot's libraries (links), where ld-linux.so.3
# looks for them.
armroot() {
	local d
	mkdir -p "$1/lib"
	for d in /usr/arm-linux-gnueabi/lib "$SYSROOT/lib/arm-linux-gnueabi" "$SYSROOT/usr/lib/arm-linux-gnueabi"; do
		ln -sf "$d"/* "$1/lib/"
	done
}

# module_config NAME FILE: the robot's configuration of NAME on the simulated
# devices (the response timeout of the rs485 suite: TCG, see common.inc).
module_config() {
	local dev=
	case $1 in
	driver_aux) cp "$CONF/daemons/driver_aux/conf/driver_aux.yaml" "$2"; return ;;
	driver_rs485a) dev=/dev/ttyTSU0 ;;
	driver_rs485b) dev=/dev/ttyTSU1 ;;
	driver_power) dev=/dev/ttyTSU2 ;;
	driver_canbus) sed "s/\bcan0\b/$CAN_IF/" "$CONF/daemons/driver_canbus/conf/driver_canbus.yaml" >"$2"; return ;;
	esac
	sed -e "s|device: [a-z]*,|device: $dev,|" -e "s/timeout_ms: [0-9]*/timeout_ms: $TIMEOUT_MS/" \
		-e 's/\[systemctl, poweroff\]/["true"]/' -e 's/\[systemctl, reboot\]/["true"]/' \
		"$CONF/daemons/${1%[ab]}/conf/${1}.yaml" >"$2"
}

# can_up: vcan0 with the simulated EPOS (node 1) and IclA (node 2).
can_up() {
	local n p
	modprobe vcan || return 1
	ip link add dev "$CAN_IF" type vcan 2>/dev/null
	CAN_UP=1
	ip link set up "$CAN_IF" || return 1
	for n in 1:epos 2:icla; do
		p=${n#*:}
		bg "$VMTEST_BUILD/userland/canopen/advee-canopen-sim-drive" -i "$CAN_IF" -n "${n%%:*}" -p "$p" >"$SCR/sim-$p.log" 2>&1
		wait_for "$SCR/sim-$p.log" "ready on" 20 || return 1
	done
}

# try_all NAME...: run the modules side by side, each alone on its devices,
# until each has announced RUN or ended, or TRY s pass; RAN[NAME]=1 for those
# that announced RUN. Their stderr (qemu's unsupported-ioctl lines included)
# is in $SCR/try-NAME.err. Side by side: the failures come at start-up, and
# one after the other would not fit the suite's time limit under TCG.
declare -A RAN=()
try_all() {
	local m lis i left
	declare -A pid=()
	"$LCMCTL" echo --timeout "$TRY" CM_DATA_STATE >"$SCR/try.states" &
	lis=$!
	sleep 0.3
	for m in "$@"; do
		QEMU_LOG=unimp "${RUN[@]}" "${BIN[$m]}" --config "$SCR/$m.yaml" 2>"$SCR/try-$m.err" &
		pid[$m]=$!
		RAN[$m]=0
	done
	for ((i = 0; i < TRY * 2; i++)); do
		left=0
		for m in "$@"; do
			[ "${RAN[$m]}" = 1 ] && continue
			grep -q "module=$m state=RUN" "$SCR/try.states" && { RAN[$m]=1; continue; }
			kill -0 "${pid[$m]}" 2>/dev/null && left=1
		done
		[ $left = 0 ] && break
		sleep 0.5
	done
	for m in "$@"; do
		[ "${RAN[$m]}" = 1 ] || echo "  (after $((i / 2)) s: $(kill -0 "${pid[$m]}" 2>/dev/null && echo "still starting" || echo "ended"))" >>"$SCR/try-$m.err"
		kill "${pid[$m]}" 2>/dev/null
		wait "${pid[$m]}" 2>/dev/null
	done
	kill "$lis" 2>/dev/null
	wait "$lis" 2>/dev/null
	return 0
}

# try_report NAME: why NAME did not run under qemu-user (without "Unsupported
# syscall: 398": rseq, which qemu 7.2 lacks and glibc does without).
try_report() {
	echo "did not run $1 under qemu-user; its stderr:"
	grep -v '^Unsupported syscall: 398$' "$SCR/try-$1.err" | sort -u | head -8 | sed 's/^/  /'
}

# show_logs: what the watchdog and the modules logged (warnings and worse):
# a restart or a failing board shows here.
show_logs() {
	local f
	for f in "$SCR/watchdog.err" "$SCR"/log/*/*.log; do
		[ -s "$f" ] && tail -n 20 "$f" | sed "s|^|log ${f##*/}: |"
	done
	return 0
}

trap cleanup EXIT
for p in "$WD_BIN" "$PROBE" "$LCMCTL" "$SIMBIN/advee-rs485-sim"; do
	[ -x "$p" ] || { echo "bench/daemons.sh: $p not built" >&2; exit 1; }
done
if [ "$ARCH" = armel ]; then
	[ -x "${RUN[0]}" ] || { echo "bench/daemons.sh: ${RUN[0]} missing (apt-get install qemu-user)" >&2; exit 1; }
	[ -d "$SYSROOT" ] || { echo "bench/daemons.sh: no armel sysroot (scripts/fetch-arm-sysroot.sh armel)" >&2; exit 1; }
	armroot "$SCR/armroot"
	export QEMU_LD_PREFIX=$SCR/armroot
fi
net_setup || { echo "bench/daemons.sh: no loopback multicast" >&2; exit 1; }
# The DIO header + MAX6615 first (sim_load loads ts7800_dio before the
# simulated FPGA), then the TS-UARTs and advee-rs485-sim on the same FPGA.
board_up || { echo "bench/daemons.sh: simulated MAX6615 did not come up" >&2; exit 1; }
modprobe ts_uart || exit 1
for p in /dev/ttyTSU0 /dev/ttyTSU1 /dev/ttyTSU2; do
	wait_path "$p" 10 || { echo "bench/daemons.sh: $p did not appear" >&2; exit 1; }
done
start_sim "$DSUITE/boards.yaml" || { echo "bench/daemons.sh: advee-rs485-sim did not start" >&2; sed 's/^/  /' "$SCR/sim.err" >&2; exit 1; }
sim set sd1@0x10 srf all 1.50 >/dev/null
sim set sd1@0x11 srf all 2.50 >/dev/null
sim set so1@0x20 rate 1024 1024 >/dev/null
# A beacon scanner with beacons in view: its answer has a bearing per beacon.
"$PROBE" active-beacons 1 2 3 >/dev/null

echo "# daemons bench, $ARCH$([ "$ARCH" = armel ] && echo " under $("${RUN[0]}" --version | head -1)"), guest kernel $(uname -r), $(nproc) CPUs, guest load $(cut -d' ' -f1-3 /proc/loadavg)"
CANDIDATES=()
for m in "${MODULES[@]}"; do
	if [ ! -x "${BIN[$m]}" ]; then
		echo "not built $m (${BIN[$m]#"$VMTEST_BUILD"/})"
		continue
	fi
	if [ "$m" = driver_canbus ]; then
		if ! can_up; then echo "not measured $m: vcan0 or the simulated drives did not come up"; continue; fi
	fi
	module_config "$m" "$SCR/$m.yaml"
	CANDIDATES+=("$m")
done
STACK=()
if [ "$ARCH" = armel ] && [ ${#CANDIDATES[@]} -gt 0 ]; then
	try_all "${CANDIDATES[@]}"
	for m in "${CANDIDATES[@]}"; do
		[ "${RAN[$m]}" = 1 ] && { STACK+=("$m"); continue; }
		try_report "$m"
		# qemu-user does not know the GPIO character device's ioctls:
		# driver_aux without its (optional) fan-fail line still reads the
		# chip through hwmon sysfs, which is most of its work.
		# Not tried alone again (a C++ start-up under qemu-user in TCG takes
		# tens of seconds): the watchdog's start shows whether it runs.
		if [ "$m" = driver_aux ] && grep -q 'fan-fail line' "$SCR/try-$m.err"; then
			sed -i '/^  fan_fail:/,/^    line:/d' "$SCR/$m.yaml"
			echo "note: $m is measured without fan_fail (its configuration minus the fan-fail line)"
			STACK+=("$m")
		fi
	done
else
	STACK=("${CANDIDATES[@]}")
fi
[ ${#STACK[@]} -gt 0 ] || { echo "bench/daemons.sh: no module to measure" >&2; exit 1; }
echo "[${SECONDS} s] starting advee-watchdog with: ${STACK[*]}"

{
	echo "module: {name: watchdog, print_severity: warning, log_root: $SCR/log}"
	echo "supervisor: {dead_after_s: 2, check_period_s: 0.2, term_grace_s: 2, startup_grace_s: 60}"
	echo "modules:"
	for m in "${STACK[@]}"; do
		if [ "$ARCH" = armel ]; then
			echo "  - {name: $m, path: ${RUN[0]}, args: [${BIN[$m]}, --config, $SCR/$m.yaml]}"
		else
			echo "  - {name: $m, path: ${BIN[$m]}, args: [--config, $SCR/$m.yaml]}"
		fi
	done
} >"$SCR/watchdog.yaml"

if [[ " ${STACK[*]} " == *" driver_canbus "* ]]; then
	bg "$PROBE" motion 0.3 0.1 "$MOTION_HZ" $((SETTLE + WINDOW + 120))
fi
bg "${RUN[@]}" "$WD_BIN" --config "$SCR/watchdog.yaml" 2>"$SCR/watchdog.err"
WD=$LAST_BG

# Every module's pid from its RUN announcement (under qemu-user, getpid() is
# the emulator's pid).
declare -A PID=()
deadline=$((SECONDS + 90))
while [ ${#PID[@]} -lt ${#STACK[@]} ] && [ $SECONDS -lt $deadline ]; do
	while read -r _ch mod st pid; do
		mod=${mod#module=}
		[ "$st" = state=RUN ] && [[ " ${STACK[*]} " == *" $mod "* ]] || continue
		PID[$mod]=${pid#pid=}
	done < <("$LCMCTL" echo --timeout 2 CM_DATA_STATE)
done
for m in "${STACK[@]}"; do
	if [ -z "${PID[$m]:-}" ]; then
		echo "bench/daemons.sh: $m did not announce RUN under the watchdog" >&2
		show_logs
		exit 1
	fi
done
# Steering homed, so that LL_CMD_MOTION moves both drives (as on the robot).
[[ " ${STACK[*]} " == *" driver_canbus "* ]] && "$PROBE" homing
echo "[${SECONDS} s] every module announces RUN; settling for $SETTLE s"
sleep "$SETTLE"

IDLE=
if [ "$ARCH" = armel ]; then
	printf '#include <unistd.h>\nint main(void) { for (;;) pause(); }\n' >"$SCR/idle.c"
	arm-linux-gnueabi-gcc -O2 -o "$SCR/idle" "$SCR/idle.c" || exit 1
	bg "${RUN[@]}" "$SCR/idle"
	IDLE=$LAST_BG
	sleep 2
fi

echo "[${SECONDS} s] measuring for $WINDOW s"
chans=()
for m in "${STACK[@]}"; do for c in ${CHANNELS[$m]}; do chans+=("${c%:*}"); done; done
"$PROBE" listen "$WINDOW" "${chans[@]}" >"$SCR/rates.out" &
LISTEN=$!
args=(--window "$WINDOW" --breakdown 8 "watchdog=$WD")
for m in "${STACK[@]}"; do args+=("$m=${PID[$m]}"); done
[ "$ARCH" = armel ] && args+=(--guest --baseline "$IDLE")
"$HERE/proc-usage.py" "${args[@]}"
rc=$?
wait "$LISTEN"

echo "rates in the window (messages / $WINDOW s):"
for m in "${STACK[@]}"; do
	for c in ${CHANNELS[$m]}; do
		n=$(grep -c "^${c%:*} " "$SCR/rates.out")
		awk -v m="$m" -v c="${c%:*}" -v n="$n" -v w="$WINDOW" -v want="${c#*:}" 'BEGIN {
			printf "rate %s %s %.2f Hz (configured %d Hz) = %.2f\n", m, c, n / w, want, n / w / want }'
	done
done
# How fast this CPU is: a fixed user-space loop, to compare the CPU shares
# with another machine (bench/README.md has the host's time for the same loop).
# Most of the modules' CPU time is system time (syscalls, the simulated
# devices' kernel work), so the cost of a plain syscall is the other one.
t0=$(date +%s%N)
awk 'BEGIN { for (i = 0; i < 3000000; i++) s += i }'
echo "speed reference: awk loop of 3e6 additions $(( ($(date +%s%N) - t0) / 1000000 )) ms"
t0=$(date +%s%N)
dd if=/dev/zero of=/dev/null bs=1 count=100000 status=none
echo "speed reference: dd of 1e5 1-byte blocks (2e5 read/write syscalls) $(( ($(date +%s%N) - t0) / 1000000 )) ms"
echo "guest CPU mitigations: meltdown: $(cat /sys/devices/system/cpu/vulnerabilities/meltdown 2>/dev/null); spectre_v2: $(cut -d, -f1 /sys/devices/system/cpu/vulnerabilities/spectre_v2 2>/dev/null); mds: $(cat /sys/devices/system/cpu/vulnerabilities/mds 2>/dev/null)"
show_logs
exit $rc
