#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# browser-check.sh [USERLAND_BUILD_DIR]: the dashboard end to end on the host.
# Starts advee-web on a private LCM group (UDP multicast over the host's
# loopback, ttl=0: nothing leaves the machine; a port of 7680-8679 of its own,
# so that LCM tests on 7667 and another run of this check at the same time
# cannot mix in: the real-browser test counts every command on LCM), publishes the known scene of
# advee-web-test-publisher, renders the page with headless Chromium and checks
# the DOM for the values a user would look at (the open view, no login). Then
# tests/browser/dashboard-test.mjs drives the page in real browsers
# (puppeteer-core, installed by scripts/deps.sh): login, control, the lease,
# the refusals, fuzz, the phone layout, with what reaches LCM read by
# advee-stack-listen. Then the same bridge over TLS (a self-signed
# certificate made for the run): one login and drive over https and wss
# (tests/browser/tls-test.mjs). Keeps the screenshots and the DOM under build/web/. One
# TSV row per check in build/results/web.tsv (name, passed, failed, skipped,
# status, note) for scripts/check.sh; the measured figures in
# build/web/figures.txt.
# Needs a route for multicast (the default route, or 224.0.0.0/4 dev lo).
set -uo pipefail
TOP=$(cd "$(dirname "$0")/../../.." && pwd)
BUILD=${BUILD:-$TOP/build}
UL=${1:-$BUILD/userland}
OUT=$BUILD/web
RESULTS=$BUILD/results
ROWS=$RESULTS/web.tsv
mkdir -p "$OUT" "$RESULTS"
: >"$ROWS"
export LCM_DEFAULT_URL="udpm://239.255.76.67:$((7680 + $$ % 1000))?ttl=0"
failed=0
row() {	# row NAME ok|fail|skip [NOTE]
	case $2 in
	ok) printf 'web: %s\t1\t0\t0\tok\t\n' "$1" ;;
	skip) printf 'web: %s\t0\t0\t1\tskip\t%s\n' "$1" "${3:-}"; echo "SKIP: $1 (${3:-})" >&2 ;;
	*) printf 'web: %s\t0\t1\t0\tfail\t%s\n' "$1" "${3:-}"; failed=1; echo "FAIL: $1 (${3:-})" >&2 ;;
	esac >>"$ROWS"
	[ "$2" = ok ] && echo "ok: $1"
}
PIDS=
cleanup() {
	for p in $PIDS; do kill "$p" 2>/dev/null; done
	for p in $PIDS; do wait "$p" 2>/dev/null; done
}
trap cleanup EXIT

WEB=$UL/web/advee-web
PUB=$UL/web/advee-web-test-publisher
LISTEN=$UL/demo/advee-stack-listen
NODE_TESTS=$TOP/userland/web/tests/browser
CHROMIUM=$(command -v chromium || command -v chromium-browser || true)
if [ ! -x "$WEB" ] || [ ! -x "$PUB" ] || [ ! -x "$LISTEN" ]; then
	row "build: advee-web, advee-web-test-publisher, advee-stack-listen" fail "not built in $UL"
	exit 1
fi
if [ -z "$CHROMIUM" ]; then
	row "chromium installed" fail "apt-get install chromium (scripts/packages.txt)"
	exit 1
fi

# Two operators with random passwords, for this run only.
OPS=$OUT/operators
rm -f "$OPS"
: >"$OUT/advee-web.log"
OP1=alice OP2=bob
PW1=$("$WEB" --operators "$OPS" passwd "$OP1" --random 2>>"$OUT/advee-web.log")
PW2=$("$WEB" --operators "$OPS" passwd "$OP2" --random 2>>"$OUT/advee-web.log")
if [ "$(stat -c %a "$OPS" 2>/dev/null)" = 640 ] && [ ${#PW1} = 16 ] && ! grep -q "$PW1" "$OPS"; then
	row "advee-web passwd: a 0640 file of hashes, no password in it" ok
else
	row "advee-web passwd: a 0640 file of hashes, no password in it" fail "$(stat -c %a "$OPS" 2>&1)"
fi

# A free TCP port: advee-web reports the one it got when given port 0.
"$WEB" --listen 127.0.0.1:0 --root "$TOP/userland/web/static" --operators "$OPS" \
	--robot "$TOP/userland/robotsim/conf/robot.yaml" --map "$TOP/userland/robotsim/conf/room.yaml" \
	2>>"$OUT/advee-web.log" &
WEB_PID=$!
PIDS="$PIDS $WEB_PID"
port=
for _ in $(seq 50); do
	port=$(sed -n 's|.* on http://127.0.0.1:\([0-9]*\)/$|\1|p' "$OUT/advee-web.log")
	[ -n "$port" ] && break
	sleep 0.1
done
if [ -z "$port" ]; then
	# LCM's UDP multicast needs a route for 224.0.0.0/4 (a default route
	# does; on a host without one: ip route add 224.0.0.0/4 dev lo).
	row "advee-web starts and listens" fail "$(tail -1 "$OUT/advee-web.log")"
	exit 1
fi
row "advee-web starts and listens" ok
URL=http://127.0.0.1:$port/

# The drive (6 s at 10 Hz) happens before the browser connects: the page must
# show it from the bridge's history and odometry, as for a page opened late.
"$PUB" --drive 6 --hold 60 2>"$OUT/publisher.log" &
PIDS="$PIDS $!"
sleep 7.5

# --virtual-time-budget: the page runs 2.5 s of its own (virtual) time after
# loading, enough for the WebSocket's history and snapshot, then the DOM or
# the picture is taken.
chrome() {	# chrome ARGS...: headless, no sandbox (root), no GPU
	timeout 120 "$CHROMIUM" --headless --no-sandbox --disable-gpu --hide-scrollbars \
		--no-first-run --user-data-dir="$OUT/chromium-profile" \
		--window-size=1400,900 --virtual-time-budget=2500 "$@" 2>>"$OUT/chromium.log"
}
rm -rf "$OUT/chromium-profile" "$OUT/dashboard.png" "$OUT/chromium.log"
chrome --dump-dom "$URL" >"$OUT/dashboard-dom.html"
chrome --screenshot="$OUT/dashboard.png" "$URL" >/dev/null

dom=$OUT/dashboard-dom.html
check() {	# check NAME REGEX: the rendered DOM matches
	if grep -Eq "$2" "$dom"; then row "$1" ok; else row "$1" fail "no match for $2 in build/web/dashboard-dom.html"; fi
}
check "page connected to the bridge" 'id="conn-status"[^>]*>connected<'
check "module driver_aux shown in RUN" 'id="module-driver_aux".*state RUN">RUN<'
check "module driver_rs485a shown in RUN" 'id="module-driver_rs485a".*state RUN">RUN<'
check "module driver_power shown in PAUSE" 'id="module-driver_power".*state PAUSE">PAUSE<'
check "supervisor restarts shown (driver_aux: 1)" 'id="module-driver_aux"[^>]*><td>driver_aux</td><td[^>]*>RUN</td><td>RUNNING pid [0-9]+</td><td>1</td>'
check "temperature temp1 41.5 C" 'id="temp-temp1">41\.5 °C<'
check "temperature temp2 33.2 C" 'id="temp-temp2">33\.2 °C<'
check "fan fan1 2400 rpm" 'id="fan-fan1">2400 rpm'
check "battery 24.6 V" 'id="battery-v"[^>]*>24\.6 V<'
check "PAUSE indicator on" 'id="pause-indicator" class="pill paused">PAUSE<'
check "commanded and actual speed after the stop" 'id="cmd-speed">0\.00 m/s<.*id="act-speed">0\.00 m/s<'
check "error report listed" 'driver_rs485a: test error: bus timeout \(110\)'
check "bridge status shown" 'id="bridge-stats"[^>]*>bridge: [0-9]+ messages'

# The odometry estimate after the drive: the publisher drives a circle of
# radius 0.62/tan(0.3) = 2.00 m at 0.5 m/s for 6 s from (2, 2) heading 0:
# 3.0 m of arc = 1.50 rad, so x = 2 + 2.00 sin 1.5 = 4.00, y = 2 + 2.00 (1 - cos 1.5) = 3.86.
odo=$(sed -n 's|.*id="odo-pose">x \([-0-9.]*\) m  y \([-0-9.]*\) m  heading \([-0-9.]*\)°<.*|\1 \2 \3|p' "$dom")
if [ -n "$odo" ] && awk -v p="$odo" 'BEGIN { split(p, a, " ");
	exit !(a[1] > 3.9 && a[1] < 4.1 && a[2] > 3.76 && a[2] < 3.96 && a[3] > 80 && a[3] < 92) }'; then
	row "odometry pose from the bridge's history ($odo)" ok
else
	row "odometry pose from the bridge's history" fail "got '${odo}', want about 4.00 3.86 85.9"
fi
# SIM_DATA_POSE only when the sim package is part of the build.
if [ -f "$UL/msgs/gen/sim/data_pose_t.hpp" ]; then
	check "true pose from SIM_DATA_POSE shown" 'id="true-pose">x 4\.0[0-9] m  y 3\.8[0-9] m'
else
	row "true pose from SIM_DATA_POSE shown" skip "sim.data_pose_t not in this build"
fi

# The screenshot: a real rendering (dark page with a drawn map), not an
# error page. PNG header, size, and enough distinct bytes to be a picture.
if [ -s "$OUT/dashboard.png" ] && [ "$(head -c 8 "$OUT/dashboard.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] &&
	[ "$(stat -c %s "$OUT/dashboard.png")" -gt 50000 ]; then
	row "screenshot build/web/dashboard.png ($(stat -c %s "$OUT/dashboard.png") bytes)" ok
else
	row "screenshot build/web/dashboard.png" fail "missing or too small: see build/web/chromium.log"
fi

# The real-browser tests (dashboard-test.mjs), while the publisher still runs.
if [ ! -d "$NODE_TESTS/node_modules/puppeteer-core" ]; then
	row "real-browser tests: puppeteer-core installed" fail "run scripts/deps.sh (npm ci in userland/web/tests/browser)"
else
	start=$(date +%s.%N)
	WEB_URL=$URL WEB_PID=$WEB_PID LISTEN=$LISTEN CHROMIUM=$CHROMIUM OUT=$OUT OP1=$OP1 PW1=$PW1 OP2=$OP2 PW2=$PW2 \
		timeout 180 node "$NODE_TESTS/dashboard-test.mjs" >"$OUT/browser-test.out" 2>"$OUT/browser-test.err"
	rc=$?
	: >"$OUT/figures.txt"
	while IFS=$'\t' read -r kind a b c; do
		case $kind in
		ROW) row "$b" "$a" "$c" ;;
		FIGURE) printf '%s: %s\n' "$a" "$b" | tee -a "$OUT/figures.txt" ;;
		esac
	done <"$OUT/browser-test.out"
	printf 'real-browser tests: %.1f s\n' "$(echo "$(date +%s.%N) - $start" | bc)" | tee -a "$OUT/figures.txt"
	if [ "$rc" != 0 ] && ! grep -q '^ROW	fail' "$OUT/browser-test.out"; then
		row "real-browser tests ran" fail "exit $rc: $(tail -3 "$OUT/browser-test.err" | tr '\n' ' ')"
	fi
fi
# Nothing secret in the log.
if grep -qF -e "$PW1" -e "$PW2" "$OUT/advee-web.log"; then
	row "no password in advee-web's log" fail "build/web/advee-web.log"
else
	row "no password in advee-web's log" ok
fi

# SIGTERM ends the bridge cleanly (exit 0) with its drop count.
kill -TERM "$WEB_PID"
wait "$WEB_PID"
rc=$?
PIDS=${PIDS/ $WEB_PID/}
if [ "$rc" = 0 ] && grep -Eqx 'advee-web: stopped: [0-9]+ messages, [0-9]+ dropped for slow clients' "$OUT/advee-web.log"; then
	row "SIGTERM: advee-web exits 0" ok
else
	row "SIGTERM: advee-web exits 0" fail "exit $rc"
fi

# The same over TLS: a second advee-web with a throw-away self-signed
# certificate for this run (EC P-256, 127.0.0.1 in its subjectAltName), and
# one login + drive in Chromium over https and wss (tls-test.mjs). Chromium
# trusts exactly that certificate: the SHA-256 of its public key goes to
# --ignore-certificate-errors-spki-list.
TLS=$OUT/tls
rm -rf "$TLS"
mkdir -p "$TLS"
if ! openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -days 2 -subj /CN=127.0.0.1 \
	-addext subjectAltName=IP:127.0.0.1 -keyout "$TLS/key.pem" -out "$TLS/cert.pem" 2>"$TLS/openssl.log"; then
	row "https: a self-signed certificate for the run" fail "$(tail -1 "$TLS/openssl.log")"
	exit 1
fi
spki=$(openssl x509 -in "$TLS/cert.pem" -pubkey -noout | openssl pkey -pubin -outform der |
	openssl dgst -sha256 -binary | base64)
: >"$OUT/advee-web-tls.log"
"$WEB" --listen 127.0.0.1:0 --root "$TOP/userland/web/static" --operators "$OPS" --robot "" --map "" \
	--tls-cert "$TLS/cert.pem" --tls-key "$TLS/key.pem" 2>>"$OUT/advee-web-tls.log" &
WEB_PID=$!
PIDS="$PIDS $WEB_PID"
port=
for _ in $(seq 50); do
	port=$(sed -n 's|.* on https://127.0.0.1:\([0-9]*\)/$|\1|p' "$OUT/advee-web-tls.log")
	[ -n "$port" ] && break
	sleep 0.1
done
if [ -z "$port" ]; then
	row "https: advee-web --tls-cert starts and listens" fail "$(tail -1 "$OUT/advee-web-tls.log")"
	exit 1
fi
row "https: advee-web --tls-cert starts and listens" ok
if [ -d "$NODE_TESTS/node_modules/puppeteer-core" ]; then
	WEB_URL=https://127.0.0.1:$port/ SPKI=$spki LISTEN=$LISTEN CHROMIUM=$CHROMIUM OP1=$OP1 PW1=$PW1 \
		timeout 120 node "$NODE_TESTS/tls-test.mjs" >"$OUT/browser-tls-test.out" 2>"$OUT/browser-tls-test.err"
	rc=$?
	while IFS=$'\t' read -r kind a b c; do
		case $kind in
		ROW) row "$b" "$a" "$c" ;;
		FIGURE) printf '%s: %s\n' "$a" "$b" | tee -a "$OUT/figures.txt" ;;
		esac
	done <"$OUT/browser-tls-test.out"
	if [ "$rc" != 0 ] && ! grep -q '^ROW	fail' "$OUT/browser-tls-test.out"; then
		row "https real-browser test ran" fail "exit $rc: $(tail -3 "$OUT/browser-tls-test.err" | tr '\n' ' ')"
	fi
fi
# Plain HTTP to the TLS port gets no HTTP answer (at most a TLS alert), and
# the connection is closed.
# The server may close before the request is all written: no SIGPIPE then
# (a run ended with 141), the reply is read all the same.
(trap '' PIPE; exec 3<>"/dev/tcp/127.0.0.1/$port" || exit 2
	printf 'GET / HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n' >&3 2>/dev/null
	timeout 5 cat <&3 >"$TLS/plain-reply" 2>/dev/null)
rc=$?	# 0: closed by the server, 1: reset, 2: no connection, 124: left open
if [ "$rc" -le 1 ] && [ -f "$TLS/plain-reply" ] && ! grep -q "HTTP/" "$TLS/plain-reply"; then
	row "https: plain HTTP to the TLS port gets no HTTP answer and is closed" ok
else
	row "https: plain HTTP to the TLS port gets no HTTP answer and is closed" fail "exit $rc, $(head -c 80 "$TLS/plain-reply")"
fi
kill -TERM "$WEB_PID"
wait "$WEB_PID"
rc=$?
PIDS=${PIDS/ $WEB_PID/}
if [ "$rc" = 0 ] && ! grep -qF -e "$PW1" -e "$PW2" "$OUT/advee-web-tls.log"; then
	row "https: SIGTERM exits 0, no password in the log" ok
else
	row "https: SIGTERM exits 0, no password in the log" fail "exit $rc"
fi
exit $failed
