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

# arm_apt_opts DEBARCH: set the array apt_opts to apt's options for the
# private DEBARCH setup of fetch-arm-kernel.sh under the cache (its lists,
# sources and an empty dpkg status: the machine's own apt is never touched),
# running that script first when the lists are not there yet.
arm_apt_opts() {
	local cache=${ADVEE_CACHE:-$TOP/.cache}/arm/$1
	if ! compgen -G "$cache/lists/*_Packages*" >/dev/null; then
		"$TOP/scripts/fetch-arm-kernel.sh" "$1" "$(arm_flavour "$1")" >/dev/null
	fi
	mkdir -p "$cache/apt-cache/archives/partial"
	apt_opts=(-q -oAPT::Architecture="$1" -oAPT::Architectures="$1"
		-oDir::State::Lists="$cache/lists" -oDir::State::status="$cache/status"
		-oDir::Etc::SourceParts="$cache/sources" -oDir::Etc::SourceList="$cache/sources/sources.list"
		-oDir::Cache="$cache/apt-cache" -oDebug::NoLocking=1 -oAPT::Sandbox::User=root)
}
