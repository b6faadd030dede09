# SPDX-License-Identifier: GPL-2.0
# Random writes to sysfs attributes (bash; sourced by the sysfs-fuzz programs
# of the max6615 and dio-i2c suites). Everything runs in bash builtins: on the
# debug kernel every process a shell starts costs a tenth of a second.
#
#   fz_value             sets FZ_VAL to a random value: an integer near the
#                        attributes' ranges, a huge or negative number, an
#                        empty string, garbage (random bytes, numbers with
#                        trailing junk, hex, spaces), or a string longer than
#                        a page
#   fz_write FILE VALUE  writes VALUE with a newline in one write() (3 of 4)
#                        or one byte per write() (partial writes); sets FZ_RES
#                        to "ok" or the first error's text ("Invalid argument")
#   fz_count             adds FZ_RES to the counts: FZ_OK, FZ_CLEAN (an errno
#                        in FZ_CLEAN_ERRNOS), FZ_BAD (any other), FZ_BAD_LIST
#                        (the first ten: "file value -> error")
#   fz_report            prints the counts per result (TAP diagnostics)
#
# RANDOM is seeded by the caller (RANDOM=SEED): the same seed, the same writes.

FZ_ERR=${VMTEST_SCRATCH:-/tmp}/sysfs-fuzz.err
FZ_OK=0 FZ_CLEAN=0 FZ_BAD=0 FZ_BAD_LIST=
# The errnos a bad value may give: the caller may widen it (one "|"-list).
FZ_CLEAN_ERRNOS=${FZ_CLEAN_ERRNOS:-"Invalid argument|Numerical result out of range"}
declare -A FZ_BY_RES=()

FZ_HUGE=(9223372036854775807 -9223372036854775808 9223372036854775808
	-9223372036854775809 18446744073709551615 18446744073709551616
	99999999999999999999999999 2147483647 2147483648 -2147483648 -2147483649
	4294967295 4294967296 65535 65536 -1 0 -0 +0 00000000000000000000000001)
FZ_JUNK=("" " " "abc" "12abc" " 12" "12 " "0x10" "0X7f" "1e3" "+5" "--1" "-+1" "1.5"
	"٣" "nan" "inf" "-" "+" "0b101" "1,000" "1_000" "\t7" "7\t" "$(printf '\001\002\003')"
	"enable" "disable" "in" "out" "high" "low" "rising" "none" "both")

fz_rand32() { FZ_R=$(((RANDOM << 17) ^ (RANDOM << 2) ^ (RANDOM >> 13))); }

fz_value() {
	local i n s
	case $((RANDOM % 8)) in
	0 | 1) fz_rand32; FZ_VAL=$((FZ_R % 600000 - 300000)) ;;	# millidegrees, rpm, duty
	2) FZ_VAL=$((RANDOM % 300 - 20)) ;;			# small, some negative
	3) FZ_VAL=${FZ_HUGE[RANDOM % ${#FZ_HUGE[@]}]} ;;
	4) FZ_VAL=${FZ_JUNK[RANDOM % ${#FZ_JUNK[@]}]} ;;
	5)	# random bytes (no NUL: bash cannot hold one), 1..16 of them
		n=$((RANDOM % 16 + 1)) s=
		for ((i = 0; i < n; i++)); do
			printf -v s '%s\\x%02x' "$s" $((RANDOM % 255 + 1))
		done
		printf -v FZ_VAL '%b' "$s" ;;
	6) FZ_VAL=$((RANDOM % 1000))${FZ_JUNK[RANDOM % ${#FZ_JUNK[@]}]} ;;
	7)	# longer than a page, or empty
		if ((RANDOM % 2)); then
			printf -v FZ_VAL '%05000d' $((RANDOM))
		else
			FZ_VAL=
		fi ;;
	esac
}

fz_write() {
	local f=$1 v=$2 i fd=
	FZ_RES=
	if ((RANDOM % 4)); then
		{ printf '%s\n' "$v" >"$f"; } 2>"$FZ_ERR"
	else
		# partial writes: one byte per write(), each its own store()
		{
			exec {fd}>"$f" &&
				for ((i = 0; i < ${#v}; i++)); do
					printf '%s' "${v:i:1}" >&"$fd" || break
				done
			[ -n "${fd:-}" ] && exec {fd}>&-
		} 2>"$FZ_ERR"
	fi
	read -r FZ_RES <"$FZ_ERR" || true
	if [ -z "$FZ_RES" ]; then
		FZ_RES=ok
	else
		FZ_RES=${FZ_RES##*: }
	fi
}

fz_count() {	# fz_count FILE VALUE
	FZ_BY_RES[$FZ_RES]=$((${FZ_BY_RES[$FZ_RES]:-0} + 1))
	if [ "$FZ_RES" = ok ]; then
		FZ_OK=$((FZ_OK + 1))
	elif [[ $FZ_RES =~ ^($FZ_CLEAN_ERRNOS)$ ]]; then
		FZ_CLEAN=$((FZ_CLEAN + 1))
	else
		FZ_BAD=$((FZ_BAD + 1))
		[ "$FZ_BAD" -le 10 ] && printf -v FZ_BAD_LIST '%s\n# %s %q -> %s' "$FZ_BAD_LIST" "$1" "$2" "$FZ_RES"
	fi
}

fz_report() {
	local r
	for r in "${!FZ_BY_RES[@]}"; do
		printf '#   %s: %s\n' "$r" "${FZ_BY_RES[$r]}"
	done
	[ -n "$FZ_BAD_LIST" ] && printf '# writes with other errors:%s\n' "$FZ_BAD_LIST"
	return 0
}
