# SPDX-License-Identifier: GPL-2.0
# shellcheck shell=bash
# Helpers of the install VM suite (sourced, not a test program): a staging
# install (scripts/install.sh --destdir) into the guest's tmpfs, and an
# overlay over /etc so that the installed group and udev rules can be made
# live without touching the host's root (read-only 9p in the guest).

. "$VMTEST_REPO/tests/lib/tap.sh"
. "$VMTEST_REPO/tests/lib/wait.sh"

DEST=$VMTEST_SCRATCH/root
OVL=/tmp/install-ovl.$$
MOUNTS=()

# overlay_rw DIR: a writable tmpfs layer over DIR (unmounted by cleanup_mounts).
overlay_rw() {
	local name
	name=$(echo "$1" | tr / _)
	mkdir -p "$OVL/$name/upper" "$OVL/$name/work" || return 1
	grep -qw overlay /proc/filesystems || modprobe overlay || return 1
	mount -t overlay overlay \
		-o "lowerdir=$1,upperdir=$OVL/$name/upper,workdir=$OVL/$name/work" "$1" || return 1
	MOUNTS=("$1" "${MOUNTS[@]}")
}

cleanup_mounts() {
	local m
	rm -f /run/udev/rules.d/6?-advee-*.rules
	for m in "${MOUNTS[@]}"; do umount "$m" 2>/dev/null || umount -l "$m"; done
	MOUNTS=()
	rm -rf "$OVL"
	return 0
}

# stage_install [ARGS]: scripts/install.sh into $DEST. cmake --install writes
# its install_manifest.txt into the build dir, read-only here: overlaid.
stage_install() {
	overlay_rw "$VMTEST_BUILD/userland" || return 1
	"$VMTEST_REPO/scripts/install.sh" --destdir "$DEST" "$@"
}

# tap_here DESC CMD [ARGS]: CMD as a TAP point run in this shell, its output
# as diagnostics when it fails. Not through tap_ok, whose $(...) is a
# subshell: the overlays stage_install and make_live mount must be recorded
# in this shell's MOUNTS for cleanup_mounts, or they stay mounted under the
# next program (two left over made the third overlay mount on the build
# directory fail).
tap_here() {
	local desc=$1 rc
	shift
	"$@" >"$VMTEST_SCRATCH/tap_here.log" 2>&1
	rc=$?
	[ "$rc" = 0 ] || sed 's/^/# /' "$VMTEST_SCRATCH/tap_here.log"
	tap_result "$rc" "$desc"
}

# stage_system: only the system files (udev, systemd, sysusers, configs), so
# that the rules and units are tested whatever state the userland build is in.
stage_system() {
	"$VMTEST_REPO/scripts/install.sh" --destdir "$DEST" --modules none --userland-build none
}

# make_live: the group of the installed sysusers.d file (on the /etc overlay)
# and the installed udev rules, in force for udevadm: all in /run/udev/rules.d
# (udev orders rules by file name across its directories).
make_live() {
	overlay_rw /etc || return 1
	systemd-sysusers "$DEST/usr/lib/sysusers.d/advee.conf" || return 1
	mkdir -p /run/udev/rules.d
	cp "$DEST"/usr/lib/udev/rules.d/*.rules /run/udev/rules.d/ || return 1
}

# udev_test SYSPATH: what udev would do on "add" for that device (no udevd
# needed: udevadm test runs the rules itself and executes no RUN program).
udev_test() { udevadm test --action=add "$1" 2>&1; }

# prop OUTPUT NAME: the value of a property in udevadm test's final list.
prop() { printf '%s\n' "$1" | sed -n "s/^$2=//p" | tail -1; }
