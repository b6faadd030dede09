#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# install.sh [--destdir DIR] [--arch native|armhf|armel] [--modules kmod|dkms|none]
#            [--userland-build DIR|none] [--dkms-source-only]
# Install the Advee stack from the build tree (make; make ARCH=arm for ARM):
#   userland      cmake --install of build/userland[-ARCH] (prefix /usr, /etc;
#                 --userland-build another build dir, or none)
#   system files  udev rules, systemd units, systemd-networkd CAN file,
#                 sysusers.d, modules-load.d, /etc/sensors.d/advee-max6615.conf
#   docs          /usr/share/doc/advee/
#   modules       kmod: the production .ko files of build/kmod/ARCH into
#                 /lib/modules/KVER/extra (test-only modules never);
#                 dkms: the module sources into /usr/src/advee-VERSION/ (the
#                 DKMS source tree; without --destdir also dkms add/build/install)
# DESTDIR (or --destdir) stages everything under DIR and touches nothing else;
# without it the live system is changed and the post-install steps run
# (systemd-sysusers, depmod, udevadm control --reload, systemctl daemon-reload).
# docs/install.md lists every file this puts in place.
set -euo pipefail
. "$(dirname "$0")/lib.sh"

destdir=${DESTDIR:-}
arch=native
modules=kmod
dkms_source_only=0
ubuild=
while [ $# -gt 0 ]; do
	case $1 in
	--destdir) destdir=$2; shift 2 ;;
	--arch) arch=$2; shift 2 ;;
	--modules) modules=$2; shift 2 ;;
	--userland-build) ubuild=$2; shift 2 ;;
	--dkms-source-only) dkms_source_only=1; shift ;;
	-h|--help) sed -n '3,21p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
	*) die "install.sh: unknown argument $1 (see --help)" ;;
	esac
done
case $modules in kmod|dkms|none) ;; *) die "--modules kmod|dkms|none, not $modules" ;; esac
[ -z "$destdir" ] || destdir=$(mkdir -p "$destdir" && cd "$destdir" && pwd)
D=$destdir

# inst MODE SRC DEST: one file, parents created (like install -D).
inst() { install -D -m "$1" "$2" "$D$3"; }

# production_modules: "dir name" of every module the robot gets: the obj-m
# and obj-$(CONFIG_...) lines of the Kbuild source dirs outside tests/
# (tests/kmod, tests/sim carry MODULE_INFO(test, "Y") and are never installed).
production_dirs() { for d in $KSRC_DIRS; do case $d in tests|tests/*) ;; *) echo "$d" ;; esac; done; }
production_modules() {
	local d
	for d in $(production_dirs); do
		sed -n 's/^obj-[^[:space:]]*[[:space:]]*+=[[:space:]]*\(.*\)\.o[[:space:]]*$/\1/p' "$TOP/$d/Kbuild" |
			while read -r m; do echo "$d $m"; done
	done
}


# check_dkms_conf: dkms.conf builds exactly the production modules.
check_dkms_conf() {
	local want have
	want=$(production_modules | awk '{ print $1 "/ " $2 }' | sort)
	have=$(bash -c '. "$1"; for i in "${!BUILT_MODULE_NAME[@]}"; do
		echo "${BUILT_MODULE_LOCATION[$i]} ${BUILT_MODULE_NAME[$i]}"; done' _ "$TOP/dkms/dkms.conf" | sort)
	if [ "$want" != "$have" ]; then
		diff <(echo "$want") <(echo "$have") | sed 's/^/    /' >&2
		die "dkms/dkms.conf does not list the production modules of the Kbuild tree (< Kbuild, > dkms.conf)"
	fi
}

# install_dkms_source: /usr/src/advee-VERSION/ = production sources + a top
# Kbuild without the test dirs + dkms.conf.
install_dkms_source() {
	local ver src d
	check_dkms_conf
	ver=$(advee_version)
	[ -n "$ver" ] || die "no version in debian/changelog"
	src=$D/usr/src/advee-$ver
	say "DKMS source tree $src"
	rm -rf "$src"
	mkdir -p "$src"
	for d in $(production_dirs); do
		mkdir -p "$src/$d"
		(cd "$TOP/$d" && find . \( -name '*.[ch]' -o -name '*.S' -o -name Kbuild \) -print0 |
			xargs -0 -r cp --parents -t "$src/$d")
	done
	# The project headers (kernel/include) come with the kernel dir; the
	# test dirs are dropped from the top Kbuild.
	grep -v '^obj-y[[:space:]]*+=[[:space:]]*tests/' "$TOP/Kbuild" >"$src/Kbuild"
	sed "s/#MODULE_VERSION#/$ver/g" "$TOP/dkms/dkms.conf" >"$src/dkms.conf"
	find "$src" -type d -exec chmod 0755 {} + && find "$src" -type f -exec chmod 0644 {} +
	echo "$ver"
}

if [ "$dkms_source_only" = 1 ]; then
	install_dkms_source >/dev/null
	exit 0
fi

# --- user space ----------------------------------------------------------------
case $arch in
native) ubuild=${ubuild:-$BUILD/userland}; kbuild=$BUILD/kmod/x86_64 ;;
armhf|armel) ubuild=${ubuild:-$BUILD/userland-$arch}; kbuild=$BUILD/kmod/$arch ;;
*) die "unknown arch $arch" ;;
esac
if [ "$ubuild" != none ]; then
	[ -f "$ubuild/cmake_install.cmake" ] || die "no userland build in $ubuild (run: make$([ "$arch" = native ] || echo ' ARCH=arm'))"
	say "userland ($arch) from $ubuild"
	DESTDIR=$D cmake --install "$ubuild" >/dev/null
fi

# --- system integration ----------------------------------------------------------
say "udev rules, systemd units, configuration, docs"
for f in 60-advee-rs485-buses.rules 61-advee-rs485.rules 61-advee-gpio.rules 62-advee-max6615.rules; do
	inst 0644 "$TOP/udev/$f" "/usr/lib/udev/rules.d/$f"
done
for f in "$TOP"/systemd/*.service; do
	inst 0644 "$f" "/usr/lib/systemd/system/${f##*/}"
done
for f in "$TOP"/systemd/*.network; do
	inst 0644 "$f" "/usr/lib/systemd/network/${f##*/}"
done
inst 0644 "$TOP/systemd/advee.conf" /usr/lib/sysusers.d/advee.conf
inst 0644 "$TOP/systemd/modules-load.conf" /usr/lib/modules-load.d/advee.conf
inst 0644 "$TOP/i2c-max6615/advee-max6615.conf" /etc/sensors.d/advee-max6615.conf
for f in "$TOP"/docs/*.md; do
	inst 0644 "$f" "/usr/share/doc/advee/${f##*/}"
done
for f in "$TOP"/docs/hwmon/*; do
	[ -f "$f" ] && inst 0644 "$f" "/usr/share/doc/advee/hwmon/${f##*/}"
done

# --- kernel modules ----------------------------------------------------------------
case $modules in
kmod)
	[ -s "$kbuild/modules.list" ] || die "no module build in $kbuild (run: make modules / make ARCH=arm)"
	# The release the modules were built for (Debian's kernel.release holds
	# the upstream version, the modules' vermagic the package's release).
	kver=$(modinfo -F vermagic "$(head -1 "$kbuild/modules.list")" | awk '{ print $1 }')
	say "modules for $kver into /lib/modules/$kver/extra"
	production_modules | while read -r d m; do
		ko=$kbuild/$d/$m.ko
		if [ ! -f "$ko" ]; then
			# obj-$(CONFIG_X): left out by a kernel without X
			grep -Eq "^obj-\\\$\(CONFIG_[A-Z0-9_]+\)[[:space:]]*\+=[[:space:]]*$m\.o" "$TOP/$d/Kbuild" &&
				{ say "  $m: not built for this kernel (its Kbuild condition is off)"; continue; }
			die "module $d/$m.ko was not built (run: make modules)"
		fi
		inst 0644 "$ko" "/lib/modules/$kver/extra/$m.ko"
	done
	[ -n "$D" ] || depmod -a "$kver"
	;;
dkms)
	ver=$(install_dkms_source)
	if [ -z "$D" ]; then
		dkms add -m advee -v "$ver"
		dkms build -m advee -v "$ver"
		dkms install -m advee -v "$ver"
	fi
	;;
none) ;;
esac

# --- post-install on the live system --------------------------------------------------
if [ -z "$D" ]; then
	say "post-install: sysusers, udev, systemd"
	systemd-sysusers advee.conf
	udevadm control --reload || true
	systemctl daemon-reload || true
	say "done; next steps: docs/install.md (enable the units, add users to group advee)"
fi
