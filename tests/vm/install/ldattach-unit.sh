#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# The command of the installed advee-rs485-ldattach@.service (instance
# ttyTSU0, as udev names it), without capabilities like the unit, attaches
# n_rs485 and keeps it attached while it
# runs in the foreground (what systemd supervises); stopping it (SIGTERM, as
# systemctl stop does) detaches the discipline again.
. "$(dirname "$0")/lib.sh"
pid=
cleanup() {
	[ -n "$pid" ] && kill "$pid" 2>/dev/null && wait "$pid" 2>/dev/null
	modprobe -r n_rs485 2>/dev/null
	modprobe -r ts7800_sim 2>/dev/null
	modprobe -r ts_uart ts7800_fpga 2>/dev/null
	cleanup_mounts
}
trap cleanup EXIT

tap_plan 5
tap_ok "staging install (system files)" stage_system
unit=$DEST/usr/lib/systemd/system/advee-rs485-ldattach@.service
cmd=$(sed -n 's/^ExecStart=//p' "$unit" | sed 's/%I/ttyTSU0/g; s/%i/ttyTSU0/g')
tap_diag "ExecStart for ttyTSU0: $cmd"
if ! modprobe ts_uart || ! modprobe ts7800_sim; then tap_diag "cannot load ts_uart + ts7800_sim"; exit 1; fi
wait_path /dev/ttyTSU0 5

# The discipline's module is autoloaded by TIOCSETD and referenced while attached.
refcnt() { cat /sys/module/n_rs485/refcnt 2>/dev/null || echo none; }
# The unit's empty CapabilityBoundingSet=: no capability survives the exec
# (the autoload of n_rs485 by TIOCSETD relies on CONFIG_LDISC_AUTOLOAD).
tap_diag "unit: $(grep '^CapabilityBoundingSet=' "$unit")"
setpriv --bounding-set=-all $cmd >"$VMTEST_SCRATCH/ldattach.log" 2>&1 &
pid=$!
attached() { [ "$(refcnt)" != none ] && [ "$(refcnt)" -gt 0 ]; }
wait_until 10 attached
tap_ok "n_rs485 attached (module referenced: refcnt $(refcnt))" test "$(refcnt)" != none -a "$(refcnt)" -gt 0
sleep 1	# an observation window: a daemonising ldattach would have exited by now
tap_ok "ldattach still runs in the foreground (Type=simple)" kill -0 "$pid"
kill -TERM "$pid"
wait "$pid" 2>/dev/null
pid=
wait_until 5 eval '[ "$(refcnt)" = 0 ]'
tap_is "stopping it detaches the discipline (refcnt 0)" "$(refcnt)" 0
tap_ok "n_rs485 unloads afterwards" modprobe -r n_rs485
tap_finish
