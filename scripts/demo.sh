#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# demo.sh: the main job (README, first command; docs/demo.md). Installs what
# is missing, builds the kernel modules and the user space, boots the x86_64
# VM and runs the whole low level of the robot there on the simulated robot
# (tests/harness/demo-guest.sh):
#
#   scripts/demo.sh              advee-diagnostic-center's terminal UI on this
#                                terminal (the VM's serial console); q quits
#                                it and the VM powers off (Ctrl-a x kills it)
#   scripts/demo.sh --for 30s    non-interactive: the robot drives the scripted
#                                path, advee-diagnostic-center --text prints a
#                                summary every 5 s; exit 0 when all went well
#                                (`make demo FOR=30s`)
#
# The interactive demo also serves the web dashboard on the host at
# http://127.0.0.1:8080/ (ADVEE_WEB_PORT=N another port, 0 none), with one
# operator, "operator", whose random password this run creates and prints
# (build/demo/web-operators; docs/web-dashboard.md "Security model").
set -euo pipefail
. "$(dirname "$0")/lib.sh"

for_=
while [ $# -gt 0 ]; do
	case $1 in
	--for) for_=$2; shift 2 ;;
	--for=*) for_=${1#--for=}; shift ;;
	-h|--help) sed -n '4,18p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
	*) die "demo.sh: unknown argument $1 (see --help)" ;;
	esac
done
case $for_ in
'') ;;
*[0-9]s|*[0-9]) for_=${for_%s}s ;;
*) die "demo.sh: --for takes seconds, e.g. 30s" ;;
esac
if [ -z "$for_" ] && [ ! -t 0 ]; then
	die "the interactive demo needs a terminal; use --for 30s (make demo FOR=30s) without one"
fi

"$TOP/scripts/deps.sh"
"$TOP/scripts/build-kmod.sh" x86_64
"$TOP/scripts/build-userland.sh" native

if [ -n "$for_" ]; then
	# The run's time limit (300 s) covers boot, stack start-up and the demo.
	[ "${for_%s}" -le 200 ] || die "demo.sh: --for at most 200s"
	VMTEST_APPEND="advee.demo=for:$for_" \
		exec "$TOP/tests/harness/vm-x86.sh" --lane demo --run "$TOP/tests/harness/demo-guest.sh"
fi
read -r rows cols < <(stty size)
# The web dashboard's port on the host (ADVEE_WEB_PORT=0: none); skipped
# when something on the host already listens there.
web_port=${ADVEE_WEB_PORT:-8080}
if [ "$web_port" != 0 ] && (exec 3<>"/dev/tcp/127.0.0.1/$web_port") 2>/dev/null; then
	say "port $web_port is in use on this host: no web dashboard (ADVEE_WEB_PORT=N picks another)"
	web_port=0
fi
if [ "$web_port" != 0 ]; then
	export VMTEST_HOSTFWD=$web_port
	# A new password for every run, only its hash on disk; the guest reads
	# the file over the read-only 9p root (demo-guest.sh: --operators).
	mkdir -p "$BUILD/demo"
	rm -f "$BUILD/demo/web-operators"
	web_pw=$("$BUILD/userland/web/advee-web" --operators "$BUILD/demo/web-operators" passwd operator --random 2>/dev/null) ||
		die "advee-web passwd failed"
	say "web dashboard: http://127.0.0.1:$web_port/ - log in as: operator  password: $web_pw"
	say "(a phone-sized window works too; docs/demo.md \"Driving from the web page\")"
	sleep 3
fi
VMTEST_APPEND="advee.demo=tui advee.rows=$rows advee.cols=$cols advee.term=${TERM:-vt100}" \
	exec "$TOP/tests/harness/vm-x86.sh" --lane demo --interactive --run "$TOP/tests/harness/demo-guest.sh"
