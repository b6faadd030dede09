#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# The README's main command in its non-interactive form (`make demo FOR=30s`
# runs tests/harness/demo-guest.sh --for 30s in its own VM; this runs the
# same guest script inside the suite's VM, no extra boot): it exits 0 and
# advee-diagnostic-center's text summary shows, every 5 s, every module in RUN,
# the robot moving along the scripted path (ground truth and odometry
# estimate, 0.3 m apart at most), and the last summary's ranges, beacons,
# temperatures and power with the values and relations the simulators give.
. "$(dirname "$0")/lib.sh"
stack_require canbus robot-can sim-pose diagnostic-center

ODO_TOL=0.3
tap_plan 9
OUT=$(mktemp "${VMTEST_SCRATCH:-/tmp}/demo.XXXXXX")
"$VMTEST_REPO/tests/harness/demo-guest.sh" --for 30s >"$OUT" 2>&1
rc=$?
sed 's/^/# /' "$OUT" | head -30
echo "# ..."
tail -25 "$OUT" | sed 's/^/# /'
tap_is "demo-guest.sh --for 30s exits 0" "$rc" 0

blocks=$(grep -c '^summary ' "$OUT")
tap_ok "a summary every 5 s: $blocks blocks in 30 s (5..7)" test "$blocks" -ge 5 -a "$blocks" -le 7

modules=$(grep '^modules ' "$OUT" | tail -1)
bad=
for m in watchdog driver_aux driver_rs485a driver_rs485b driver_power driver_canbus; do
	[[ " $modules " == *" $m=RUN "* ]] || bad="$bad $m"
done
tap_ok "the last summary lists every module in RUN${bad:+ (not:$bad)}" test -z "$bad"

first=$(grep -m1 '^pose_true x=' "$OUT") last=$(grep '^pose_true x=' "$OUT" | tail -1)
moved=$(awk -v a="$(field "$first" x)" -v b="$(field "$first" y)" \
	-v c="$(field "$last" x)" -v d="$(field "$last" y)" 'BEGIN { printf "%.2f", sqrt((c-a)^2 + (d-b)^2) }')
tap_ok "the robot moves along the path: the true pose went $moved m (> 3 m)" awk -v m="$moved" 'BEGIN { exit !(m > 3) }'

odo=$(grep '^pose_odo ' "$OUT" | tail -1)
err=$(awk -v a="$(field "$odo" x)" -v b="$(field "$odo" y)" \
	-v c="$(field "$last" x)" -v d="$(field "$last" y)" 'BEGIN { printf "%.3f", sqrt((c-a)^2 + (d-b)^2) }')
tap_diag "last: $odo / $last"
tap_ok "the odometry estimate follows the truth ($err m apart, <= $ODO_TOL m)" \
	awk -v e="$err" -v t="$ODO_TOL" 'BEGIN { exit !(e <= t) }'

srf=$(grep '^srf ' "$OUT" | tail -1)
tap_diag "$srf"
tap_ok "ranges: 16 SRF readings, each an echo (0.02..6 m) or none (-1), at least 8 with an echo, not stale" \
	awk -v l="$srf" 'BEGIN { n = split(l, w, " "); for (i = 2; i <= n; i++) { if (w[i] == "stale=1") exit 1
		if (w[i] !~ /^[0-9]+=/) continue; c++; split(w[i], kv, "="); r = kv[2] + 0
		if (r > 0) { e++; if (r < 0.02 || r > 6) exit 1 } else if (r != -1) exit 1 }
		exit !(c == 16 && e >= 8) }'
# The beacons named by the drive script (--beacons 1..8), as bearings in
# radians: as many pairs as the count says, each id named once.
beacons=$(grep '^beacons ' "$OUT" | tail -1)
tap_diag "$beacons"
tap_ok "beacons: count=N and N bearings (0..2 pi) of distinct ids among 1..8, at least one, not stale" \
	awk -v l="$beacons" 'BEGIN { n = split(l, w, " "); for (i = 2; i <= n; i++) { if (w[i] == "stale=1") exit 1
		split(w[i], kv, "="); if (kv[1] == "count") { want = kv[2]; continue }
		if (kv[1] !~ /^[0-9]+$/) continue
		if (kv[1] < 1 || kv[1] > 8 || (kv[1] in seen) || kv[2] < 0 || kv[2] >= 6.2832) exit 1; seen[kv[1]] = 1; c++ }
		exit !(c >= 1 && c == want) }'
# advee-robot-sim's thermal model (userland/robotsim/conf/robot.yaml): ambient
# 25 C plus at most 35 C (propulsion, temp1) and 15 C (steering, temp2).
temps=$(grep '^temps ' "$OUT" | tail -1)
tap_diag "$temps"
tap_ok "temperatures: temp1 25..60 C, temp2 25..40 C (the thermal model's range), not stale" \
	awk -v a="$(field "$temps" temp1)" -v b="$(field "$temps" temp2)" -v l="$temps" \
	'BEGIN { exit !(a != "" && b != "" && a >= 25 && a <= 60 && b >= 25 && b <= 40 && l !~ /stale=1/) }'
# The PSC1 of tests/vm/stack/conf/boards.yaml: outputs 0..3 on, their
# currents, no battery measurement, no PAUSE on the scripted path.
power=$(grep '^power ' "$OUT" | tail -1)
tap_diag "$power"
tap_is "power: outputs 0..3 on, 1.5/0.8/0.4/0.2 A, no battery reading, not paused" \
	"$(for k in battery out0 out1 out2 out3 out4 i0 i1 i2 i3 paused; do printf '%s ' "$(field "$power" $k)"; done)" \
	"-1.00 on on on on off 1.50 0.80 0.40 0.20 0 "
tap_finish
