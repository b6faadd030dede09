#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# advee-watchdog supervising driver_aux (on the simulated board) and a test
# module: SIGSTOP of driver_aux -> ended within 3 s and replaced; SIGKILL
# -> restarted; CM_CMD_STATE TERMINATE keeps it down, RUN starts it again;
# with the chip gone driver_aux exits 0x21 and the restarts back off (0,
# 0.5, 1, 2 s); SIGTERM of the supervisor ends every module.
. "$(dirname "$0")/lib.sh"
trap modules_cleanup EXIT

tap_plan 12
lcm_net_up || { tap_diag "cannot set up loopback multicast"; exit 1; }
board_up || { tap_diag "cannot bring up the simulated board"; exit 1; }
aux_config "$VMTEST_SCRATCH/driver_aux.yaml" 1
# A run this long counts as stable (the next restart is immediate). Well
# above what a failing start of driver_aux takes: 2.1 s under load once,
# counted as stable at 2 s (CI of cadd873: "got 0 0 500 1000").
STABLE_S=5
cat >"$VMTEST_SCRATCH/watchdog.yaml" <<EOC
module: {name: watchdog, print_severity: notice, log_root: $VMTEST_SCRATCH/log}
supervisor:
  term_grace_s: 1
  backoff: {initial_s: 0.5, max_s: 4, factor: 2, stable_s: $STABLE_S}
modules:
  - name: driver_aux
    path: $DRIVER_AUX
    args: [--config, $VMTEST_SCRATCH/driver_aux.yaml]
  - name: tmod
    path: $TEST_MODULE
    args: [tmod]
EOC

bg "$WATCHDOG" --config "$VMTEST_SCRATCH/watchdog.yaml"
WD=$LAST_BG
p1=$(state_pid driver_aux RUN 20)
tap_ok "driver_aux started and announces RUN" test -n "$p1"
t=$(echo_msgs 1 3 LL_DATA_TEMPERATURE)
tap_is "supervised driver_aux publishes the simulated temperature" "$(field "$t" temp1)" 31.500
logdir=$(ls -d "$VMTEST_SCRATCH"/log/*/ 2>/dev/null | head -1)
tap_ok "a per-run log directory with the modules' logs" test -s "$logdir/driver_aux.log"

# other_instance FILE OLDPID: the first CM_DATA_STATE of driver_aux in FILE
# sent by a pid other than OLDPID (empty if none yet).
other_instance() {
	first_other driver_aux "$2" <"$1" 2>/dev/null
}
has_other() { [ -n "$(other_instance "$1" "$2")" ]; }
ST=$VMTEST_SCRATCH/states.out

# kill -STOP: dead after dead_after_s (2 s, the default) without
# announcement, SIGTERM+SIGCONT, restart. The functional limit is the
# supervisor's: the stopped instance is gone within 2 s + 1 s of margin;
# the time until the new instance announces RUN (process start-up under
# TCG included) is reported.
bg "$LCMCTL" echo --timeout 60 CM_DATA_STATE >"$ST"
E=$LAST_BG
wait_lcm_listening "$E" 20
uptime_cs
t0=$UPTIME_CS
kill -STOP "$p1"
wait_gone "$p1" 10
gone=$?
uptime_cs
gone_ms=$(((UPTIME_CS - t0) * 10))
wait_until 10 has_other "$ST" "$p1"
uptime_cs
line=$(other_instance "$ST" "$p1")
tap_diag "after SIGSTOP: old instance gone after $gone_ms ms, new one announced after $(((UPTIME_CS - t0) * 10)) ms ($line)"
tap_ok "a stopped driver_aux is ended within 3 s ($gone_ms ms)" test "$gone" = 0 -a "$gone_ms" -lt 3000
tap_ok "and replaced: a new instance announces itself" test -n "$line"
p2=$(field "$line" pid)

# kill -9: restarted.
t0=$UPTIME_CS
kill -9 "$p2"
wait_until 10 has_other "$ST" "$p2"
uptime_cs
line=$(other_instance "$ST" "$p2")
tap_diag "restart after SIGKILL: $(((UPTIME_CS - t0) * 10)) ms ($line)"
tap_ok "a killed driver_aux is restarted" test -n "$line"
p3=$(field "$line" pid)
kill "$E"

# TERMINATE keeps it down; tmod keeps running; RUN brings it back.
"$LCMCTL" state driver_aux TERMINATE
wait_gone "$p3" 10
tap_ok "after TERMINATE the process is gone" sh -c "! kill -0 $p3 2>/dev/null"
# An observation window: a restart (backoff from 0.5 s, start-up under TCG
# up to 2 s) would announce within it.
n=$(echo_msgs 0 3 CM_DATA_STATE | grep -c 'module=driver_aux')
tap_is "and nothing announces driver_aux for 3 s" "$n" 0
"$LCMCTL" state driver_aux RUN
p4=$(state_pid driver_aux RUN 10)
uptime_cs
p4_seen=$UPTIME_CS
tap_ok "RUN starts driver_aux again" test -n "$p4" -a "$p4" != "$p3"

# The chip goes away: driver_aux ends with 0x21 at each start, restarts back off.
PH=$VMTEST_SCRATCH/phases.out
bg "$LCMCTL" echo --timeout 60 CM_DATA_MODULES >"$PH"
E=$LAST_BG
wait_lcm_listening "$E" 20
# p4 runs longer than STABLE_S before it is killed: it started before the
# test saw it (p4_seen), so that much time since then is enough.
longer_ago_than() {	# longer_ago_than UPTIME_CS SECONDS
	uptime_cs
	[ $((UPTIME_CS - $1)) -gt $(($2 * 100)) ]
}
modprobe -r max6615
wait_until $((STABLE_S + 10)) longer_ago_than "$p4_seen" "$STABLE_S" ||
	tap_diag "no stable run of driver_aux (pid $p4) before the kill"
kill "$p4"		# a stable run: restarted at once; from then on every start fails
wait_lines "$PH" 'target=driver_aux phase=TERMINATED' 4 30 >/dev/null
kill "$E"
phases=$(grep 'target=driver_aux phase=TERMINATED' "$PH")
tap_diag "$phases"
codes=$(printf '%s\n' "$phases" | sed -n 's/.* exit=\([0-9]*\) .*/\1/p' | tail -n +2 | sort -u)
tap_is "every failed start exits with 0x21 (33)" "$codes" 33
delays=$(printf '%s\n' "$phases" | sed -n 's/.*next_start_ms=\([0-9]*\).*/\1/p' | head -4 |
	awk '{ printf "%s%d", (NR > 1 ? " " : ""), int(($1 + 50) / 100) * 100 }')
tap_is "restarts back off: 0, 500, 1000, 2000 ms" "$delays" "0 500 1000 2000"

# The supervisor's SIGTERM ends its modules.
tp=$(state_pid tmod RUN 3)
kill "$WD"
wait "$WD"
rc=$?
BG_PIDS=
tap_ok "advee-watchdog exits 0 on SIGTERM and tmod (pid $tp) is gone" \
	sh -c "[ $rc = 0 ] && [ -n '$tp' ] && ! kill -0 '$tp' 2>/dev/null"
tap_finish
