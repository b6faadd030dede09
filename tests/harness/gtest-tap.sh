#!/bin/sh
# SPDX-License-Identifier: GPL-2.0
#
# gtest-tap.sh BINARY: run a GoogleTest binary in its build directory (where
# CTest runs it) and print one TAP point per test, the whole output as "# "
# lines. The armel VM lane runs the C++ unit tests with it
# (vm-arm.sh --arch armel --cxx): the guest has no CTest.
bin=${1:?GoogleTest binary}
out=${VMTEST_SCRATCH:-/tmp}/gtest.out
cd "$(dirname "$bin")" || exit 1
# The tests that talk LCM (UDP multicast) need the loopback up with a
# multicast route (as tests/lib/lcm.sh sets up for the VM suites).
if command -v ip >/dev/null; then
	ip link set lo up 2>/dev/null
	ip route show table all | grep -q '224.0.0.0/4' || ip route add 224.0.0.0/4 dev lo 2>/dev/null
fi
"$bin" --gtest_color=no >"$out" 2>&1
rc=$?
awk -v rc="$rc" -v bin="$bin" '
	{ print "# " $0 }
	/^\[       OK \] .* \([0-9]+ ms\)$/ { n++; t = $0; sub(/^\[       OK \] /, "", t); sub(/ \([0-9]+ ms\)$/, "", t); pts[n] = "ok " n " " t }
	/^\[  FAILED  \] .* \([0-9]+ ms\)$/ { n++; f++; t = $0; sub(/^\[  FAILED  \] /, "", t); sub(/ \([0-9]+ ms\)$/, "", t); pts[n] = "not ok " n " " t }
	/^\[  SKIPPED \] .* \([0-9]+ ms\)$/ { n++; t = $0; sub(/^\[  SKIPPED \] /, "", t); sub(/ \([0-9]+ ms\)$/, "", t); pts[n] = "ok " n " " t " # SKIP" }
	END {
		# A crash or an exit status that no failed test explains: one more point.
		if (rc != 0 && f == 0) { n++; pts[n] = "not ok " n " " bin " exit status " rc }
		print "1.." n
		for (i = 1; i <= n; i++) print pts[i]
	}' "$out"
[ "$rc" = 0 ]
