#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# The README's main command in its non-interactive form (`make demo FOR=30s`
# runs tests/harness/demo-guest.sh --for 30s in its own VM; this runs the
# same guest script inside the suite's VM, no extra boot): it exits 0 and
# diagnostic_center's text summary shows, every 5 s, every module in RUN,
# the robot moving along the scripted path (ground truth and odometry
# estimate, 0.3 m apart at most), ranges, beacons, temperatures and power.
. "$(dirname "$0")/lib.sh"
stack_require canbus robot-can sim-pose diagnostic-center

ODO_TOL=0.3
tap_plan 8
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
moved=$(awk -v a="$(stack_field "$first" x)" -v b="$(stack_field "$first" y)" \
	-v c="$(stack_field "$last" x)" -v d="$(stack_field "$last" y)" 'BEGIN { printf "%.2f", sqrt((c-a)^2 + (d-b)^2) }')
tap_ok "the robot moves along the path: the true pose went $moved m (> 3 m)" awk -v m="$moved" 'BEGIN { exit !(m > 3) }'

odo=$(grep '^pose_odo ' "$OUT" | tail -1)
err=$(awk -v a="$(stack_field "$odo" x)" -v b="$(stack_field "$odo" y)" \
	-v c="$(stack_field "$last" x)" -v d="$(stack_field "$last" y)" 'BEGIN { printf "%.3f", sqrt((c-a)^2 + (d-b)^2) }')
tap_diag "last: $odo / $last"
tap_ok "the odometry estimate follows the truth ($err m apart, <= $ODO_TOL m)" \
	awk -v e="$err" -v t="$ODO_TOL" 'BEGIN { exit !(e <= t) }'

srf=$(grep '^srf ' "$OUT" | tail -1)
tap_ok "ranges: 16 SRF readings, at least 8 with an echo" \
	awk -v l="$srf" 'BEGIN { n = split(l, w, " "); for (i = 2; i <= n; i++) if (w[i] ~ /^[0-9]+=/) { c++; split(w[i], kv, "="); if (kv[2] > 0) e++ } exit !(c == 16 && e >= 8) }'
tap_ok "beacons seen" grep -qE '^beacons .*[0-9]+=' <(grep '^beacons ' "$OUT" | tail -1)
tap_ok "temperatures and power outputs shown" \
	sh -c "grep '^temps ' '$OUT' | tail -1 | grep -q '[0-9]' && grep '^power ' '$OUT' | tail -1 | grep -q '[0-9]'"
tap_finish
