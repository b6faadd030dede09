#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# make install DESTDIR=...: every file lands where docs/install.md says and
# nothing else is installed; the modules are the production ones only, each
# under the release it was built for (the x86_64 build of the stock kernel,
# also when this runs on the debug lane's kernel).
. "$(dirname "$0")/lib.sh"
trap cleanup_mounts EXIT

tap_plan 5
tap_here "staging install (userland, system files, docs, modules)" stage_install --modules kmod
kver=$(ls "$DEST/lib/modules" 2>/dev/null | head -1)
tap_diag "modules staged for ${kver:-nothing}"
tap_ok "the staging tree matches the list in docs/install.md" \
	"$VMTEST_REPO/scripts/install-manifest.sh" "$DEST" "$kver"

test_only=$(cd "$DEST" && find . -name 'vmtest_*.ko' -o -name 'ts7800-sim.ko')
tap_is "no test-only module installed" "$test_only" ""
kos=$(ls "$DEST/lib/modules/$kver/extra/"*.ko 2>/dev/null)
wrong=$(for k in $kos; do v=$(modinfo -F vermagic "$k" | awk '{ print $1 }'); [ "$v" = "$kver" ] || echo "${k##*/}:$v"; done)
[ -n "$kos" ] || wrong="no module staged"
tap_is "every installed module is built for $kver" "$wrong" ""
tap_is "the sensors configuration is the project's" \
	"$(cmp "$DEST/etc/sensors.d/advee-max6615.conf" "$VMTEST_REPO/i2c-max6615/advee-max6615.conf" && echo same)" same

tap_finish
