#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Issue 21 items 1 and 2: one place for the LCM URL on an installed robot.
# A staging install ships /etc/advee/lcm.conf (a URL with ttl=1: the robot's
# internal network, nothing beyond) and the network file with the multicast
# route; no installed unit or configuration names a URL of its own. Then,
# with the staged configuration live in /etc (an overlay) and its port
# changed so that it cannot be mistaken for LCM's built-in default:
# - without a multicast route, every unit's ExecStart exits 0x11 with one
#   line that names the fix and the URL from /etc/advee/lcm.conf;
# - with the route, every installed tool and the supervisor with a module
#   talk on that URL (subscribers bind its port, publishers are heard there);
#   --lcm still overrides it.
. "$(dirname "$0")/lib.sh"
. "$VMTEST_REPO/tests/lib/lcm.sh"
unset LCM_DEFAULT_URL	# lcm.sh sets it for the other suites; here the file decides
UNITS=$DEST/usr/lib/systemd/system
PORT=7693 OTHER_PORT=7694
PIDS=
cleanup() {
	local p
	for p in $PIDS; do kill "$p" 2>/dev/null; done
	for p in $PIDS; do wait "$p" 2>/dev/null; done
	lcm_net_down
	cleanup_mounts
}
trap cleanup EXIT
bg() { "$@" & PIDS="$! $PIDS"; LAST=$!; }

units="advee-watchdog.service driver_aux.service driver_canbus.service driver_power.service driver_rs485@.service"
tap_plan $((5 + $(echo $units | wc -w) + 7))
tap_here "staging install" stage_install --modules none
conf=$DEST/etc/advee/lcm.conf
url=$(sed -n 's/^LCM_DEFAULT_URL=//p' "$conf" 2>/dev/null)
tap_diag "installed URL: $url"
tap_ok "/etc/advee/lcm.conf: one multicast URL with ttl=1 (the robot's internal network only)" \
	test "$(grep -c '^LCM_DEFAULT_URL=udpm://239\.[0-9.]*:[0-9]*?ttl=1$' "$conf" 2>/dev/null)" = 1
net=$DEST/usr/lib/systemd/network/80-advee-lcm.network
tap_is "80-advee-lcm.network: eth0, link-local IPv4, the multicast route" \
	"$(grep -E '^(Name|LinkLocalAddressing|Destination)=' "$net" 2>/dev/null | tr '\n' ' ')" \
	"Name=eth0 LinkLocalAddressing=ipv4 Destination=224.0.0.0/4 "
found=$(grep -lE 'udpm://|memq://|LCM_DEFAULT_URL|--lcm|--url|lcm\.conf' "$UNITS"/* 2>/dev/null)
tap_is "no installed unit names an LCM URL or sets one" "$found" ""
found=$(grep -rlE 'udpm://|memq://|lcm_url' "$DEST/etc/advee" --include='*.yaml' 2>/dev/null)
tap_is "no installed configuration names an LCM URL" "$found" ""

# The staged /etc/advee live, with the URL on a port of its own.
overlay_rw /etc || { tap_diag "cannot overlay /etc"; exit 1; }
mkdir -p /etc/advee && cp -r "$DEST"/etc/advee/. /etc/advee/
sed -i "s|^\(LCM_DEFAULT_URL=udpm://[0-9.]*\):[0-9]*|\1:$PORT|" /etc/advee/lcm.conf
# The supervisor refuses a module program it cannot execute (0x41, before
# LCM): its modules are the staged ones here.
sed -i "s|path: /usr/|path: $DEST/usr/|" /etc/advee/watchdog.yaml
live=$(sed -n 's/^LCM_DEFAULT_URL=//p' /etc/advee/lcm.conf)
tap_diag "live URL for this test: $live"

# Item 2: no multicast route (the guest has no other interface: lo down).
lcm_net_down
ip route del 224.0.0.0/4 dev lo 2>/dev/null
ip link set lo down
for u in $units; do
	cmd=$(sed -n 's/^ExecStart=//p' "$UNITS/$u" | sed 's/%i/a/g')
	out=$(timeout 20 "$DEST${cmd%% *}" ${cmd#* } 2>&1)
	rc=$?
	printf '%s\n' "$out" | sed "s/^/# $u: /"
	lines=$(printf '%s\n' "$out" | grep -c .)
	tap_ok "$u without a multicast route: exit 0x11 (got $rc), one line (got $lines) naming the route and the URL from /etc/advee/lcm.conf" \
		test "$rc" = 17 -a "$lines" = 1 -a -n "$(printf '%s' "$out" | grep -F "ip route add 224.0.0.0/4" | grep -F "$live (from /etc/advee/lcm.conf)")"
done

lcm_net_up || { tap_diag "cannot set up loopback multicast"; exit 1; }
scratch=$VMTEST_SCRATCH/lcm-url
mkdir -p "$scratch"
# A listener with its own --url hears what the programs publish there.
bg "$VMTEST_BUILD/userland/module/advee-lcmctl" --url "$live" echo 'CM_DATA_STATE|LL_CMD_MOTION|SIM_DATA_POSE' >"$scratch/heard" 2>&1
listener=$LAST
tap_ok "advee-lcmctl --url subscribes on the port of its --url" wait_udp_bound "$listener" "$PORT" 20

# The supervisor and a module it starts (advee-test-module from the build:
# the test module is not installed).
cat >"$scratch/watchdog.yaml" <<EOC
module: {name: watchdog}
modules:
  - {name: testmod, path: $VMTEST_BUILD/userland/module/advee-test-module, args: [testmod]}
EOC
bg "$DEST/usr/sbin/advee-watchdog" --config "$scratch/watchdog.yaml" >"$scratch/watchdog.log" 2>&1
ok=0
wait_line "$scratch/heard" 'module=watchdog ' 30 >/dev/null && wait_line "$scratch/heard" 'module=testmod ' 30 >/dev/null && ok=1
tap_ok "advee-watchdog and the module it starts announce on the configured URL" test "$ok" = 1
[ "$ok" = 1 ] || { sed 's/^/# watchdog: /' "$scratch/watchdog.log"; tail -5 "$scratch/heard" | sed 's/^/# heard: /'; }

# Subscribers: each binds the configured port.
bad=
bg "$DEST/usr/bin/advee-diagnostic-center" --text --for 60s --period 10s >/dev/null 2>&1
wait_udp_bound "$LAST" "$PORT" 20 || bad="$bad advee-diagnostic-center"
bg "$DEST/usr/bin/advee-web" --listen 127.0.0.1:0 --root "$DEST/usr/share/advee/web" >"$scratch/web.log" 2>&1
wait_udp_bound "$LAST" "$PORT" 20 || bad="$bad advee-web"
bg "$DEST/usr/bin/advee-lcmctl" echo CM_DATA_STATE >/dev/null 2>&1
wait_udp_bound "$LAST" "$PORT" 20 || bad="$bad advee-lcmctl"
bg "$DEST/usr/bin/advee-robot-sim-pose" >/dev/null 2>&1
wait_udp_bound "$LAST" "$PORT" 20 || bad="$bad advee-robot-sim-pose"
bg "$DEST/usr/libexec/advee/tests/advee-stack-listen" --seconds 60 >/dev/null 2>&1
wait_udp_bound "$LAST" "$PORT" 20 || bad="$bad advee-stack-listen"
tap_is "every installed subscriber binds the configured port" "$bad" ""

# Publishers: heard on the configured URL.
printf 'path:\n  - {speed_mps: 0.1, steering_deg: 0, duration_s: 0.5}\n' >"$scratch/path.yaml"
tap_ok "advee-drive-script publishes on the configured URL" \
	"$DEST/usr/bin/advee-drive-script" --path "$scratch/path.yaml" --hold 0 --quiet
tap_ok "... its LL_CMD_MOTION is heard there" wait_line "$scratch/heard" '^LL_CMD_MOTION ' 10
bg "$DEST/usr/bin/advee-robot-sim" --map "$DEST/etc/advee/robotsim/room.yaml" --robot "$DEST/etc/advee/robotsim/robot.yaml" \
	--path "$scratch/path.yaml" --duration 30 --lcm
tap_ok "advee-robot-sim --lcm: its SIM_DATA_POSE is heard on the configured URL" wait_line "$scratch/heard" '^SIM_DATA_POSE ' 20

# --lcm overrides the file.
bg "$DEST/usr/bin/advee-diagnostic-center" --text --for 60s --period 10s --lcm "udpm://239.255.76.67:$OTHER_PORT?ttl=0" >/dev/null 2>&1
tap_ok "advee-diagnostic-center --lcm URL overrides the file (binds port $OTHER_PORT)" wait_udp_bound "$LAST" "$OTHER_PORT" 20
tap_finish
