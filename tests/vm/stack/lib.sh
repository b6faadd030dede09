# SPDX-License-Identifier: GPL-2.0
# The whole low-level stack on the simulated robot, inside the VM guest
# (sourced by the tests of this suite, by tests/harness/demo-guest.sh and by
# other suites that need the stack up). docs/demo.md draws what runs where.
#
#   stack_up            kernel modules (simulated TS-7800 FPGA + TS-UART + DIO,
#                       n_rs485, DIO I2C adapter + MAX6615, vcan0), advee-rs485-sim
#                       with the robot's boards, advee-robot-sim, advee-watchdog with
#                       every driver daemon; returns once all modules are in RUN
#   stack_drive FILE    the planner stand-in: advee-drive-script plays FILE
#                       (a advee-robot-sim path file) onto LL_CMD_MOTION at 10 Hz
#   stack_down          stops everything stack_up and stack_drive started and
#                       unloads the modules (also on EXIT: stack_up sets a trap)
#   stack_missing       the pieces of the stack not built yet (one per line)
#   stack_has PIECE     canbus | robot-can | sim-pose | diagnostic-center
#   stack_require PIECE...  a test needs them: a missing one fails the
#                       program (a failing TAP point naming it), never a skip
#
# Variables after stack_up: STACK_RUN (scratch dir: conf/, logs, sockets),
# STACK_MODULES (names the supervisor runs), STACK_ROBOT_DRIVES (can: the
# robot moves as the simulated drives on vcan0 turn; path: advee-robot-sim plays
# the path itself because its CAN drives are not there yet).
# STACK_DEBUG=1 prints what is started on stderr.

. "$VMTEST_REPO/tests/lib/tap.sh"
. "$VMTEST_REPO/tests/lib/lcm.sh"

STACK_UL=$VMTEST_BUILD/userland
STACK_CONF_SRC=$VMTEST_REPO/tests/vm/stack/conf
STACK_USERLAND_SRC=$VMTEST_REPO/userland
RS485_SIM=$STACK_UL/rs485sim/advee-rs485-sim
ROBOT_SIM=$STACK_UL/robotsim/advee-robot-sim
WATCHDOG=$STACK_UL/watchdog/advee-watchdog
DRIVER_AUX=$STACK_UL/daemons/driver_aux/driver_aux
DRIVER_RS485=$STACK_UL/daemons/driver_rs485/driver_rs485
DRIVER_POWER=$STACK_UL/daemons/driver_power/driver_power
DRIVER_CANBUS=$STACK_UL/daemons/driver_canbus/driver_canbus
LCMCTL=$STACK_UL/module/advee-lcmctl
PROBE=$STACK_UL/daemons/driver_rs485/advee-daemons-probe
DRIVE_SCRIPT=$STACK_UL/demo/advee-drive-script
STACK_LISTEN=$STACK_UL/demo/advee-stack-listen
DIAGNOSTIC_CENTER=$STACK_UL/diagcenter/advee-diagnostic-center
# STACK_ROBOTSIM_CONF: another directory with room.yaml and robot.yaml.
ROBOTSIM_CONF=${STACK_ROBOTSIM_CONF:-$STACK_USERLAND_SRC/robotsim/conf}
SIMFS=/sys/kernel/debug/ts7800-sim

STACK_RUN=
STACK_PIDS=
STACK_MODULES=
STACK_ROBOT_DRIVES=
STACK_LOADED=
STACK_DEBUGFS_MOUNTED=0
STACK_VCAN_ADDED=0
STACK_RS485_SIM_PID=
STACK_ROBOT_SIM_PID=
STACK_WATCHDOG_PID=
STACK_DRIVE_PID=

stack_log() { [ "${STACK_DEBUG:-0}" = 1 ] && echo "stack: [$(cut -d" " -f1 /proc/uptime)] $*" >&2; return 0; }

# stack_has PIECE: whether another engineer's piece is there (built and
# offering what the stack uses). Remembered: each --help costs ~0.5 s under TCG.
declare -A STACK_HAS=()
stack_has() {
	if [ -z "${STACK_HAS[$1]:-}" ]; then
		local help=
		[ -x "$ROBOT_SIM" ] && [ -z "${STACK_ROBOT_SIM_HELP:-}" ] && STACK_ROBOT_SIM_HELP=$("$ROBOT_SIM" --help 2>&1)
		help=${STACK_ROBOT_SIM_HELP:-}
		case $1 in
		canbus) [ -x "$DRIVER_CANBUS" ] ;;
		robot-can) [[ $help == *--can* ]] ;;
		sim-pose) [[ $help == *--lcm* ]] ;;
		diagnostic-center) [ -x "$DIAGNOSTIC_CENTER" ] ;;
		*) false ;;
		esac
		STACK_HAS[$1]=$?
	fi
	return "${STACK_HAS[$1]}"
}

# stack_missing: one line per missing piece, naming it.
stack_missing() {
	stack_has canbus || echo "driver_canbus ($DRIVER_CANBUS not built)"
	stack_has robot-can || echo "advee-robot-sim --can (simulated EPOS/IclA on vcan0)"
	stack_has sim-pose || echo "advee-robot-sim --lcm (SIM_DATA_POSE, the ground-truth pose on LCM)"
	stack_has diagnostic-center || echo "advee-diagnostic-center ($DIAGNOSTIC_CENTER not built)"
	return 0
}

# stack_require PIECE...: before tap_plan. Every piece of the stack is built
# by make userland, so a missing one is a defect: the program fails with one
# TAP point naming what is missing (exit 1).
stack_require() {
	local p missing=
	for p in "$@"; do
		stack_has "$p" || missing="${missing:+$missing, }$(stack_missing | grep -m1 "^$(stack_piece_name "$p")")"
	done
	[ -z "$missing" ] && return 0
	printf 'TAP version 13\n1..1\nnot ok 1 the stack is complete: missing %s\n' "$missing"
	exit 1
}
stack_piece_name() {
	case $1 in
	canbus) echo driver_canbus ;;
	robot-can) echo "advee-robot-sim --can" ;;
	sim-pose) echo "advee-robot-sim --lcm" ;;
	diagnostic-center) echo advee-diagnostic-center ;;
	esac
}

# stack_bg NAME CMD...: CMD in the background, output in $STACK_RUN/NAME.log;
# sets STACK_LAST_PID.
stack_bg() {
	local name=$1
	shift
	stack_log "start $name: $*"
	"$@" >"$STACK_RUN/$name.log" 2>&1 &
	STACK_LAST_PID=$!
	STACK_PIDS="$STACK_LAST_PID $STACK_PIDS"
}

stack_modprobe() {	# stack_modprobe MODULE...: load, remembered for stack_down
	local m
	for m in "$@"; do
		grep -q "^${m//-/_} " /proc/modules && continue
		modprobe "$m" || { echo "stack: modprobe $m failed" >&2; return 1; }
		STACK_LOADED="$m $STACK_LOADED"
	done
}

# stack_kernel_up: the simulated TS-7800 (FPGA, TS-UART buses, DIO header
# with the bit-banged I2C bus and the MAX6615 model), n_rs485, vcan0.
stack_kernel_up() {
	stack_log "loading modules"
	if [ ! -d /sys/kernel/debug/tracing ] && [ -z "$(ls -A /sys/kernel/debug 2>/dev/null)" ]; then
		mount -t debugfs none /sys/kernel/debug && STACK_DEBUGFS_MOUNTED=1
	fi
	stack_modprobe ts7800_dio ts_uart ts7800_sim n_rs485 ts7800_dio_i2c i2c-dev max6615 vcan || return 1
	local p
	for p in /dev/ttyTSU0 /dev/ttyTSU1 /dev/ttyTSU2 /dev/ts7800-sim/uart0 /dev/ts7800-sim/uart1 \
		/dev/ts7800-sim/uart2 "$SIMFS/max6615/temp1"; do
		wait_path "$p" 10 || { echo "stack: $p did not appear" >&2; return 1; }
	done
	wait_until 5 grep -q '^max6615$' /sys/class/hwmon/hwmon*/name 2>/dev/null ||
		{ echo "stack: no max6615 hwmon device" >&2; return 1; }
	if ! ip link show vcan0 >/dev/null 2>&1; then
		ip link add dev vcan0 type vcan || return 1
		STACK_VCAN_ADDED=1
	fi
	ip link set vcan0 txqueuelen 1000
	ip link set up vcan0 || return 1
}

# stack_conf: the daemons' configurations. The robot's own files
# (userland/*/conf) with only what differs in the simulation replaced: the
# bus devices (/dev/rs485/a, b, power -> the simulated TS-UARTs), response
# timeouts for TCG, the power-off command, can0 -> vcan0.
stack_conf() {
	local c=$STACK_RUN/conf d=$STACK_USERLAND_SRC/daemons
	mkdir -p "$c"
	# Under TCG a round trip through advee-rs485-sim takes tens of ms (the boards
	# answer in 0.2-2 ms on the robot): 100 ms as in tests/vm/rs485.
	sed -e 's|device: a,|device: /dev/ttyTSU0,|' -e 's|timeout_ms: 20|timeout_ms: 100|' \
		"$d/driver_rs485/conf/driver_rs485a.yaml" >"$c/driver_rs485a.yaml"
	sed -e 's|device: b,|device: /dev/ttyTSU1,|' -e 's|timeout_ms: 20|timeout_ms: 100|' \
		"$d/driver_rs485/conf/driver_rs485b.yaml" >"$c/driver_rs485b.yaml"
	# The PSC1's power-off must not power off the VM under a test: it leaves
	# a marker file instead.
	sed -e 's|device: power,|device: /dev/ttyTSU2,|' -e 's|timeout_ms: 20|timeout_ms: 100|' \
		-e "s|^\( *poweroff_command:\).*|\1 [touch, $STACK_RUN/poweroff-requested]|" \
		-e "s|^\( *reboot_command:\).*|\1 [touch, $STACK_RUN/reboot-requested]|" \
		"$d/driver_power/conf/driver_power.yaml" >"$c/driver_power.yaml"
	cp "$d/driver_aux/conf/driver_aux.yaml" "$c/driver_aux.yaml"
	if stack_has canbus; then
		# Heartbeats: on a loaded TCG host the simulated drives' 100 ms
		# heartbeat (lost after 3 periods) drops out for seconds at a time
		# (seen: "heartbeat lost", motion refused); 300 ms, and a master
		# timeout and SDO timeout with the same headroom.
		sed -e 's|\bcan0\b|vcan0|' -e 's|heartbeat_ms: 100|heartbeat_ms: 300|g' \
			-e 's|master_timeout_ms: 500|master_timeout_ms: 1500|' -e 's|sdo_timeout_ms: 500|sdo_timeout_ms: 1500|' \
			"$d/driver_canbus/conf/driver_canbus.yaml" >"$c/driver_canbus.yaml"
	fi

	STACK_MODULES="driver_aux driver_rs485a driver_rs485b driver_power"
	stack_has canbus && STACK_MODULES="$STACK_MODULES driver_canbus"
	{
		cat <<EOC
# advee-watchdog of the simulated robot (generated by tests/vm/stack/lib.sh)
module: {name: watchdog, log_root: $STACK_RUN/log, print_severity: notice, send_severity: warning}
supervisor:
  # 2 s on the robot. Under TCG on a loaded 2-core host every module was once
  # declared dead at the same moment (announcements 3.9 s old: the
  # supervisor itself had not run) and all were restarted mid-demo.
  dead_after_s: 4
  term_grace_s: 2
  # Under TCG a module's start (dynamic linking over 9p) takes up to ~2 s.
  startup_grace_s: 10
  backoff: {initial_s: 0.5, max_s: 8, factor: 2, stable_s: 10}
modules:
  - {name: driver_aux, path: $DRIVER_AUX, args: [--config, $c/driver_aux.yaml]}
  - {name: driver_rs485a, path: $DRIVER_RS485, args: [--config, $c/driver_rs485a.yaml]}
  - {name: driver_rs485b, path: $DRIVER_RS485, args: [--config, $c/driver_rs485b.yaml]}
  - {name: driver_power, path: $DRIVER_POWER, args: [--config, $c/driver_power.yaml]}
EOC
		if stack_has canbus; then
			echo "  - {name: driver_canbus, path: $DRIVER_CANBUS, args: [--config, $c/driver_canbus.yaml]}"
		fi
	} >"$c/watchdog.yaml"
	cp "$STACK_CONF_SRC/boards.yaml" "$c/boards.yaml"
}

# stack_robot_up [ROBOT-SIM ARGS...]: advee-robot-sim in real time, publishing to
# advee-rs485-sim and the MAX6615 model; the simulated drives on vcan0 when advee-robot-sim
# has them, else (until then) the scripted path STACK_FALLBACK_PATH.
stack_robot_up() {
	local args=(--map "$ROBOTSIM_CONF/room.yaml" --robot "$ROBOTSIM_CONF/robot.yaml"
		--rs485-control "$STACK_RUN/rs485-sim.sock" --max6615 "$SIMFS/max6615")
	if stack_has robot-can; then
		STACK_ROBOT_DRIVES=can
		args+=(--can vcan0)
	else
		STACK_ROBOT_DRIVES=path
		args+=(--path "${STACK_FALLBACK_PATH:-$ROBOTSIM_CONF/square-path.yaml}")
	fi
	stack_has sim-pose && args+=(--lcm)
	stack_bg robot-sim "$ROBOT_SIM" "${args[@]}" "$@"
	STACK_ROBOT_SIM_PID=$STACK_LAST_PID
	# With its CAN drives it says when they are on the bus; the path
	# fallback has no such line (the checks after stack_wait_run see it).
	if [ "$STACK_ROBOT_DRIVES" = can ] && ! wait_line "$STACK_RUN/robot-sim.log" '^drives on vcan0' 20 >/dev/null; then
		echo "stack: advee-robot-sim did not put its drives on vcan0:" >&2
		tail -5 "$STACK_RUN/robot-sim.log" >&2
		return 1
	fi
	kill -0 "$STACK_ROBOT_SIM_PID" 2>/dev/null ||
		{ echo "stack: advee-robot-sim exited:" >&2; tail -5 "$STACK_RUN/robot-sim.log" >&2; return 1; }
}

# stack_wait_run SECONDS [MODULE...]: every module (default STACK_MODULES)
# announced RUN within SECONDS; the ones that did not are in
# $STACK_RUN/not-running. A shell loop, not awk: mawk reads a pipe in blocks
# and would see the lines only when advee-lcmctl exits.
stack_wait_run() {
	local secs=$1 m
	shift
	local -A need=()
	for m in ${*:-$STACK_MODULES}; do need[$m]=1; done
	local ch mod st rest
	while read -r ch mod st rest; do
		[ "$st" = state=RUN ] && unset "need[${mod#module=}]"
		[ ${#need[@]} = 0 ] && break
	done < <("$LCMCTL" echo --timeout "$secs" CM_DATA_STATE)
	echo "${!need[@]}" >"$STACK_RUN/not-running"
	[ ${#need[@]} = 0 ]
}

# stack_up [ROBOT-SIM ARGS...]: bring the whole stack up; non-zero (with the
# reason on stderr) when any part does not come up.
stack_up() {
	STACK_RUN=$(mktemp -d "${VMTEST_SCRATCH:-/tmp}/stack.XXXXXX")
	trap stack_down EXIT
	local p
	for p in "$RS485_SIM" "$ROBOT_SIM" "$WATCHDOG" "$DRIVER_AUX" "$DRIVER_RS485" "$DRIVER_POWER" "$LCMCTL"; do
		[ -x "$p" ] || { echo "stack: $p not built (make userland)" >&2; return 1; }
	done
	lcm_net_up || { echo "stack: cannot set up loopback multicast" >&2; return 1; }
	stack_kernel_up || return 1
	stack_conf || return 1

	stack_bg rs485-sim "$RS485_SIM" -c "$STACK_RUN/conf/boards.yaml" --control "$STACK_RUN/rs485-sim.sock"
	STACK_RS485_SIM_PID=$STACK_LAST_PID
	wait_line "$STACK_RUN/rs485-sim.log" '^advee-rs485-sim: ready' 20 >/dev/null ||
		{ echo "stack: advee-rs485-sim did not start:" >&2; tail -5 "$STACK_RUN/rs485-sim.log" >&2; return 1; }

	stack_robot_up "$@" || return 1

	stack_bg watchdog "$WATCHDOG" --config "$STACK_RUN/conf/watchdog.yaml"
	STACK_WATCHDOG_PID=$STACK_LAST_PID
	if ! stack_wait_run 30; then
		echo "stack: not in RUN after 30 s: $(cat "$STACK_RUN/not-running")" >&2
		tail -15 "$STACK_RUN/watchdog.log" >&2
		return 1
	fi
	stack_log "up: $STACK_MODULES (robot drives: $STACK_ROBOT_DRIVES)"
}

# stack_drive FILE [ARGS...]: advee-drive-script plays FILE onto LL_CMD_MOTION.
stack_drive() {
	[ -x "$DRIVE_SCRIPT" ] || { echo "stack: $DRIVE_SCRIPT not built" >&2; return 1; }
	local file=$1
	shift
	stack_bg drive-script "$DRIVE_SCRIPT" --path "$file" "$@"
	STACK_DRIVE_PID=$STACK_LAST_PID
}

# stack_world_at X Y HEADING_RAD: what the robot's sensors see standing at
# that pose in the same world (advee-robot-sim's own model, --print block of one
# simulated second: srf_m, ir_m, beacons lines), for comparing with what
# came through the simulators, the kernel and the daemons.
stack_world_at() {
	local robot=$STACK_RUN/robot-at.yaml
	awk -v x="$1" -v y="$2" -v h="$3" '
		/^start:/ { printf "start: {x: %s, y: %s, heading_deg: %.6f}\n", x, y, h * 180 / 3.14159265358979; next }
		{ print }' "$ROBOTSIM_CONF/robot.yaml" >"$robot"
	printf '0 0\n' | "$ROBOT_SIM" --map "$ROBOTSIM_CONF/room.yaml" --robot "$robot" --drive-input - \
		--fast --duration 1 --print
}

# Odometry tolerance: robotsim's own tick odometry closes this path to
# 0.02 m / 0.08 deg at 4 Hz (docs/robotsim.md); through the stack, with every
# tick counted, 0.003 m / 0.02 deg were measured (the robot drove a
# different path then: the drives' timing under TCG shapes it). 0.1 m and
# 1 degree leave room for a command change inside a longer poll interval.
# Ticks lost in a poll gap (checked on their own below) fail it, as they
# should: the estimate is then wrong.
STACK_POS_TOL=0.1 STACK_HEAD_TOL_DEG=1
# stack_path_points OUT: 6 TAP points on a listener's output (advee-stack-listen
# lines) over a driven path: the robot moved and followed the commanded 0.5 m/s,
# stands still at the end, LL_DATA_ODO counted every tick, and the odometry
# integrated from the true start pose ends within the tolerances of the true
# end pose (SIM_DATA_POSE). Sets x1 y1 h1 (the true end pose) and dist.
stack_path_points() {
	local OUT=$1 first last x0 y0 h0 xo yo ho n_odo perr herr vmax ticks enc
	first=$(grep -m1 '^SIM_DATA_POSE ' "$OUT")
	last=$(grep '^SIM_DATA_POSE ' "$OUT" | tail -1)
	tap_diag "true start: $first"
	tap_diag "true end:   $last"
	x0=$(field "$first" x) y0=$(field "$first" y) h0=$(field "$first" heading)
	x1=$(field "$last" x) y1=$(field "$last" y) h1=$(field "$last" heading)
	dist=$(awk -v a="$x0" -v b="$y0" -v c="$x1" -v d="$y1" 'BEGIN { printf "%.3f", sqrt((c-a)^2 + (d-b)^2) }')
	tap_ok "the robot moved: the true end pose is $dist m from the start (> 2 m)" \
		awk -v d="$dist" 'BEGIN { exit !(d > 2) }'
	vmax=$(grep '^SIM_DATA_POSE ' "$OUT" | tr ' ' '\n' | sed -n 's/^speed=//p' | sort -g | tail -1)
	tap_ok "the drives followed LL_CMD_MOTION: top true speed $vmax m/s (0.5 commanded, +-0.02)" \
		close_to "$vmax" 0.5 0.02
	tap_ok "the robot stands still after the path (true speed 0)" close_to "$(field "$last" speed)" 0 0.001

	# Odometry: every LL_DATA_ODO interval as one arc, from the true start pose.
	read -r xo yo ho n_odo < <(grep '^LL_DATA_ODO ' "$OUT" | awk -v x="$x0" -v y="$y0" -v h="$h0" '
		{
			for (i = 1; i <= NF; i++) { split($i, kv, "="); f[kv[1]] = kv[2] }
			d = f["speed"] * f["interval"]; dh = f["yaw"] * f["interval"]
			x += d * cos(h + dh / 2); y += d * sin(h + dh / 2); h += dh; n++
		}
		END { printf "%.4f %.4f %.4f %d\n", x, y, h, n }')
	read -r perr herr < <(awk -v a="$xo" -v b="$yo" -v c="$x1" -v d="$y1" -v h="$ho" -v g="$h1" 'BEGIN {
		pi = 3.14159265358979; e = h - g; while (e > pi) e -= 2 * pi; while (e < -pi) e += 2 * pi
		printf "%.3f %.2f\n", sqrt((c-a)^2 + (d-b)^2), (e < 0 ? -e : e) * 180 / pi }')
	tap_diag "odometry ($n_odo LL_DATA_ODO): x=$xo y=$yo heading=$ho; truth x=$x1 y=$y1 heading=$h1"
	ticks=$(grep '^LL_DATA_ODO ' "$OUT" | tr ' ' '\n' | awk -F= '$1 == "ticks_left" { l += $2 } $1 == "ticks_right" { r += $2 } END { print l + 0, r + 0 }')
	enc="$(field "$last" ticks_left) $(field "$last" ticks_right)"
	tap_ok "LL_DATA_ODO counted every encoder tick (odometry $ticks, encoders $enc, +-2 each; a poll gap > 1 s restarts the baseline and loses ticks)" \
		awk -v a="$ticks" -v b="$enc" 'BEGIN { split(a, x, " "); split(b, y, " "); d1 = x[1] - y[1]; d2 = x[2] - y[2]; exit !(d1 * d1 <= 4 && d2 * d2 <= 4) }' 
	tap_diag "odometry error after $dist m from the start: $perr m, $herr degrees"
	tap_ok "odometry position within $STACK_POS_TOL m of the truth ($perr m)" awk -v e="$perr" -v t="$STACK_POS_TOL" 'BEGIN { exit !(e <= t) }'
	tap_ok "odometry heading within $STACK_HEAD_TOL_DEG degrees of the truth ($herr)" awk -v e="$herr" -v t="$STACK_HEAD_TOL_DEG" 'BEGIN { exit !(e <= t) }'
}

# stack_sim COMMAND...: one advee-rs485-sim control command, its reply on stdout.
stack_sim() { "$RS485_SIM" --control "$STACK_RUN/rs485-sim.sock" --send "$*"; }

# stack_logs [LINES]: the tail of every log, as TAP diagnostics.
stack_logs() {
	local f
	for f in "$STACK_RUN"/*.log "$STACK_RUN"/log/*/*.log; do
		[ -s "$f" ] || continue
		echo "# --- ${f#"$STACK_RUN"/}"
		tail -n "${1:-10}" "$f" | sed 's/^/#   /'
	done
}

stack_down() {
	local p
	# The supervisor first: it stops its modules (SIGTERM, then SIGKILL).
	if [ -n "$STACK_WATCHDOG_PID" ]; then
		kill -TERM "$STACK_WATCHDOG_PID" 2>/dev/null
		wait "$STACK_WATCHDOG_PID" 2>/dev/null
		STACK_WATCHDOG_PID=
	fi
	for p in $STACK_PIDS; do kill -TERM "$p" 2>/dev/null; done
	for p in $STACK_PIDS; do wait "$p" 2>/dev/null; done
	STACK_PIDS=
	if [ "$STACK_VCAN_ADDED" = 1 ]; then
		ip link del vcan0 2>/dev/null
		STACK_VCAN_ADDED=0
	fi
	# n_rs485 stays busy until the ttys are closed: the daemons are gone now.
	for p in $STACK_LOADED; do modprobe -r "$p" 2>/dev/null; done
	modprobe -r ts7800_fpga can_raw can 2>/dev/null
	STACK_LOADED=
	lcm_net_down
	if [ "$STACK_DEBUGFS_MOUNTED" = 1 ]; then
		umount /sys/kernel/debug 2>/dev/null
		STACK_DEBUGFS_MOUNTED=0
	fi
	return 0
}
