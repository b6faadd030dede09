#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# The installed systemd units pass systemd-analyze verify (syntax, known
# directives, dependencies, executables: a staged daemon is verified at its
# staged path). Every daemon is built by make userland: one that is not
# staged fails its unit, naming the binary, like any other complaint.
. "$(dirname "$0")/lib.sh"
trap cleanup_mounts EXIT
UNITS=$DEST/usr/lib/systemd/system

stage_install --modules none >/dev/null 2>&1 || { tap_diag "staging install failed"; exit 1; }
units=$(cd "$UNITS" && ls)
tap_plan $(($(echo "$units" | wc -l) + 2))
for u in $units; do
	# A template is verified as one instance (bus a, tty ttyTSU0).
	case $u in
	*@.service) inst=${u%@.service}@$([ "$u" = driver_rs485@.service ] && echo a || echo ttyTSU0).service ;;
	*) inst=$u ;;
	esac
	dir=$VMTEST_SCRATCH/verify.$u
	exe=$(sed -n 's/^ExecStart=\([^ ]*\).*/\1/p' "$UNITS/$u")
	mkdir -p "$dir" && cp "$UNITS/$u" "$dir/$inst"
	if [ -x "$DEST$exe" ]; then
		sed -i "s|^ExecStart=$exe|ExecStart=$DEST$exe|" "$dir/$inst"
		exe=$DEST$exe
	fi
	out=$(cd "$dir" && systemd-analyze verify "./$inst" 2>&1)
	if [ -n "$out" ]; then
		printf '%s\n' "$out" | sed 's/^/# /'
		tap_result 1 "$u: systemd-analyze verify${exe:+ ($exe)}"
	else
		tap_result 0 "$u: systemd-analyze verify"
	fi
done

# Templates name their instance's device; the daemons run as the advee group.
tap_is "ldattach unit bound to the tty's device unit" \
	"$(grep -E '^(BindsTo|After)=' "$UNITS/advee-rs485-ldattach@.service" | sort | tr '\n' ' ')" \
	"After=dev-%i.device BindsTo=dev-%i.device "
tap_is "every daemon unit runs with group advee" \
	"$(grep -L '^Group=advee$' "$UNITS"/advee-watchdog.service "$UNITS"/driver_*.service)" ""
tap_finish
