#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# advee-rs485-sim as a program: configuration errors name line and field, the
# control socket answers and refuses, SIGTERM stops it cleanly with counters,
# a missing wire is a clear error. (The protocol itself: drivers.sh.)
. "$(dirname "$0")/common.inc"

rs485_setup "$SIMBIN/advee-rs485-sim"
tap_plan 11
S=$SIMBIN/advee-rs485-sim

tap_ok "--check accepts the suite's configuration" "$S" --check -c "$SUITE/stack.yaml"
printf 'buses:\n  - name: a\n    wire: /dev/ts7800-sim/uart0\n    devices:\n      - type: sd1\n        address: 0x10\n        srf_cm: [1]\n' >"$SCR/bad.yaml"
out=$("$S" --check -c "$SCR/bad.yaml" 2>&1); rc=$?
sed "s/^/# /" <<<"$out"
tap_ok "a typo in a key: exit 1, file:line and field named" \
	bash -c '[ "$1" = 1 ] && [[ "$2" == *"bad.yaml:7:"*"buses[0].devices[0].srf_cm: unknown key"* ]]' _ "$rc" "$out"
printf 'buses:\n  - {name: a, wire: /dev/ts7800-sim/uart0, devices: [{type: so1, address: 0x20}, {type: sd1, address: 0x20}]}\n' >"$SCR/dup.yaml"
out=$("$S" --check -c "$SCR/dup.yaml" 2>&1); rc=$?
tap_ok "two devices at one address: exit 1, named" \
	bash -c '[ "$1" = 1 ] && [[ "$2" == *"address already taken on bus a by so1@0x20"* ]]' _ "$rc" "$out"
printf 'buses:\n  - {name: a, wire: /dev/ts7800-sim/uart42, devices: [{type: so1, address: 0x20}]}\n' >"$SCR/nowire.yaml"
out=$(timeout 20 "$S" -c "$SCR/nowire.yaml" 2>&1); rc=$?
sed "s/^/# /" <<<"$out"
tap_ok "a wire that does not exist: exit 1, path named" \
	bash -c '[ "$1" = 1 ] && [[ "$2" == *"/dev/ts7800-sim/uart42: No such file"* ]]' _ "$rc" "$out"
tap_ok "--help documents configuration, control commands and exit status" \
	bash -c '"$1" --help | grep -q "^CONFIGURATION" && "$1" --help | grep -q "^CONTROL COMMANDS" && "$1" --help | grep -q "^EXIT STATUS"' _ "$S"

if ! start_sim "$SUITE/stack.yaml"; then
	echo "Bail out! advee-rs485-sim did not start"
	sed 's/^/# /' "$SCR/sim.err"
	exit 1
fi
tap_is "control 'list' names every simulated device" "$(sim list | tr '\n' ' ')" \
	"ok a:sd1@0x10 a:sd1@0x11 a:so1@0x20 b:sbs1@0x30 power:psc1@0x01 "
tap_is "control 'set' of a reading is shown back" "$(sim set a:sd1@0x11 srf 2 3.5 && sim show a:sd1@0x11 | cut -d' ' -f2-5)" \
	"ok
srf_cm 0 0 350"
out=$(sim set a:so1@0x20 speed 1 2); rc=$?
tap_ok "a wrong control command: 'error:' with the usage, exit 1" \
	bash -c '[ "$1" = 1 ] && [[ "$2" == "error: so1: set ticks"* ]]' _ "$rc" "$out"
tap_ok "an event from a board that sends none is refused" bash -c '! "$1" --control "$2" --send "event a:sd1@0x10 power"' _ "$S" "$CTL"
stop_sim; rc=$?
tap_is "SIGTERM: exit status 0" "$rc" 0
tap_ok "SIGTERM: counters of every device on stderr, control socket removed" \
	bash -c 'grep -q "advee-rs485-sim: power:psc1@0x01 requests=0" "$1" && [ ! -e "$2" ]' _ "$SCR/sim.err" "$CTL"
tap_finish
