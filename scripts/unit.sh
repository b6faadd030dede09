#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# unit.sh [VARIANT...]: the unit-test lane. Builds userland with ASan/UBSan
# (RelWithDebInfo, see build-userland.sh) and runs every CTest test of it;
# `unit.sh native` (or both) runs the plain build's tests instead. Rows per
# test go to build/results/unit-<variant>.tsv; exit 1 on any failure.
set -uo pipefail
. "$(dirname "$0")/lib.sh"

mkdir -p "$BUILD/results"
failed=0
variants=("$@")
[ ${#variants[@]} -gt 0 ] || variants=(asan)
for variant in "${variants[@]}"; do
	rows=$BUILD/results/unit-$variant.tsv
	: >"$rows"
	if ! "$TOP/scripts/build-userland.sh" "$variant"; then
		printf 'unit-%s: build\t0\t1\t0\tfail\tbuild failed\n' "$variant" >>"$rows"
		failed=1
		continue
	fi
	dir=$BUILD/userland
	[ "$variant" = asan ] && dir=$BUILD/userland-asan
	junit=$BUILD/results/unit-$variant.xml
	# halt_on_error: a sanitizer report fails the test that caused it.
	ASAN_OPTIONS=detect_leaks=1:halt_on_error=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
		ctest --test-dir "$dir" -j"$(nproc)" --output-on-failure --timeout 120 \
		--output-junit "$junit" | tee "$BUILD/results/unit-$variant.log" | grep -E 'tests passed|FAILED|Failed|\*\*\*|Errors while' || true
	status=${PIPESTATUS[0]}
	# One row per test from the JUnit report.
	grep -o '<testcase [^>]*' "$junit" 2>/dev/null | while read -r tc; do
		name=$(echo "$tc" | sed -n 's/.* name="\([^"]*\)".*/\1/p')
		st=$(echo "$tc" | sed -n 's/.* status="\([^"]*\)".*/\1/p')
		case $st in
		run) printf 'unit-%s: %s\t1\t0\t0\tok\t\n' "$variant" "$name" ;;
		disabled|notrun) printf 'unit-%s: %s\t0\t0\t1\tskip\t%s\n' "$variant" "$name" "$st" ;;
		*) printf 'unit-%s: %s\t0\t1\t0\tfail\t%s\n' "$variant" "$name" "$st" ;;
		esac
	done >>"$rows"
	if [ "$status" != 0 ] || [ ! -s "$rows" ]; then
		failed=1
		[ -s "$rows" ] || printf 'unit-%s: ctest\t0\t1\t0\tfail\tno test ran\n' "$variant" >>"$rows"
	fi
done
exit $failed
