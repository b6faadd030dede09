# SPDX-License-Identifier: GPL-2.0
# Shared helpers of the project's scripts (source it).
TOP=${TOP:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}
BUILD=${BUILD:-$TOP/build}
KSRC_DIRS="kernel tsuart-fix rs485proto i2c-max6615 tests/kmod tests/sim ts7800-can"

say()  { printf '==> %s\n' "$*" >&2; }
die()  { printf 'error: %s\n' "$*" >&2; exit 1; }

# arm_tree DEBARCH FLAVOUR: root of the extracted Debian ARM kernel packages.
arm_tree() { "$TOP/scripts/fetch-arm-kernel.sh" "$1" "$2"; }

# cross prefix per Debian architecture
cross_prefix() {
	case $1 in
	armhf) echo arm-linux-gnueabihf- ;;
	armel) echo arm-linux-gnueabi- ;;
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
