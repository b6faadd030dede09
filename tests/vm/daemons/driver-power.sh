#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# driver_power on the simulated BR-PSC1 (full-duplex link /dev/ttyTSU2):
# LL_DATA_POWER at 1 Hz with the status and currents the simulator was set
# to, LL_CMD_POWER switching an output (SET_PWR_STATUS seen by the board),
# the board's PAUSE events as LL_EVENT_STOP (latency from the simulator
# command reported, not asserted), the power-off command (a marker file,
# never systemctl), PAUSE of the module, a POWER event published while
# paused, SIGTERM exit 0. Every step waits for what it needs (module state,
# a message), never for a fixed time.
. "$(dirname "$0")/lib.sh"

daemons_rs485_up "$DRIVER_POWER"
tap_plan 12

MARK=$SCR/poweroff.marker
cat >"$SCR/power.yaml" <<EOC
module: {name: driver_power, print_severity: notice, send_severity: notice}
driver_power:
  bus: {device: /dev/ttyTSU2, timeout_ms: $TIMEOUT_MS, retries: 1}
  address: 0x01
  rate_hz: 1
  poweroff_command: [touch, $MARK]
  reboot_command: ["false"]
EOC
sim set psc1@0x01 status 0x0f >/dev/null
sim set psc1@0x01 current all none >/dev/null
sim set psc1@0x01 current 0 1.25 >/dev/null
sim set psc1@0x01 current 1 0.5 >/dev/null

bg "$DRIVER_POWER" --config "$SCR/power.yaml" 2>"$SCR/power.err"
P=$LAST_BG
wait_state driver_power 3 30 "$P" >/dev/null || sed 's/^/# power.err: /' "$SCR/power.err" | tail -20

# The rate: 5 messages at 1 Hz, counted over the interval they span.
listen_for 5 20 LL_DATA_POWER
p=$(last LL_DATA_POWER)
tap_diag "$p"
tap_rate "LL_DATA_POWER at 1 Hz" "$SCR/listen.out" LL_DATA_POWER 1 ||
	{ tap_diag "psc1: $(sim stats psc1@0x01)"; sed 's/^/# power.err: /' "$SCR/power.err" | tail -20; }
tap_is "status 0x0f: outputs 0..3 on, not paused" "$(field "$p" module) $(field "$p" outputs) $(field "$p" mask) $(field "$p" paused)" "driver_power 8 15 0"
tap_is "currents as set: 1.25 A, 0.5 A, no sensor -1" "$(field "$p" i0) $(field "$p" i1) $(field "$p" i2)" "1.250 0.500 -1.000"

# LL_CMD_POWER: output 5 on, output 1 off (0x0f -> 0x2d).
listen_bg "$SCR/cmd.out" LL_DATA_POWER
"$PROBE" power output 5 on
"$PROBE" power output 1 off
wait_line "$SCR/cmd.out" '^LL_DATA_POWER .* mask=45 ' 10 >/dev/null
listen_stop
tap_is "the board's status after the commands: 0x2d" "$(sim show psc1@0x01 | grep -o 'status=0x[0-9a-f]*')" "status=0x2d"
tap_is "LL_DATA_POWER shows it (mask 45)" "$(field "$(grep '^LL_DATA_POWER ' "$SCR/cmd.out" | tail -1)" mask)" 45

# send_us COMMAND: one control command, sent from python so that the time
# printed (CLOCK_REALTIME, us) is taken right before the datagram leaves
# (the advee-rs485-sim client takes about a second to start under TCG).
send_us() {
	python3 -c 'import socket, sys, time
s = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
s.bind("")
s.settimeout(5)
t = time.time_ns() // 1000
s.sendto(sys.argv[2].encode(), sys.argv[1])
s.recv(8192)
print(t)' "$CTL" "$1"
}

# PAUSE pressed on the board; released once LL_DATA_POWER has shown it.
listen_bg "$SCR/stop.out" LL_EVENT_STOP LL_DATA_POWER
t0=$(send_us "event psc1@0x01 pause 1 1")
wait_line "$SCR/stop.out" '^LL_DATA_POWER .* paused=1 ' 10 >/dev/null
send_us "event psc1@0x01 pause 0 0" >/dev/null
wait_line "$SCR/stop.out" '^LL_EVENT_STOP .* stop=0 ' 10 >/dev/null
listen_stop
s1=$(grep '^LL_EVENT_STOP ' "$SCR/stop.out" | head -1)
s2=$(grep '^LL_EVENT_STOP ' "$SCR/stop.out" | sed -n 2p)
tap_diag "$s1"
tap_diag "$s2"
tap_is "PAUSE engaged then released: two LL_EVENT_STOP (stop 1, 0; source PSC1)" \
	"$(field "$s1" stop) $(field "$s1" source) $(field "$s2" stop) $(field "$s2" source)" "1 0 0 0"
lat=$(( ($(field "$s1" rx_us) - t0) / 1000 ))
tap_diag "LL_EVENT_STOP received $lat ms after the control datagram was sent (simulator, wire, n_rs485, driver_power, LCM); driver publish to receive $(field "$s1" age_us) us"
# No timing assertion (TCG on a shared host: 18 and 68 ms seen); what must
# hold is that the stop is forwarded as an event, ahead of the status
# message that carries paused=1.
first_order() { awk '/^LL_EVENT_STOP .* stop=1 / && !e { e = NR } /^LL_DATA_POWER .* paused=1 / && !p { p = NR } END { exit !(e && p && e < p) }' "$SCR/stop.out"; }
tap_ok "LL_EVENT_STOP arrives before the LL_DATA_POWER that shows paused=1" first_order
tap_ok "LL_DATA_POWER reported paused=1 in between" grep -q '^LL_DATA_POWER .* paused=1' "$SCR/stop.out"

# Power-off runs the configured command (here: touch a marker).
"$PROBE" power poweroff
wait_path "$MARK" 10
tap_ok "LL_CMD_POWER POWEROFF ran the configured command" test -e "$MARK"

# PAUSE of the module: announced, then no LL_DATA_POWER over two periods.
"$LCMCTL" state driver_power PAUSE
wait_state driver_power 6 10 "$P" >/dev/null
listen_bg "$SCR/paused.out" LL_DATA_POWER
uptime_cs
t_paused=$UPTIME_CS
sleep 2.2	# an observation window (the absence of a message), not a synchronisation
uptime_cs
tap_is "module PAUSE: no LL_DATA_POWER in $(((UPTIME_CS - t_paused) * 10)) ms (1 Hz in RUN)" "$(grep -c '^LL_DATA_POWER ' "$SCR/paused.out")" 0

# A POWER event (the board's power sequence) is published at once, in every
# module state: while PAUSEd (no polls) it is the only way to LL_DATA_POWER.
sim set psc1@0x01 status 0x81 >/dev/null
sim event psc1@0x01 power >/dev/null
wait_line "$SCR/paused.out" '^LL_DATA_POWER .* mask=129 ' 10 >/dev/null
listen_stop
tap_is "POWER event while PAUSEd: one LL_DATA_POWER with the new status 0x81" \
	"$(grep -c '^LL_DATA_POWER ' "$SCR/paused.out") $(grep -c '^LL_DATA_POWER .* mask=129 ' "$SCR/paused.out")" "1 1"

kill -TERM "$P"
wait_exit "$P" 5
tap_is "SIGTERM: exit 0" "$?" 0
BG_PIDS=
tap_finish
