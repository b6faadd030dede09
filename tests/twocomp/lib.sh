# SPDX-License-Identifier: GPL-2.0
# shellcheck shell=bash
# The two-computer test (issue 21), sourced by both guests' programs:
# robot.sh (guest A) and high-level.sh (guest B), booted side by side by
# tests/harness/vm-pair.sh on one private Ethernet link (eth0 in each guest).
#
#   twocomp_clock OFFSET_S  the guest's clock: the host's + OFFSET_S
#   twocomp_net ADDRESS   eth0 up with the link-local ADDRESS/16 and the
#                         multicast route, as 80-advee-lcm.network sets up the
#                         robot; the shipped /etc/advee/lcm.conf in force (an
#                         overlay over /etc; LCM_DEFAULT_URL unset), so every
#                         program uses the robot's one URL (ttl=1)
#   TWOCOMP_SHARE         the guest's results share: the files the host and
#                         the guest exchange (link-down-request, link-up, stop;
#                         B's listener output over the path, high-level-path.txt,
#                         which the host hands to A before stop)
#   TWOCOMP_MODULES       the robot modules guest B must see
. "$VMTEST_REPO/tests/vm/stack/lib.sh"
unset LCM_DEFAULT_URL

TWOCOMP_SHARE=${VMTEST_RESULTS:-/run/vmtest}
# shellcheck disable=SC2034 # for the programs that source this
TWOCOMP_MODULES="driver_aux driver_rs485a driver_rs485b driver_power driver_canbus"
TWOCOMP_OVL=/tmp/twocomp-etc

twocomp_net() {
	modprobe virtio_net 2>/dev/null
	wait_path /sys/class/net/eth0 10 || { echo "twocomp: no eth0" >&2; return 1; }
	ip link set lo up && ip link set eth0 up || return 1
	ip addr add "$1/16" dev eth0 || return 1
	ip route add 224.0.0.0/4 dev eth0 || return 1
	mkdir -p "$TWOCOMP_OVL/upper" "$TWOCOMP_OVL/work"
	grep -qw overlay /proc/filesystems || modprobe overlay || return 1
	mount -t overlay overlay -o "lowerdir=/etc,upperdir=$TWOCOMP_OVL/upper,workdir=$TWOCOMP_OVL/work" /etc || return 1
	mkdir -p /etc/advee && cp "$VMTEST_REPO/userland/msgs/conf/lcm.conf" /etc/advee/lcm.conf
}

# twocomp_clock OFFSET_S: this guest's clock = the host's + OFFSET_S. The
# host's time comes from the modification time the host gives a file touched
# in the results share (a guest's own clock at boot is the emulated RTC's,
# whole seconds off from the other guest's).
twocomp_clock() {
	local f=$TWOCOMP_SHARE/clock.$$ t
	touch "$f" && t=$(stat -c %.6Y "$f") && rm -f "$f" || return 1
	date -s "@$(awk -v t="$t" -v o="$1" 'BEGIN { printf "%.6f", t + o }')" >/dev/null
}

# twocomp_wait_file NAME SECONDS: the host wrote NAME into the share.
twocomp_wait_file() { wait_until "$2" test -f "$TWOCOMP_SHARE/$1"; }
