#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# dkms-check.sh: prove the DKMS packaging. Installs the module sources as
# /usr/src/advee-VERSION would be (make dkms-source, into build/dkms/src),
# runs `dkms add`, `dkms build -k KVER`, `dkms install -k KVER` against
# Debian's 6.1 amd64 headers in a private DKMS tree (--sourcetree,
# --dkmstree, --installtree under build/dkms), checks that exactly the
# production modules came out, then boots the x86_64 VM (lane "dkms") with
# those .ko files and loads/unloads each (tests/vm/install/dkms/load.sh).
# The host's /lib/modules and /var/lib/dkms are never written: dkms runs in a
# private mount namespace with throw-away overlays on both (its depmod would
# otherwise rewrite the host's index, which the VM lanes use; its signing key
# setup writes /var/lib/dkms).
set -euo pipefail
. "$(dirname "$0")/lib.sh"

kver=${KVER:-$("$TOP/scripts/kver.sh")}
kdir=/usr/src/linux-headers-$kver
[ -f "$kdir/Makefile" ] || die "no headers for $kver (run: make deps)"
command -v dkms >/dev/null || die "dkms is not installed (run: make deps)"
work=$BUILD/dkms
rm -rf "$work"
# dkms install wants INSTALLTREE/KVER to exist, as /lib/modules/KVER would.
mkdir -p "$work/tree" "$work/install/$kver" "$work/ovl/upper" "$work/ovl/work" \
	"$work/ovl-dkms/upper" "$work/ovl-dkms/work"

"$TOP/scripts/install.sh" --dkms-source-only --destdir "$work/stage"
src=$work/stage/usr/src
ver=$(sed -n 's/^PACKAGE_VERSION="\(.*\)"$/\1/p' "$TOP/dkms/dkms.conf")
opts=(-m advee -v "$ver" --sourcetree "$src" --dkmstree "$work/tree" --installtree "$work/install")

say "dkms add / build / install advee/$ver for $kver (private trees in $work)"
# shellcheck disable=SC2016 # expanded by the inner shell
unshare --mount --propagation private bash -euo pipefail -c '
	mount -t overlay overlay -o "lowerdir=/lib/modules,upperdir=$1/ovl/upper,workdir=$1/ovl/work" /lib/modules
	mkdir -p /var/lib/dkms
	mount -t overlay overlay -o "lowerdir=/var/lib/dkms,upperdir=$1/ovl-dkms/upper,workdir=$1/ovl-dkms/work" /var/lib/dkms
	shift
	kver=$1 kdir=$2; shift 2
	dkms add "$@"
	dkms build "$@" -k "$kver" --kernelsourcedir "$kdir"
	dkms install "$@" -k "$kver" --kernelsourcedir "$kdir" --force
	dkms status "$@"
' _ "$work" "$kver" "$kdir" "${opts[@]}" 2>&1 | tee "$work/dkms.log"

find "$work/install" -name '*.ko' | sort >"$work/modules.list"
got=$(xargs -r -n1 basename <"$work/modules.list" | sed 's/\.ko$//' | sort | tr '\n' ' ')
want=$(bash -c '. "$1"; printf "%s\n" "${BUILT_MODULE_NAME[@]}"' _ "$TOP/dkms/dkms.conf" | sort | tr '\n' ' ')
say "dkms installed: $got"
[ "$got" = "$want" ] || die "dkms installed [$got], dkms.conf lists [$want]"
# DKMS signed them (its MOK, as on a Secure Boot machine).
unsigned=$(while read -r ko; do [ -n "$(modinfo -F signer "$ko")" ] || basename "$ko"; done <"$work/modules.list")
[ -z "$unsigned" ] || die "not signed by dkms: $unsigned"
# Nothing leaked into the host's trees.
while read -r ko; do
	[ ! -e "/lib/modules/$kver/updates/dkms/${ko##*/}" ] ||
		die "${ko##*/} appeared in the host's /lib/modules/$kver/updates/dkms"
done <"$work/modules.list"
[ ! -e /var/lib/dkms/advee ] || die "/var/lib/dkms/advee exists: dkms used the host's tree"

say "booting the VM with the modules DKMS installed"
"$TOP/tests/harness/vm-x86.sh" --lane dkms --kver "$kver" --modules "$work/modules.list" \
	--run "$TOP/tests/vm/install/dkms/load.sh"
