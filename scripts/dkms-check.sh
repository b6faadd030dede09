#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# dkms-check.sh: prove the DKMS packaging. Installs the module sources as
# /usr/src/advee-VERSION would be (make dkms-source, into build/dkms/src),
# runs `dkms add`, `dkms build -k KVER`, `dkms install -k KVER` against the
# headers of each supported amd64 kernel (lib.sh: AMD64_KERNELS, Debian 6.1,
# 6.12, 6.12-rt; or the ones named as arguments) in a private DKMS tree
# (--sourcetree, --dkmstree, --installtree under build/dkms/KERNEL), checks
# that exactly the production modules came out, then boots that kernel in
# the x86_64 VM (lane "dkms-KERNEL") with those .ko files and loads/unloads
# each (tests/vm/install/dkms/load.sh).
#
# usage: scripts/dkms-check.sh [KERNEL...]   e.g. 6.12-rt
# The host's /lib/modules and /var/lib/dkms are never written: dkms runs in a
# private mount namespace with throw-away overlays on both (its depmod would
# otherwise rewrite the host's index, which the VM lanes use; its signing key
# setup writes /var/lib/dkms).
set -euo pipefail
. "$(dirname "$0")/lib.sh"

command -v dkms >/dev/null || die "dkms is not installed (run: make deps)"

dkms_check_kernel() {	# NAME: one of AMD64_KERNELS
	local name=$1 work src ver opts got want unsigned ko
	amd64_kernel "$name"	# sets kver, kdir, vmlinuz, modbase
	[ -f "$kdir/Makefile" ] || die "no headers for $kver (run: make deps)"
	work=$BUILD/dkms/$name
	rm -rf "$work"
	# dkms install wants INSTALLTREE/KVER to exist, as /lib/modules/KVER would.
	mkdir -p "$work/tree" "$work/install/$kver" "$work/ovl/upper" "$work/ovl/work" \
		"$work/ovl-dkms/upper" "$work/ovl-dkms/work"

	"$TOP/scripts/install.sh" --dkms-source-only --destdir "$work/stage"
	src=$work/stage/usr/src
	ver=$(advee_version)
	opts=(-m advee -v "$ver" --sourcetree "$src" --dkmstree "$work/tree" --installtree "$work/install")

	say "dkms add / build / install advee/$ver for $kver (private trees in $work)"
	# shellcheck disable=SC2016 # expanded by the inner shell
	unshare --mount --propagation private bash -euo pipefail -c '
		mount -t overlay overlay -o "lowerdir=/lib/modules,upperdir=$1/ovl/upper,workdir=$1/ovl/work" /lib/modules
		mkdir -p /var/lib/dkms
		mount -t overlay overlay -o "lowerdir=/var/lib/dkms,upperdir=$1/ovl-dkms/upper,workdir=$1/ovl-dkms/work" /var/lib/dkms
		shift
		kver=$1 kdir=$2; shift 2
		# A kernel that is not installed here (6.12): its directory as its
		# package would leave it (depmod runs there, and dkms finds
		# scripts/sign-file through build/), in the throw-away overlay.
		if [ ! -d "/lib/modules/$kver" ]; then
			mkdir -p "/lib/modules/$kver"
			ln -s "$kdir" "/lib/modules/$kver/build"
		fi
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

	say "booting $kver with the modules DKMS installed"
	"$TOP/tests/harness/vm-x86.sh" --lane "dkms-$name" --kernel-flavour "$name" --modules "$work/modules.list" \
		--run "$TOP/tests/vm/install/dkms/load.sh"
}

if [ $# = 1 ]; then
	dkms_check_kernel "$1"
	exit 0
fi
# One process per kernel (set -e holds in each); a failure does not stop
# the others.
[ $# -gt 0 ] || set -- $AMD64_KERNELS
failed=()
for k in "$@"; do
	"$0" "$k" || failed+=("$k")
done
[ ${#failed[@]} = 0 ] || die "DKMS check failed for: ${failed[*]}"
say "DKMS builds, installs and loads on: $*"
