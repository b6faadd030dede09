#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# advee-robot-sim publishing to a real advee-rs485-sim through its control socket: after
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
[ -S "$dir/ctl.sock" ] || fail "advee-rs485-sim did not start: $(cat "$dir/sim.log")"

"$robot_sim" -m "$conf/room.yaml" -r "$conf/robot.yaml" -p "$conf/square-path.yaml" \
  --rs485-control "$dir/ctl.sock" --fast --duration 20 --print > "$dir/print.log"
show() { "$rs485_sim" --control "$dir/ctl.sock" --send "show $1"; }

# Every check compares whole fields at their positions in the boards' show
# lines ("ok ticks L R rate ...", "ok srf_cm V0..V7 ir_2mm ...", "ok ids ...
# visible ID:DEG/Q ..."), not a substring anywhere in them.
last=$(grep '^t=20.0 ' "$dir/print.log") || fail "no t=20.0 line in: $(cat "$dir/print.log")"
ticks=$(sed -n 's/.* ticks=\([0-9-]*\),\([0-9-]*\)$/\1 \2/p' <<< "$last")
[ -n "$ticks" ] || fail "no ticks=L,R at the end of: $last"
so1=$(show a:so1@0x20)
read -ra w <<< "$so1"
[ "${w[0]} ${w[1]}" = "ok ticks" ] && [ "${w[4]}" = rate ] || fail "so1 show line not 'ok ticks L R rate ...': $so1"
[ "${w[2]} ${w[3]}" = "$ticks" ] || fail "so1 holds ticks '${w[2]} ${w[3]}', advee-robot-sim printed '$ticks'"
left=${ticks% *}
[ "$left" -gt 20000 ] || fail "only $left ticks after 20 s of driving"

# robot.yaml: SRF 0..7 on the front SD1 (0x10), 8..15 on the rear one (0x11);
# advee-robot-sim prints metres with 2 decimals or "-" (no echo), a board holds
# centimetres or "none".
srf=$(sed -n '/^t=20.0 /{n;p}' "$dir/print.log")
read -ra m <<< "$srf"
[ "${m[0]}" = srf_m ] && [ "${#m[@]}" -eq 17 ] || fail "not 'srf_m' and 16 ranges: $srf"
m=("${m[@]:1}")
check_sd1() {	# check_sd1 DEVICE FIRST: its 8 srf_cm fields against m[FIRST..FIRST+7]
	local dev=$1 first=$2 line i want
	line=$(show "$dev")
	read -ra w <<< "$line"
	[ "${w[0]} ${w[1]}" = "ok srf_cm" ] && [ "${w[10]}" = ir_2mm ] ||
		fail "$dev show line not 'ok srf_cm V0..V7 ir_2mm ...': $line"
	for i in 0 1 2 3 4 5 6 7; do
		want=none
		[ "${m[$((first + i))]}" = - ] ||
			want=$(awk -v v="${m[$((first + i))]}" 'BEGIN { printf "%d", v * 100 + (v < 0 ? -0.5 : 0.5) }')
		[ "${w[$((i + 2))]}" = "$want" ] ||
			fail "$dev SRF $i holds '${w[$((i + 2))]}', advee-robot-sim printed ${m[$((first + i))]} m: $line"
	done
	echo "$line"
}
front=$(check_sd1 a:sd1@0x10 0)
rear=$(check_sd1 a:sd1@0x11 8)
seen=0
for v in "${m[@]}"; do [ "$v" = - ] || seen=$((seen + 1)); done
[ "$seen" -gt 0 ] || fail "no SRF saw anything: $srf"

# Beacons: advee-robot-sim prints "ID@DEG.DDdeg(qQ)", the SBS1 holds "ID:DEG/Q"
# (DEG as %g). The visible sets are equal.
beacons=$(sed -n '/^t=20.0 /,/^  beacons/{s/^  beacons//p}' "$dir/print.log")
want=$(tr ' ' '\n' <<< "$beacons" | sed -n 's/^\([0-9]*\)@\([-0-9.]*\)deg(q\([0-9]*\))$/\1 \2 \3/p' |
	awk '{ printf "%d:%g/%d\n", $1, $2, $3 }' | sort)
[ -n "$want" ] || fail "advee-robot-sim saw no beacon at t=20.0: '$beacons'"
sbs1=$(show b:sbs1@0x30)
[[ "$sbs1" == "ok ids"*" visible "* ]] || fail "sbs1 show line not 'ok ids ... visible ...': $sbs1"
got=$(tr ' ' '\n' <<< "${sbs1#* visible }" | sort)
[ "$got" = "$want" ] || fail "SBS1 holds '$(echo $got)', advee-robot-sim saw '$(echo $want)'"
echo "ok: so1 '$so1'; sd1 '$front' / '$rear'; sbs1 '$sbs1'"
