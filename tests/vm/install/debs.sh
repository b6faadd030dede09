#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# scripts/build-debs.sh: the advee package installs with dpkg into an empty
# root (maintainer scripts chrootless, DPKG_ROOT set): its files are the
# staging install's, /etc files are conffiles, the postinst creates user and
# group advee in that root; removing it removes the files. The advee-dkms
# package holds the DKMS source tree without the test-only modules.
. "$(dirname "$0")/lib.sh"
trap cleanup_mounts EXIT
OUT=$VMTEST_SCRATCH/debs
R=$VMTEST_SCRATCH/dpkgroot

tap_plan 8
overlay_rw "$VMTEST_BUILD/userland" || { tap_diag "cannot overlay the userland build"; exit 1; }
tap_ok "build-debs.sh builds both packages" "$VMTEST_REPO/scripts/build-debs.sh" native --out "$OUT"
deb=$(ls "$OUT"/advee_*_amd64.deb 2>/dev/null)
dkms_deb=$(ls "$OUT"/advee-dkms_*_all.deb 2>/dev/null)

mkdir -p "$R/var/lib/dpkg/info" "$R/var/lib/dpkg/updates"
: >"$R/var/lib/dpkg/status"
tap_ok "dpkg -i advee into an empty root" \
	dpkg --root="$R" --force-script-chrootless --force-depends -i "$deb"
# Compared lists must not be empty: two empty lists would be equal.
staged=$(cd "$OUT/stage-amd64" && find usr etc -type f | sort)
[ -n "$staged" ] || staged="(no staged file)"
tap_is "installed files = the staging install (minus modules)" \
	"$(cd "$R" && find usr etc -type f | grep -v '^etc/\(passwd\|group\|shadow\|gshadow\|\.pwd\.lock\)$' | sort)" \
	"$staged"
conffiles=$(dpkg-deb -I "$deb" conffiles | sort)
[ -n "$conffiles" ] || conffiles="(no conffile)"
tap_is "every /etc file is a conffile" \
	"$conffiles" "$(cd "$OUT/stage-amd64" && find etc -type f | sed 's|^|/|' | sort)"
both_advee() { grep -q '^advee:' "$R/etc/group" && grep -q '^advee:' "$R/etc/passwd"; }
tap_ok "postinst created user and group advee in that root (DPKG_ROOT)" both_advee
tap_ok "dpkg -r removes it" dpkg --root="$R" --force-script-chrootless -r advee
tap_is "only the conffiles stay after removal (dpkg -r, not --purge)" \
	"$(cd "$R" && find usr etc -type f 2>/dev/null | grep -v '^etc/\(passwd\|group\|shadow\|gshadow\|\.pwd\.lock\)$' | sort)" \
	"$(printf '%s\n' "$conffiles" | sed 's|^/||')"

src=$(dpkg-deb -c "$dkms_deb" | awk '{ print $6 }')
tap_is "advee-dkms: dkms.conf, no test-only source" \
	"$(grep -c '/usr/src/advee-.*/dkms\.conf$' <<<"$src") $(grep -c 'tests/' <<<"$src")" "1 0"
tap_finish
