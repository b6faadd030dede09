#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# skip-policy.sh ROWS.TSV: a skip is allowed only where tests/expected-skips
# says why. For every row of ROWS.TSV (name, passed, failed, skipped, verdict,
# reason) that skipped something and whose name matches no pattern of that
# list, print a failing row naming it; print nothing when all is well.
set -euo pipefail
. "$(dirname "$0")/lib.sh"

rows=${1:?rows (TSV)}
list=$TOP/tests/expected-skips
patterns=()
while IFS=$'\t' read -r pat why; do
	case $pat in ''|'#'*) continue ;; esac
	[ -n "${why// }" ] || die "tests/expected-skips: '$pat' has no reason (pattern<TAB>why)"
	patterns+=("$pat")
done <"$list"

# Tab is white space to read(1): empty fields (a skip without a reason)
# would collapse and shift the columns, so they are split on \x1f instead.
while IFS= read -r row; do
	IFS=$'\x1f' read -r name _pass _fail skip _verdict reason _ <<<"${row//$'\t'/$'\x1f'}"
	[ "${skip:-0}" -gt 0 ] 2>/dev/null || continue
	listed=0
	for pat in "${patterns[@]}"; do
		# shellcheck disable=SC2254 # the pattern is a glob on purpose
		case $name in $pat) listed=1; break ;; esac
	done
	[ $listed = 1 ] && continue
	printf 'skip policy: %s\t0\t1\t0\tfail\tskipped (%s) but not listed in tests/expected-skips\n' \
		"$name" "${reason:-no reason given}"
	echo "FAILED: $name skipped (${reason:-no reason given}); a skip must be listed in tests/expected-skips with why" >&2
done <"$rows"
