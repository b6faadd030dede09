#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# The Debian packages (scripts/build-debs.sh, in build/debs: make check builds
# them before the VM lanes) installed, upgraded, removed and purged with dpkg
# in a chroot: a writable overlay of the guest's root (the host's Debian, so
# every dependency is there) with an empty dpkg database of its own (the
# host's, thousands of packages read over 9p under TCG, took dpkg minutes
# per call; the dependencies are then --force-depends). No systemd runs in
# the guest (PID 1 is the test runner): deb-systemd-invoke in the chroot is a
# shim that logs what the maintainer scripts ask of it, and
# /run/systemd/system exists for the scripts to ask; systemctl is the real
# one, which enables (preset) in a chroot and ignores the rest. The test sees
# the unit enabled (the symlink), started on installation, restarted on
# upgrade, stopped on removal, and the symlinks gone on purge.
# The upgrade is to the same packages with a higher version (repacked with
# dpkg-deb, uncompressed: the cheapest to write under TCG; a rebuild would
# take the lane minutes); an edited conffile must survive it. advee-dkms is
# not installed here (its postinst would build the modules for every kernel
# with headers; scripts/dkms-check.sh covers dkms).
. "$(dirname "$0")/lib.sh"
C=/tmp/debs-chroot.$$
DEBS=$VMTEST_BUILD/debs
cleanup() {
	local m
	for m in "$C/proc" "$C/dev" "$C/sys" "$C"; do umount "$m" 2>/dev/null || umount -l "$m" 2>/dev/null; done
	rm -rf "$C" "$C.ovl"
	cleanup_mounts
}
trap cleanup EXIT

tap_plan 17
deb=$(ls "$DEBS"/advee_*_amd64.deb 2>/dev/null)
sim=$(ls "$DEBS"/advee-sim_*_amd64.deb 2>/dev/null)
dev=$(ls "$DEBS"/libadvee-dev_*_amd64.deb 2>/dev/null)
if [ -z "$deb" ] || [ -z "$sim" ] || [ -z "$dev" ]; then
	tap_diag "no packages in $DEBS (scripts/build-debs.sh; make check builds them first)"
	exit 1
fi
ver=$(dpkg-deb -f "$deb" Version)

# chroot_setup: the overlay, /proc /dev /sys, the shims, the packages.
chroot_setup() {
	mkdir -p "$C" "$C.ovl/upper" "$C.ovl/work" || return 1
	grep -qw overlay /proc/filesystems || modprobe overlay || return 1
	mount -t overlay overlay -o "lowerdir=/,upperdir=$C.ovl/upper,workdir=$C.ovl/work" "$C" || return 1
	mount --bind /proc "$C/proc" && mount --bind /dev "$C/dev" && mount --bind /sys "$C/sys" || return 1
	rm -rf "$C/var/lib/dpkg" && mkdir -p "$C"/var/lib/dpkg/{info,updates,triggers} || return 1
	: >"$C/var/lib/dpkg/status" && : >"$C/var/lib/dpkg/available" || return 1
	mkdir -p "$C/run/systemd/system" "$C/tmp/debs" || return 1
	: >"$C/tmp/systemd-calls"
	rm -f "$C/usr/bin/deb-systemd-invoke"
	printf '#!/bin/sh\necho "deb-systemd-invoke $*" >>/tmp/systemd-calls\n' >"$C/usr/bin/deb-systemd-invoke" &&
		chmod 0755 "$C/usr/bin/deb-systemd-invoke" || return 1
	cp "$deb" "$sim" "$dev" "$C/tmp/debs/" || return 1
	# The upgrade: the same files with a higher version.
	local d
	for d in "$C"/tmp/debs/*.deb; do
		rm -rf "$C/tmp/repack" && dpkg-deb -R "$d" "$C/tmp/repack" || return 1
		sed -i "s/^Version: .*/Version: $ver+upgrade1/; s/(= $ver)/(= $ver+upgrade1)/" "$C/tmp/repack/DEBIAN/control"
		mkdir -p "$C/tmp/debs-new"
		dpkg-deb --root-owner-group -Znone -b "$C/tmp/repack" "$C/tmp/debs-new/" >/dev/null || return 1
	done
}
in_chroot() { chroot "$C" "$@"; }
calls() { cat "$C/tmp/systemd-calls"; }
installed_version() { in_chroot dpkg-query -W -f '${Status} ${Version}' "$1" 2>/dev/null; }
wanted=/etc/systemd/system/multi-user.target.wants/advee-watchdog.service

tap_here "chroot: overlay of the guest's root with a shim for deb-systemd-invoke" chroot_setup
tap_here "dpkg -i advee advee-sim libadvee-dev $ver" in_chroot sh -c 'dpkg -i --force-depends /tmp/debs/*.deb'
tap_is "all three installed" "$(installed_version advee), $(installed_version advee-sim), $(installed_version libadvee-dev)" \
	"install ok installed $ver, install ok installed $ver, install ok installed $ver"
missing=$(in_chroot dpkg -L advee advee-sim libadvee-dev | while read -r f; do [ -e "$C$f" ] || echo "$f"; done)
tap_is "every file of the packages is in place" "$missing" ""
tap_ok "user and group advee created (dh_installsysusers)" \
	sh -c "grep -q '^advee:' '$C/etc/passwd' && grep -q '^advee:' '$C/etc/group'"
tap_is "advee-watchdog.service enabled (deb-systemd-helper)" "$(readlink "$C$wanted")" /lib/systemd/system/advee-watchdog.service
tap_ok "advee-watchdog.service started by the postinst" grep -qx 'deb-systemd-invoke start advee-watchdog.service' "$C/tmp/systemd-calls"
tap_is "the per-daemon units are not enabled (they conflict with the supervisor)" \
	"$(cd "$C/etc/systemd/system/multi-user.target.wants" && find . -name 'driver_*')" ""
tap_is "advee-rs485ctl --version from the package" "$(in_chroot advee-rs485ctl --version)" "advee-rs485ctl $ver"

# Upgrade: an edited conffile stays, the daemon is restarted.
echo "# edited by the administrator" >>"$C/etc/advee/watchdog.yaml"
: >"$C/tmp/systemd-calls"
tap_here "dpkg -i the upgrade ($ver+upgrade1)" in_chroot sh -c 'dpkg -i --force-depends --force-confold /tmp/debs-new/*.deb'
tap_is "advee upgraded" "$(installed_version advee)" "install ok installed $ver+upgrade1"
tap_ok "the edited conffile survived the upgrade" grep -qx '# edited by the administrator' "$C/etc/advee/watchdog.yaml"
tap_ok "advee-watchdog.service restarted on upgrade" grep -qx 'deb-systemd-invoke restart advee-watchdog.service' "$C/tmp/systemd-calls"
calls | sed 's/^/# upgrade: /'

# Remove: the daemon stopped, the programs gone, the configuration kept.
: >"$C/tmp/systemd-calls"
tap_here "dpkg -r advee-sim libadvee-dev advee" in_chroot dpkg -r --force-depends advee-sim libadvee-dev advee
tap_ok "advee-watchdog.service stopped on removal, /usr/sbin/advee-watchdog gone, /etc/advee kept" \
	sh -c "grep -qx 'deb-systemd-invoke stop advee-watchdog.service' '$C/tmp/systemd-calls' &&
		[ ! -e '$C/usr/sbin/advee-watchdog' ] && [ -f '$C/etc/advee/watchdog.yaml' ]"
calls | sed 's/^/# remove: /'

# Purge: configuration and the unit's symlinks gone.
tap_here "dpkg --purge advee" in_chroot dpkg --purge advee
tap_ok "after purge: no /etc/advee, no enablement symlink, no dpkg record" \
	sh -c "[ ! -e '$C/etc/advee' ] && [ ! -L '$C$wanted' ] && ! chroot '$C' dpkg-query -W advee >/dev/null 2>&1"
tap_finish
