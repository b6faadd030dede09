#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# advee-diagnostic-center's terminal UI driven in tmux (send-keys, capture-pane)
# against the whole stack (lib.sh): every module listed in RUN; arrow keys
# change the motion command, on screen and on LCM (LL_CMD_MOTION repeated
# while driving manually); a module stopped with SIGSTOP shows up restarted
# (new pid, restart count); the module control view terminates and restarts
# a module; the errors view shows the supervisor's report; the layout follows
# a resize; quitting during a manual drive sends a zero command and exits 0.
. "$(dirname "$0")/lib.sh"
stack_require diagnostic-center

tap_plan 17
if ! stack_up; then
	tap_diag "the stack did not come up"
	stack_logs 20
	exit 1
fi
tap_diag "modules: $STACK_MODULES; robot drives: $STACK_ROBOT_DRIVES"

TSOCK=$STACK_RUN/tmux.sock
DC_EXIT=$STACK_RUN/dc.exit
tmux_() { tmux -S "$TSOCK" "$@"; }
screen() { tmux_ capture-pane -p -t dc; }
keys() { tmux_ send-keys -t dc "$@"; }
# Waits are deadlines in seconds (wait_until, tests/lib/wait.sh), not
# iteration counts: under TCG one capture-pane costs a large part of a second.
# wait_screen ERE SECONDS: true once the screen has a line matching ERE.
on_screen() { screen | grep -qE -- "$1"; }
wait_screen() {
	wait_until "$2" on_screen "$1" && return 0
	screen | sed 's/^/#| /'
	return 1
}
# all_run PREFIX-ERE: every supervised module has a row "PREFIX<name> ... RUN".
all_run() {
	local m s
	s=$(screen)
	for m in $STACK_MODULES; do
		grep -qE "^$1$m +RUN " <<<"$s" || { echo "$m not in RUN on screen"; printf '%s\n' "$s" | sed 's/^/| /'; return 1; }
	done
}
wait_all_run() { wait_until "$2" all_run "$1" >/dev/null || all_run "$1"; }
# row NAME: the module view's row of NAME, without the selection mark:
# "name state pid age phase restarts exit next".
row() { screen | sed -n "s/^[> ] \($1 .*\)/\1/p" | head -1; }
# observe SECONDS: what another LCM client sees, as advee-diagnostic-center's text summary.
observe() { "$DIAGNOSTIC_CENTER" --text --for "$1" --period 0.5s; }
cleanup_tui() {
	tmux_ kill-server 2>/dev/null
	stack_down
}
trap cleanup_tui EXIT

tmux_ new-session -d -s dc -x 80 -y 24 \
	"$DIAGNOSTIC_CENTER 2>$STACK_RUN/dc.err; echo \$? >$DC_EXIT; sleep 600"
tmux_ set-option -g window-size manual >/dev/null

# 1-2: the summary and the module view list every module in RUN.
tap_ok "summary view lists every module in RUN ($STACK_MODULES)" wait_all_run "" 15
keys 3
tap_ok "module view lists every module in RUN" wait_all_run "[> ] " 5

# 3-7: arrow keys drive.
keys 1
# The observers run until what they must see has come (their start-up under
# TCG takes seconds: a fixed window would be spent before the keys).
observe 60 >"$STACK_RUN/obs-drive.txt" &
OBS=$!
"$PROBE" listen 60 LL_CMD_MOTION >"$STACK_RUN/probe-motion.txt" &
PRB=$!
wait_lcm_listening "$OBS" 20 && wait_lcm_listening "$PRB" 20 || tap_diag "the observers did not subscribe"
keys Up Up Left
tap_ok "up, up, left: the title shows MANUAL +0.20 m/s +5 deg" \
	wait_screen 'MANUAL \+0\.20 m/s \+5 deg' 5
tap_ok "the summary's command line (read back from LCM) shows v +0.20 steer +5.0" \
	wait_screen '^Command +v \+0\.20 m/s steer +\+5\.0 by us' 5
wait_line "$STACK_RUN/obs-drive.txt" 'cmd_v=0.200 cmd_steer=0.087 .*cmd_from=diagnostic_center' 10 >/dev/null
# Repeated, not only sent per key (3 keys): 8 messages of 0.2 m/s. The exact
# 10 Hz schedule is a unit test (Controller.ArrowsDriveAndCommandsRepeatAtTenHertz);
# the interval and the longest gap are reported, since TCG stalls the guest.
wait_lines "$STACK_RUN/probe-motion.txt" '^LL_CMD_MOTION .* speed=0\.2000 ' 8 10 >/dev/null
kill "$OBS" "$PRB" 2>/dev/null
wait "$OBS" "$PRB" 2>/dev/null
tap_diag "the summary view while driving:"
screen | sed 's/^/#| /'
tap_ok "another LCM client sees LL_CMD_MOTION 0.2 m/s, 0.087 rad from diagnostic_center (its LCM name)" \
	grep -q 'cmd_v=0.200 cmd_steer=0.087 .*cmd_from=diagnostic_center' "$STACK_RUN/obs-drive.txt"
times=$(sed -n 's/^LL_CMD_MOTION t=\([0-9.]*\) .* speed=0\.2000 .*/\1/p' "$STACK_RUN/probe-motion.txt")
n=$(printf '%s\n' "$times" | grep -c .)
span=$(printf '%s\n' "$times" | awk 'NR == 1 { a = $1 } { b = $1 } NR > 1 && $1 - p > g { g = $1 - p } { p = $1 } END { printf "%.2f s, longest gap %.3f s", b - a, g + 0 }')
tap_diag "LL_CMD_MOTION of 0.2 m/s while driving manually: $n messages over $span"
tap_ok "LL_CMD_MOTION repeats while driving manually ($n of 0.2 m/s after 3 keys, over $span)" test "$n" -ge 8
keys Right Right Down Down Down
wait_screen 'MANUAL -0\.10 m/s -5 deg' 5 >/dev/null
observe 1 >"$STACK_RUN/obs-reverse.txt"
keys Space
wait_screen 'MANUAL \+0\.00 m/s \+0 deg' 5 >/dev/null
observe 1 >"$STACK_RUN/obs-stop.txt"
reverse_then_stop() {
	grep -q 'cmd_v=-0.100 cmd_steer=-0.087' "$STACK_RUN/obs-reverse.txt" &&
		grep -q 'cmd_v=0.000 cmd_steer=0.000' "$STACK_RUN/obs-stop.txt"
}
tap_ok "right, right, down x3 -> -0.1 m/s, -5 deg on LCM; space -> 0, 0" reverse_then_stop
keys m
wait_screen '^manual driving off' 5 >/dev/null

# 8-10: SIGSTOP of driver_aux -> the supervisor replaces it; the module view shows it.
keys 3
wait_all_run "[> ] " 5 >/dev/null
set -- $(row driver_aux)
old_pid=$3
old_restarts=$6
[ "$old_restarts" = - ] && old_restarts=0
tap_diag "driver_aux before: $*"
kill -STOP "$old_pid"
t0=$(date +%s%N)
restarted() {
	set -- $(row driver_aux)
	[ "$2" = RUN ] && [ "$3" != "$old_pid" ] && [ "$3" -gt 0 ] 2>/dev/null && [ "$6" != - ] &&
		[ "$6" -gt "$old_restarts" ]
}
wait_until 25 restarted
dt=$(( ($(date +%s%N) - t0) / 1000000 ))
set -- $(row driver_aux)
tap_diag "driver_aux after SIGSTOP ($dt ms): $*"
tap_ok "stopped driver_aux shows up restarted: RUN, new pid ($old_pid -> $3), restarts $old_restarts -> $6" restarted
tap_ok "the stopped instance is gone" sh -c "! kill -0 $old_pid 2>/dev/null"
keys 2
tap_ok "errors view shows the supervisor's report on driver_aux" \
	wait_screen 'watchdog +warning .*driver_aux' 5

# 11-12: module control: TERMINATE keeps driver_rs485b down, RUN starts it again.
keys 3
set -- $(row driver_rs485b)
rs_pid=$3
# Select it: to the top, then down to its position in the (sorted) list.
for ((i = 0; i < 10; i++)); do keys Up; done
# (rows from the 4th screen line: the 3rd is the column header)
idx=$(screen | sed -n '4,$ s/^[> ] \([a-z_0-9]*\) .*/\1/p' | grep -nx driver_rs485b | cut -d: -f1)
tap_diag "driver_rs485b is row $idx of the module list"
for ((i = 1; i < idx; i++)); do keys Down; done
if ! wait_screen '^> driver_rs485b ' 5 >/dev/null; then
	# Never send TERMINATE to whatever else is selected (the supervisor!).
	tap_diag "could not select driver_rs485b"
	exit 1
fi
keys t
wait_screen 'press t again to TERMINATE driver_rs485b' 5 >/dev/null
keys t
tap_ok "t t in the module view: driver_rs485b terminated and kept DOWN" \
	wait_screen '^> driver_rs485b .* DOWN ' 15
keys r
rs_new() {
	set -- $(row driver_rs485b)
	[ "$2" = RUN ] && [ "$3" != "$rs_pid" ] && [ "$5" = RUNNING ]
}
wait_until 20 rs_new
tap_ok "r: driver_rs485b runs again with a new pid ($rs_pid -> $(row driver_rs485b | awk '{ print $3 }'))" rs_new

# 13-14: resize to 100x30 and back to 80x24.
keys 1
big_layout() {
	local s
	s=$(screen)
	printf '%s\n' "$s" | head -1 | grep -q 'Advee diagnostic centre' &&
		printf '%s\n' "$s" | sed -n 30p | grep -q 'q quit'
}
small_layout() {
	local s
	s=$(screen)
	printf '%s\n' "$s" | sed -n 24p | grep -q 'q quit' &&
		printf '%s\n' "$s" | grep -q '^driver_aux  *RUN '
}
tmux_ resize-window -t dc -x 100 -y 30
tap_ok "resized to 100x30: the full title, the help line on line 30" wait_until 5 big_layout
tmux_ resize-window -t dc -x 80 -y 24
tap_ok "back to 80x24: the help line on line 24, the module rows" wait_until 5 small_layout

# 15-17: quit in the middle of a manual drive.
keys Up
wait_screen 'MANUAL \+0\.10' 5 >/dev/null
observe 60 >"$STACK_RUN/obs-quit.txt" &
OBS=$!
wait_lcm_listening "$OBS" 20 || tap_diag "the observer did not subscribe"
wait_line "$STACK_RUN/obs-quit.txt" '^motion cmd_v=0.100 ' 10 >/dev/null
keys q
wait_until 5 test -s "$DC_EXIT"
tap_is "q: advee-diagnostic-center exits 0" "$(cat "$DC_EXIT" 2>/dev/null)" 0
# Two more summaries (0.5 s apart) after the exit: the last command is in.
wait_lines "$STACK_RUN/obs-quit.txt" '^motion ' $(($(grep -c '^motion ' "$STACK_RUN/obs-quit.txt") + 2)) 10 >/dev/null
kill "$OBS" 2>/dev/null
wait "$OBS" 2>/dev/null
last=$(grep '^motion' "$STACK_RUN/obs-quit.txt" | tail -1)
tap_diag "last motion seen: $last"
tap_ok "its last LL_CMD_MOTION is a stop (0, 0)" \
	grep -q 'cmd_v=0.000 cmd_steer=0.000 .*cmd_from=diagnostic_center' <<<"$last"
# A fresh observer, subscribed, over an observation window of 1.5 s: the
# summaries it prints show no command at all.
observe 60 >"$STACK_RUN/obs-after-quit.txt" &
OBS=$!
wait_lcm_listening "$OBS" 20 || tap_diag "the observer did not subscribe"
sleep 1.5	# an observation window (15 periods of the 10 Hz repeat), not a synchronisation
wait_lines "$STACK_RUN/obs-after-quit.txt" '^motion ' 2 10 >/dev/null
kill "$OBS" 2>/dev/null
wait "$OBS" 2>/dev/null
none_follows() {
	[ "$(grep -c '^motion ' "$STACK_RUN/obs-after-quit.txt")" -ge 2 ] &&
		! grep '^motion ' "$STACK_RUN/obs-after-quit.txt" | grep -qv '^motion cmd_v=none'
}
tap_ok "and none follows (summaries over 1.5 s show no command)" none_follows
[ -s "$STACK_RUN/dc.err" ] && tap_diag "stderr: $(cat "$STACK_RUN/dc.err")"
tap_finish
