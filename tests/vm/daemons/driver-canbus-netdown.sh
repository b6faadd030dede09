#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# driver_canbus under advee-watchdog loses its interface: `ip link set vcan0
# down` -> the CAN loop's ENETDOWN is reported on CM_DATA_ERROR (fatal,
# number 35 = the exit code 0x23) and the module exits 0x23 instead of dying
# in std::terminate; the supervisor reports "device error 3" and restarts it;
# with vcan0 up again a new instance boots both drives.
. "$(dirname "$0")/lib.sh"

canbus_up "$DRIVER_CANBUS" "$PROBE" "$LCMCTL" "$WATCHDOG"

tap_plan 6

canbus_sims_up
canbus_config "$SCR/canbus.yaml"
cat >"$SCR/watchdog.yaml" <<EOC
module: {name: watchdog, print_severity: notice}
supervisor:
  term_grace_s: 1
  startup_grace_s: 20
  backoff: {initial_s: 0.5, max_s: 2, factor: 2, stable_s: 2}
modules:
  - name: driver_canbus
    path: $DRIVER_CANBUS
    args: [--config, $SCR/canbus.yaml]
EOC

listen_bg "$SCR/all.out" LL_DATA_DRIVES CM_DATA_ERROR
bg "$WATCHDOG" --config "$SCR/watchdog.yaml"
p1=$(state_pid driver_canbus RUN 20)
wait_line "$SCR/all.out" "^LL_DATA_DRIVES .* node1=operation_enabled .* node2=operation_enabled" 30 >/dev/null
tap_ok "supervised driver_canbus (pid $p1) runs both drives" test -n "$p1" -a "$?" = 0

ip link set "$IF" down
wait_line "$SCR/all.out" "^CM_DATA_ERROR .* module=driver_canbus number=35 .* fatal=1 " 10 >/dev/null
tap_ok "vcan0 down: fatal error 35 (exit 0x23) reported on CM_DATA_ERROR" test "$?" = 0
tap_diag "$(grep '^CM_DATA_ERROR .* module=driver_canbus number=35 ' "$SCR/all.out" | head -1)"
wait_line "$SCR/all.out" "^CM_DATA_ERROR .* module=watchdog .* text=driver_canbus:_ended_after.*device_error_3" 10 >/dev/null
tap_ok "the supervisor saw exit 0x23 (device error 3), not a signal" test "$?" = 0
tap_diag "$(grep '^CM_DATA_ERROR .* module=watchdog .*ended_after' "$SCR/all.out" | head -1)"
tap_ok "no instance died of a signal (std::terminate would be SIGABRT)" \
	sh -c "! grep -q '^CM_DATA_ERROR .* module=watchdog .*killed_by' '$SCR/all.out'"

ip link set "$IF" up
# The simulators use the same interface and lose it too: start again the
# ones that ended (their exits are not what this test is about).
for n in epos icla; do
	eval "p=\$SIM_$n"
	if ! kill -0 "$p" 2>/dev/null; then
		tap_diag "simulator $n ended when vcan0 went down; started again"
		if [ "$n" = epos ]; then sim_drive epos -n 1 -p epos; else sim_drive icla -n 2 -p icla; fi
	fi
done
p2=$("$LCMCTL" echo --timeout 30 CM_DATA_STATE | first_other driver_canbus "$p1" | head -1)
tap_ok "restarted by the supervisor ($p2)" test -n "$p2"
listen_bg "$SCR/after.out" LL_DATA_DRIVES
wait_line "$SCR/after.out" "^LL_DATA_DRIVES .* node1=operation_enabled .* node2=operation_enabled" 40 >/dev/null
tap_ok "vcan0 up again: the new instance boots both drives" test "$?" = 0
grep '^CM_DATA_ERROR .* module=watchdog ' "$SCR/all.out" | sed 's/^/# /' | head -10
tap_finish
