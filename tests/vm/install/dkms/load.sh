#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Run by scripts/dkms-check.sh only (not part of the install suite): the VM
# booted with the modules `dkms install` produced (VMTEST_MODULES lists them).
# Each loads by name from the installed tree, is the DKMS-built file (build
# ID), and unloads again.
. "$VMTEST_REPO/tests/lib/tap.sh"

mapfile -t kos <"$VMTEST_MODULES"
tap_plan $((${#kos[@]} * 2))
for ko in "${kos[@]}"; do
	m=$(basename "$ko" .ko)
	mod=${m//-/_}
	if ! grep -q "^$mod " /proc/modules; then
		modprobe "$m"
	fi
	# The loaded module's GNU build ID (the last 20 bytes of its note in
	# sysfs) is the one of the file DKMS installed: not the project's
	# ordinary build of the same sources, whose build ID differs.
	want=$(readelf -n "$ko" | awk '/Build ID:/ { print $3 }')
	got=$(od -An -tx1 -v "/sys/module/$mod/notes/.note.gnu.build-id" 2>/dev/null | tr -d ' \n' | tail -c 40)
	tap_is "$m: loaded, and it is the DKMS-built file (build ID ${want:-none})" "${got:-none}" "${want:-missing}"
	tap_ok "$m: unloads" modprobe -r "$m"
done
tap_finish
