#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# robot-sim publishing to a real rs485-sim through its control socket: after
# 20 simulated seconds of the example path, the simulated boards hold the
# virtual robot's last frame (ticks, ranges, beacons). The boards' wires are
# /dev/null: no bus traffic, only the control path is under test.
# Usage: rs485sim_loop_test.sh RS485_SIM ROBOT_SIM CONF_DIR
set -euo pipefail
rs485_sim=$1 robot_sim=$2 conf=$3
dir=$(mktemp -d /tmp/robotsim-loop.XXXXXX)
sim_pid=
cleanup() { [ -n "$sim_pid" ] && kill "$sim_pid" 2>/dev/null; wait 2>/dev/null; rm -rf "$dir"; }
trap cleanup EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

ln -s /dev/null "$dir/wire-a"
ln -s /dev/null "$dir/wire-b"
cat > "$dir/sim.yaml" <<EOT
control: $dir/ctl.sock
buses:
  - {name: a, wire: $dir/wire-a, devices: [{type: sd1, address: 0x10}, {type: sd1, address: 0x11}, {type: so1, address: 0x20}]}
  - {name: b, wire: $dir/wire-b, devices: [{type: sbs1, address: 0x30}]}
EOT
"$rs485_sim" -c "$dir/sim.yaml" > "$dir/sim.log" 2>&1 &
sim_pid=$!
for _ in $(seq 50); do [ -S "$dir/ctl.sock" ] && break; sleep 0.1; done
[ -S "$dir/ctl.sock" ] || fail "rs485-sim did not start: $(cat "$dir/sim.log")"

"$robot_sim" -m "$conf/room.yaml" -r "$conf/robot.yaml" -p "$conf/square-path.yaml" \
  --rs485-control "$dir/ctl.sock" --fast --duration 20 --print > "$dir/print.log"
show() { "$rs485_sim" --control "$dir/ctl.sock" --send "show $1"; }

last=$(grep '^t=20.0 ' "$dir/print.log") || fail "no t=20.0 line in: $(cat "$dir/print.log")"
ticks=$(sed -n 's/.*ticks=\([0-9-]*\),\([0-9-]*\).*/\1 \2/p' <<< "$last")
so1=$(show a:so1@0x20)
[[ "$so1" == "ok ticks $ticks "* ]] || fail "so1 holds '$so1', robot-sim printed ticks $ticks"
left=${ticks% *}
[ "$left" -gt 20000 ] || fail "only $left ticks after 20 s of driving"

srf=$(sed -n '/^t=20.0 /{n;p}' "$dir/print.log" | sed 's/^ *srf_m //')
read -ra m <<< "$srf"
front=$(show a:sd1@0x10)
for i in 1 2 3; do   # the board holds centimetres; robot-sim printed metres (2 decimals)
  cm=$(awk -v v="${m[$i]}" 'BEGIN { printf "%d", v * 100 + 0.5 }')
  [[ " $front " == *" srf_cm "*" $cm "* ]] || fail "front SD1 '$front' lacks SRF $i = $cm cm"
done
sbs1=$(show b:sbs1@0x30)
[[ "$sbs1" == *"visible "*":"* ]] || fail "no beacon visible on the SBS1: $sbs1"
echo "ok: so1 '$so1'; sd1 '$front'; sbs1 '$sbs1'"
