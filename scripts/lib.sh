# SPDX-License-Identifier: GPL-2.0
# Shared helpers of the project's scripts (source it).
TOP=${TOP:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}
BUILD=${BUILD:-$TOP/build}
KSRC_DIRS="kernel tsuart-fix rs485proto i2c-max6615 tests/kmod tests/sim ts7800-can"
# ADVEE_MACHINE_CACHE: the root of the caches that outlive a clone, so that a
# fresh clone on the same machine (every CI run) reuses what earlier runs
# built or fetched: debug-kernel/ (scripts/debug-kernel.sh, ADVEE_KCACHE),
# ccache/ (scripts/build-userland.sh, ADVEE_CCACHE) and fetch/ (ADVEE_CACHE).
ADVEE_MACHINE_CACHE=${ADVEE_MACHINE_CACHE:-/var/cache/advee}
export ADVEE_MACHINE_CACHE
# ADVEE_CACHE: what the scripts fetch and extract from Debian's archive (ARM
# kernels and sysroots, the 6.12 kernels, kernel sources), in
# $ADVEE_MACHINE_CACHE/fetch (58 s at the start of each run when it was in the
# clone); .cache/ in the repository where that directory cannot be written.
# Each fetch script checks its entry against what it wants (package lists,
# stamps, paths) before reusing it.
if [ -z "${ADVEE_CACHE:-}" ]; then
	ADVEE_CACHE=$ADVEE_MACHINE_CACHE/fetch
	if ! { [ -d "$ADVEE_CACHE" ] || mkdir -p "$ADVEE_CACHE" 2>/dev/null; } ||
	   [ ! -w "$ADVEE_CACHE" ]; then
		ADVEE_CACHE=$TOP/.cache
	fi
fi
export ADVEE_CACHE

say()  { printf '==> %s\n' "$*" >&2; }
die()  { printf 'error: %s\n' "$*" >&2; exit 1; }
# advee_version: the version of the build and of every package, from its one
# source, the newest entry of debian/changelog (docs/command-line.md).
advee_version() { dpkg-parsechangelog -l "$TOP/debian/changelog" -S Version; }

# arm_tree DEBARCH FLAVOUR: root of the extracted Debian ARM kernel packages.
arm_tree() { "$TOP/scripts/fetch-arm-kernel.sh" "$1" "$2"; }

# cross prefix per Debian architecture
cross_prefix() {
	case $1 in
	armhf) echo arm-linux-gnueabihf- ;;
	armel|armel-*) echo arm-linux-gnueabi- ;;
	x86_64|native) echo "" ;;
	*) die "unknown target $1" ;;
	esac
}

# kernel flavour per Debian ARM architecture
arm_flavour() {
	case $1 in
	armhf) echo armmp ;;
	armel) echo marvell ;;
	*) die "no ARM flavour for $1" ;;
	esac
}

# arm_target_flavour TARGET: the Debian kernel flavour of an ARM build target
# (build-kmod.sh): armhf and armel are the architectures' own (arm_flavour),
# armel-rpi is armel's rpi kernel, which the armel VM lane boots
# (vm-arm.sh --arch armel: QEMU has no machine for the marvell kernel).
arm_target_flavour() {
	case $1 in
	armel-rpi) echo rpi ;;
	*) arm_flavour "$1" ;;
	esac
}

# private_apt DIR DEBARCH [SUITE]: set the array apt_opts to apt's options
# for a private apt of DEBARCH under DIR: its own lists, an empty dpkg status
# and as sources the Debian ones of this machine, or only SUITE (e.g.
# bookworm-backports) of the machine's Debian mirror. The machine's own apt
# (its sources, lists and dpkg status) is never touched.
private_apt() {
	local dir=$1 debarch=$2 suite=${3:-} f uri found=0
	mkdir -p "$dir/lists/partial" "$dir/sources" "$dir/apt-cache/archives/partial"
	[ -e "$dir/status" ] || : >"$dir/status"
	if [ -n "$suite" ]; then
		uri=$(sed -n 's|^URIs: *\(http[^ ]*/debian/\{0,1\}\)$|\1|p' /etc/apt/sources.list.d/debian.sources 2>/dev/null | head -1)
		printf 'Types: deb\nURIs: %s\nSuites: %s\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n' \
			"${uri:-http://deb.debian.org/debian}" "$suite" >"$dir/sources/$suite.sources"
	else
		# Only Debian's own sources: third-party repositories rarely carry ARM.
		for f in /etc/apt/sources.list.d/debian.sources /etc/apt/sources.list; do
			if [ -s "$f" ] && grep -qi 'debian' "$f"; then
				cp "$f" "$dir/sources/$(basename "$f")"
				found=1
			fi
		done
		[ "$found" = 1 ] || die "no Debian apt sources on this machine"
	fi
	[ -f "$dir/sources/sources.list" ] || : >"$dir/sources/sources.list"
	apt_opts=(-q -oAPT::Architecture="$debarch" -oAPT::Architectures="$debarch"
		-oDir::State::Lists="$dir/lists" -oDir::State::status="$dir/status"
		-oDir::Etc::SourceParts="$dir/sources" -oDir::Etc::SourceList="$dir/sources/sources.list"
		-oDir::Cache="$dir/apt-cache" -oDebug::NoLocking=1 -oAPT::Sandbox::User=root)
}

# arm_apt_opts DEBARCH: set the array apt_opts to apt's options for the
# private DEBARCH setup of fetch-arm-kernel.sh under the cache, running that
# script first when the lists are not there yet.
arm_apt_opts() {
	local cache=$ADVEE_CACHE/arm/$1
	if ! compgen -G "$cache/lists/*_Packages*" >/dev/null; then
		"$TOP/scripts/fetch-arm-kernel.sh" "$1" "$(arm_flavour "$1")" >/dev/null
	fi
	private_apt "$cache" "$1"
}

# The amd64 kernels the modules are built and tested for (docs/kernels.md):
# 6.1 is Debian 12's (installed on this machine, scripts/kver.sh), 6.12 and
# 6.12-rt (PREEMPT_RT) come from bookworm-backports (fetch-bpo-kernel.sh).
AMD64_KERNELS="6.1 6.12 6.12-rt"

# amd64_kernel_of TARGET: the kernel of a build target of build-kmod.sh
# (x86_64 is 6.1's, x86_64-NAME is NAME's); amd64_target NAME: the reverse.
amd64_kernel_of() {
	case $1 in
	x86_64) echo 6.1 ;;
	*) echo "${1#x86_64-}" ;;
	esac
}
amd64_target() {
	case $1 in
	6.1) echo x86_64 ;;
	*) echo "x86_64-$1" ;;
	esac
}

# amd64_kernel NAME: set kver (release), kdir (headers), vmlinuz and modbase
# (the root holding lib/modules/KVER; empty: this machine's) for one of
# AMD64_KERNELS.
amd64_kernel() {
	local root
	case $1 in
	6.1)
		kver=$("$TOP/scripts/kver.sh")
		kdir=/usr/src/linux-headers-$kver vmlinuz=/boot/vmlinuz-$kver modbase= ;;
	6.12|6.12-rt)
		root=$("$TOP/scripts/fetch-bpo-kernel.sh") || die "cannot fetch the 6.12 kernels"
		kver=$(cat "$root/release-$([ "$1" = 6.12-rt ] && echo rt-amd64 || echo amd64)")
		kdir=$root/usr/src/linux-headers-$kver vmlinuz=$root/boot/vmlinuz-$kver modbase=$root ;;
	*) die "unknown kernel $1 (one of: $AMD64_KERNELS)" ;;
	esac
}
