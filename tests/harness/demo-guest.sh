#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# demo-guest.sh: what `make demo` runs inside the VM (docs/demo.md). Brings up
# the whole low level on the simulated robot (tests/vm/stack/lib.sh: kernel
# modules, advee-rs485-sim, advee-robot-sim with its CANopen drives on vcan0, the
# supervisor with every driver daemon), lets the planner stand-in drive the
# scripted path, and shows the robot through advee-diagnostic-center:
#   interactive: the terminal UI on the VM's console (the caller's terminal);
#                quitting it (q) ends the demo and the VM powers off
#   --for 30s:   advee-diagnostic-center --text prints a summary every 5 s for that
#                long; exit 0 when the stack ran and the robot moved
#
# usage: demo-guest.sh [--for DURATION] [--tui] [--rows N --cols N --term TERM]
# Without arguments the options come from the kernel command line (the host's
# scripts/demo.sh sets them): advee.demo=tui|for:DURATION, advee.rows=N,
# advee.cols=N, advee.term=TERM.
set -u
mode= for_= rows= cols= term= web_port=
for word in $(cat /proc/cmdline); do
	case $word in
	advee.demo=tui) mode=tui ;;
	advee.demo=for:*) mode=for for_=${word#advee.demo=for:} ;;
	advee.rows=*) rows=${word#*=} ;;
	advee.cols=*) cols=${word#*=} ;;
	advee.term=*) term=${word#*=} ;;
	vmtest.hostfwd=*) web_port=${word#*=} ;;
	esac
done
while [ $# -gt 0 ]; do
	case $1 in
	--for) mode=for for_=$2; shift 2 ;;
	--tui) mode=tui; shift ;;
	--rows) rows=$2; shift 2 ;;
	--cols) cols=$2; shift 2 ;;
	--term) term=$2; shift 2 ;;
	*) echo "demo-guest.sh: unknown argument $1" >&2; exit 2 ;;
	esac
done
[ -n "$mode" ] || mode=for for_=30s

. "$VMTEST_REPO/tests/vm/stack/lib.sh"
PERIOD=5s

if [ "$mode" = tui ]; then
	# The runner gives programs /dev/null and a log file; the demo wants the
	# console, i.e. the terminal QEMU's serial port is connected to. Opening
	# it makes it this session's controlling terminal (Ctrl-C, resize).
	exec </dev/ttyS0 >/dev/ttyS0 2>&1
	dmesg -n 1	# kernel messages would draw over the screen
	stty sane
	[ -n "$rows" ] && [ -n "$cols" ] && stty rows "$rows" cols "$cols"
	export TERM=${term:-vt100}
	echo "Advee demo: bringing up the low level on the simulated robot (about 30 s under TCG) ..."
fi

echo "Advee low-level stack on the simulated robot ($(uname -sr), $(nproc) CPU(s) under QEMU TCG)"
if [ -n "$(stack_missing)" ]; then
	echo "Not there yet (the demo runs without them):"
	stack_missing | sed 's/^/  - /'
fi
if ! stack_up; then
	echo "demo: the stack did not come up:"
	[ -n "$STACK_RUN" ] && stack_logs 15 | sed 's/^# //'
	[ "$mode" = tui ] && sleep 5
	exit 1
fi
echo "Running: kernel modules ts7800-sim ts-uart ts7800-dio n_rs485 ts7800-dio-i2c max6615 vcan; advee-rs485-sim;"
echo "  advee-robot-sim (robot drives: $STACK_ROBOT_DRIVES); advee-watchdog with $STACK_MODULES"

PATH_FILE=$ROBOTSIM_CONF/square-path.yaml
drive_args=(--home --home-wait 3 --beacons 1,2,3,4,5,6,7,8 --quiet)
if [ "$STACK_ROBOT_DRIVES" = can ]; then
	echo "Planner stand-in: advee-drive-script plays $(basename "$PATH_FILE") onto LL_CMD_MOTION at 10 Hz"
else
	echo "advee-robot-sim plays $(basename "$PATH_FILE") itself (no simulated CAN drives yet): LL_CMD_MOTION does not move it"
fi

# The web dashboard (docs/web-dashboard.md) when the host forwards a port to
# the guest (scripts/demo.sh, interactive only): QEMU's user network, the
# guest at 10.0.2.15; LCM stays on the loopback route.
web_up() {
	local web=$STACK_UL/web/advee-web
	[ -n "$web_port" ] && [ -x "$web" ] || return 0
	modprobe virtio_net && ip link set eth0 up && ip addr add 10.0.2.15/24 dev eth0 ||
		{ echo "web dashboard: no guest network (virtio_net), not started"; return 0; }
	# The operator's password file scripts/demo.sh wrote on the host.
	stack_bg advee-web "$web" --listen "0.0.0.0:$web_port" --root "$STACK_USERLAND_SRC/web/static" \
		--robot "$ROBOTSIM_CONF/robot.yaml" --map "$ROBOTSIM_CONF/room.yaml" \
		--operators "$VMTEST_BUILD/demo/web-operators"
	echo "Web dashboard: http://127.0.0.1:$web_port/ (open it on the host; log in as operator, password as printed before the boot)"
	sleep 2
}

if [ "$mode" = tui ]; then
	web_up
	# The path once, then the operator drives (arrow keys); standstill
	# commands would fight the manual ones, so none after the path.
	stack_drive "$PATH_FILE" "${drive_args[@]}" --hold 0
	if stack_has diagnostic-center; then
		"$DIAGNOSTIC_CENTER"
		rc=$?
	else
		echo "advee-diagnostic-center is not built: showing the LCM traffic instead (Ctrl-C ends the demo)"
		trap 'true' INT
		"$STACK_LISTEN" --seconds 86400
		rc=0
	fi
	clear 2>/dev/null
	echo "demo: advee-diagnostic-center exited ($rc); stopping the stack and powering off"
	stack_down
	# The harness counts a program that printed no TAP point as a failure.
	tap_result 0 "demo: the operator ended the interactive session (advee-diagnostic-center exit status $rc)"
	exit 0
fi

# --for: the path (if it is shorter, the robot then stands), a text summary
# every $PERIOD.
stack_drive "$PATH_FILE" "${drive_args[@]}" --stay
t0=$(date +%s)
if stack_has diagnostic-center; then
	"$DIAGNOSTIC_CENTER" --text --for "$for_" --period "$PERIOD"
	rc=$?
else
	# Until advee-diagnostic-center exists: the decoded messages of the channels the
	# summary would show, the last of each every period.
	secs=${for_%s}
	rc=0
	while [ $(($(date +%s) - t0)) -lt "$secs" ]; do
		"$STACK_LISTEN" --seconds "${PERIOD%s}" >"$STACK_RUN/period.txt" || rc=1
		echo "--- $(($(date +%s) - t0)) s"
		for ch in CM_DATA_STATE SIM_DATA_POSE LL_DATA_ODO LL_CMD_MOTION LL_DATA_DRIVES LL_DATA_SRFS \
			LL_DATA_BEACONS LL_DATA_TEMPERATURE LL_DATA_FANS LL_DATA_POWER; do
			grep "^$ch " "$STACK_RUN/period.txt" | tail -1
		done
	done
fi
echo "demo: ran $(($(date +%s) - t0)) s; advee-diagnostic-center exit status $rc"
stack_down
# The harness counts a program that printed no TAP point as a failure.
tap_result "$rc" "demo: the stack ran $for_ on the simulated robot and advee-diagnostic-center summarised it"
exit $rc
