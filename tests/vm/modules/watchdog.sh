#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# advee-watchdog supervising driver_aux (on the simulated board) and a test
# module: SIGSTOP of driver_aux -> restarted within 3 s; SIGKILL -> restarted;
# CM_CMD_STATE TERMINATE keeps it down, RUN starts it again; with the chip
# gone driver_aux exits 0x21 and the restarts back off (0, 0.5, 1, 2 s);
# SIGTERM of the supervisor ends every module.
. "$(dirname "$0")/lib.sh"
trap modules_cleanup EXIT

tap_plan 12
net_setup || { tap_diag "cannot set up loopback multicast"; exit 1; }
board_up || { tap_diag "cannot bring up the simulated board"; exit 1; }
aux_config "$VMTEST_SCRATCH/driver_aux.yaml" 1
cat >"$VMTEST_SCRATCH/watchdog.yaml" <<EOC
module: {name: watchdog, print_severity: notice, log_root: $VMTEST_SCRATCH/log}
supervisor:
  term_grace_s: 1
  backoff: {initial_s: 0.5, max_s: 4, factor: 2, stable_s: 2}
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
p1=$(state_pid driver_aux RUN 10)
tap_ok "driver_aux started and announces RUN" test -n "$p1"
t=$(echo_msgs 1 3 LL_DATA_TEMPERATURE)
tap_is "supervised driver_aux publishes the simulated temperature" "$(field "$t" temp1)" 31.500
logdir=$(ls -d "$VMTEST_SCRATCH"/log/*/ 2>/dev/null | head -1)
tap_ok "a per-run log directory with the modules' logs" test -s "$logdir/driver_aux.log"

# kill -STOP: dead after 2 s without announcement, SIGTERM+SIGCONT, restart.
exec 3< <("$LCMCTL" echo --timeout 8 CM_DATA_STATE | first_other driver_aux "$p1")
sleep 0.3
t0=$(now_ms)
kill -STOP "$p1"
read -r -t 8 line <&3
exec 3<&-
dt=$(( $(now_ms) - t0 ))
tap_diag "restart after SIGSTOP: $dt ms ($line)"
tap_ok "a stopped driver_aux is replaced within 3 s (${dt} ms)" test -n "$line" -a "$dt" -lt 3000
p2=$(field "$line" pid)
tap_ok "the stopped instance is gone" sh -c "sleep 1; ! kill -0 $p1 2>/dev/null"

# kill -9: restarted.
exec 3< <("$LCMCTL" echo --timeout 8 CM_DATA_STATE | first_other driver_aux "$p2")
sleep 0.3
t0=$(now_ms)
kill -9 "$p2"
read -r -t 8 line <&3
exec 3<&-
dt=$(( $(now_ms) - t0 ))
tap_diag "restart after SIGKILL: $dt ms ($line)"
tap_ok "a killed driver_aux is restarted" test -n "$line"
p3=$(field "$line" pid)

# TERMINATE keeps it down; tmod keeps running; RUN brings it back.
"$LCMCTL" state driver_aux TERMINATE
sleep 1
n=$(echo_msgs 0 4 CM_DATA_STATE | grep -c 'module=driver_aux')
tap_is "after TERMINATE nothing announces driver_aux for 4 s" "$n" 0
tap_ok "and the process is gone" sh -c "! kill -0 $p3 2>/dev/null"
"$LCMCTL" state driver_aux RUN
p4=$(state_pid driver_aux RUN 5)
tap_ok "RUN starts driver_aux again" test -n "$p4" -a "$p4" != "$p3"

# The chip goes away: driver_aux ends with 0x21 at each start, restarts back off.
exec 3< <("$LCMCTL" echo --timeout 12 CM_DATA_MODULES | grep --line-buffered 'target=driver_aux phase=TERMINATED')
sleep 0.3
modprobe -r max6615
kill "$p4"		# restarted at once; from then on every start fails
sleep 9
phases=$(cat <&3)
exec 3<&-
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
