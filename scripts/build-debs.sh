#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# build-debs.sh [native|armhf|armel] [--out DIR]: Debian packages from a
# staging install (scripts/install.sh), built with dpkg-deb into build/debs/
# (or DIR):
#   advee_VERSION_ARCH.deb       userland, udev rules, systemd units, sysusers,
#                                networkd, sensors and default configuration
#                                (everything of /etc is a conffile); Depends
#                                from the sonames its ELF files need
#   advee-dkms_VERSION_all.deb   the module sources in /usr/src/advee-VERSION,
#                                built and installed by DKMS on installation
# Needs the build of that architecture (make / make ARCH=arm).
set -euo pipefail
. "$(dirname "$0")/lib.sh"

variant=native
out=$BUILD/debs
while [ $# -gt 0 ]; do
	case $1 in
	--out) out=$2; shift 2 ;;
	native|armhf|armel) variant=$1; shift ;;
	*) die "build-debs.sh: unknown argument $1" ;;
	esac
done
case $variant in
native) debarch=$(dpkg --print-architecture) ;;
armhf|armel) debarch=$variant ;;
*) die "build-debs.sh: native, armhf or armel, not $variant" ;;
esac
ver=$(sed -n 's/^PACKAGE_VERSION="\(.*\)"$/\1/p' "$TOP/dkms/dkms.conf")
mkdir -p "$out"

# soname_package SONAME: the Debian package shipping it (for the target arch).
declare -A soname_pkg=(
	[libc.so.6]=libc6 [libm.so.6]=libc6 [libstdc++.so.6]=libstdc++6 [libgcc_s.so.1]=libgcc-s1
	[ld-linux-armhf.so.3]=libc6 [ld-linux.so.3]=libc6 [ld-linux-x86-64.so.2]=libc6
)
soname_package() {
	local so=$1 deb
	[ -n "${soname_pkg[$so]:-}" ] && { echo "${soname_pkg[$so]}"; return; }
	if [ "$variant" = native ]; then
		dpkg -S "*/$so" 2>/dev/null | head -1 | cut -d: -f1
	else
		for deb in "${ADVEE_CACHE:-$TOP/.cache}/arm/$variant"/sysroot-debs/*.deb; do
			dpkg-deb -c "$deb" | grep -q "/$so\$" && { dpkg-deb -f "$deb" Package; return; }
		done
	fi
}

# --- advee: user space and system integration --------------------------------
stage=$out/stage-$debarch
rm -rf "$stage"
"$TOP/scripts/install.sh" --destdir "$stage" --arch "$variant" --modules none
mkdir -p "$stage/DEBIAN"
# Like dh_strip: the package carries no debug information.
strip_tool=$(cross_prefix "$variant")strip
find "$stage" -type f -exec sh -c 'head -c 4 "$1" | grep -q ELF' _ {} \; -print0 |
	xargs -0 -r "$strip_tool" --strip-unneeded --remove-section=.comment --remove-section=.note 2>/dev/null || true
deps="systemd, udev, util-linux, lm-sensors"
sonames=$(find "$stage" -type f -exec sh -c 'head -c 4 "$1" | grep -q ELF' _ {} \; -print0 |
	xargs -0 -r readelf -d 2>/dev/null | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' | sort -u)
# Native: one dpkg -S for every soname not in the table (it reads the whole
# files database each time, which is slow on the VM's 9p root).
if [ "$variant" = native ]; then
	ask=()
	for so in $sonames; do [ -n "${soname_pkg[$so]:-}" ] || ask+=("*/$so"); done
	if [ "${#ask[@]}" -gt 0 ]; then
		while IFS= read -r line; do
			pkg=${line%%:*} path=${line#*: }
			soname_pkg[${path##*/}]=$pkg
		done < <(dpkg -S "${ask[@]}" 2>/dev/null)
	fi
fi
for so in $sonames; do
	p=$(soname_package "$so")
	[ -n "$p" ] || die "no package found for $so"
	case ", $deps, " in *", $p, "*) ;; *) deps="$deps, $p" ;; esac
done
cat >"$stage/DEBIAN/control" <<EOF
Package: advee
Version: $ver
Architecture: $debarch
Maintainer: Advee low-level stack <advee@localhost>
Section: misc
Priority: optional
Depends: $deps
Recommends: advee-dkms (= $ver)
Description: Advee robot low level: daemons, tools, udev rules, systemd units
 User space of the Advee robot's low-level stack (RS-485 and CAN drivers,
 supervisor, tools) and its system integration: /dev/rs485/<bus> names,
 the n_rs485 attach service, group advee, CAN bring-up, sensors labels.
 See /usr/share/doc/advee/install.md.
EOF
(cd "$stage" && find etc -type f 2>/dev/null | sed 's|^|/|') >"$stage/DEBIAN/conffiles"
[ -s "$stage/DEBIAN/conffiles" ] || rm -f "$stage/DEBIAN/conffiles"
# DPKG_ROOT: installation into another root (dpkg --root with
# --force-script-chrootless) creates the user there and leaves the running
# system alone.
cat >"$stage/DEBIAN/postinst" <<'EOF'
#!/bin/sh
set -e
if [ "$1" = configure ]; then
	systemd-sysusers --root="${DPKG_ROOT:-/}" "${DPKG_ROOT}/usr/lib/sysusers.d/advee.conf"
	if [ -z "$DPKG_ROOT" ]; then
		udevadm control --reload || true
		systemctl daemon-reload || true
	fi
fi
EOF
cat >"$stage/DEBIAN/postrm" <<'EOF'
#!/bin/sh
set -e
if [ -z "$DPKG_ROOT" ]; then
	systemctl daemon-reload 2>/dev/null || true
	udevadm control --reload 2>/dev/null || true
fi
EOF
chmod 0755 "$stage/DEBIAN/postinst" "$stage/DEBIAN/postrm"
dpkg-deb --root-owner-group --build "$stage" "$out/advee_${ver}_$debarch.deb" >/dev/null
say "$out/advee_${ver}_$debarch.deb (Depends: $deps)"

# --- advee-dkms: the module sources -------------------------------------------
dstage=$out/stage-dkms
rm -rf "$dstage"
"$TOP/scripts/install.sh" --dkms-source-only --destdir "$dstage"
mkdir -p "$dstage/DEBIAN"
cat >"$dstage/DEBIAN/control" <<EOF
Package: advee-dkms
Version: $ver
Architecture: all
Maintainer: Advee low-level stack <advee@localhost>
Section: kernel
Priority: optional
Depends: dkms
Description: Advee robot low level: kernel modules (DKMS source)
 TS-7800 FPGA core, TS-UART, DIO gpiochip and bit-banged I2C, n_rs485 line
 discipline, MAX6615 hwmon driver, TS-CAN1; built by DKMS for every
 installed kernel that has headers.
EOF
# What dh_dkms generates: the common postinst of Debian's dkms package.
cat >"$dstage/DEBIAN/postinst" <<EOF
#!/bin/sh
set -e
if [ "\$1" = configure ]; then
	/usr/lib/dkms/common.postinst advee $ver "" "" "\$2"
fi
EOF
cat >"$dstage/DEBIAN/prerm" <<EOF
#!/bin/sh
set -e
case "\$1" in remove|upgrade|deconfigure)
	if dkms status -m advee -v $ver | grep -q .; then dkms remove -m advee -v $ver --all; fi ;;
esac
EOF
chmod 0755 "$dstage/DEBIAN/postinst" "$dstage/DEBIAN/prerm"
dpkg-deb --root-owner-group --build "$dstage" "$out/advee-dkms_${ver}_all.deb" >/dev/null
say "$out/advee-dkms_${ver}_all.deb"
