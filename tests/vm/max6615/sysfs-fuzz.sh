#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Random writes to every writable hwmon attribute of the max6615 driver
# (issue 26 item 2): integers in and out of range, huge and negative numbers,
# empty strings, garbage bytes, strings longer than a page, and partial
# writes (one byte per write()). Every write either succeeds or fails with a
# clean errno: EINVAL, ERANGE, or EBUSY (pwmN while its fan follows a
# temperature: docs/hwmon/max6615.rst). Afterwards every readable attribute
# reads an integer (a fan whose tach is disabled: ENODATA, as documented), the
# temperatures still read the chip, and a valid write lands in its register.
# 300 writes in make check (21 s on the debug kernel: 70 ms a write), 5,000
# with VMTEST_FUZZ_SCALE=full (make fuzz).
. "$(dirname "$0")/lib.sh"
. "$VMTEST_REPO/tests/lib/sysfs-fuzz.sh"
trap cleanup_all EXIT

n=$(fuzz_size 300 5000) || exit 1
tap_plan 7
stub_load 0x18 || { tap_diag "cannot load i2c-stub"; exit 1; }
image_load || { tap_diag "cannot preload the register image"; exit 1; }
modprobe max6615 || { tap_diag "cannot load max6615"; exit 1; }
H=$(hwmon_dir)
[ -n "$H" ] || { tap_diag "max6615 did not bind at 0x18"; exit 1; }

# The classifier itself: an errno outside the clean ones is a failure.
FZ_CLEAN_ERRNOS="Invalid argument|Numerical result out of range|Device or resource busy"
FZ_RES="Input/output error"
fz_count probe 1
FZ_RES="Numerical result out of range"
fz_count probe 2
tap_is "the check counts EIO as a failure and ERANGE as clean" "$FZ_BAD/$FZ_CLEAN" 1/1
FZ_OK=0 FZ_CLEAN=0 FZ_BAD=0 FZ_BAD_LIST=
FZ_BY_RES=()

mapfile -t wattrs < <(find "$H/" -maxdepth 1 -type f -perm -u+w ! -name uevent | sort)
mapfile -t rattrs < <(find "$H/" -maxdepth 1 -type f -perm -u+r ! -name uevent ! -name name | sort)
tap_diag "${#wattrs[@]} writable attributes: $(printf '%s ' "${wattrs[@]##*/}")"

RANDOM=6615
start=$SECONDS
for ((k = 0; k < n; k++)); do
	f=${wattrs[RANDOM % ${#wattrs[@]}]}
	fz_value
	fz_write "$f" "$FZ_VAL"
	fz_count "${f##*/}" "$FZ_VAL"
done
tap_diag "$n writes in $((SECONDS - start)) s: $FZ_OK accepted, $FZ_CLEAN refused cleanly, $FZ_BAD other"
fz_report
tap_is "every write succeeded or failed with EINVAL, ERANGE or EBUSY" "$FZ_BAD" 0
tap_ok "both accepted and refused writes were exercised" test "$FZ_OK" -gt 0 -a "$FZ_CLEAN" -gt 0

tap_ok "the driver is still bound" driver_bound
bad=
for f in "${rattrs[@]}"; do
	v=
	{ read -r v <"$f"; } 2>"$FZ_ERR"
	read -r e <"$FZ_ERR" || e=
	if [ -n "$e" ]; then
		# fanN_input of a fan whose tach fuzzing disabled: ENODATA (ABI)
		[[ ${f##*/} =~ ^fan[12]_input$ && $e == *"No data available" ]] || bad+=" ${f##*/}:${e##*: }"
	elif ! [[ $v =~ ^-?[0-9]+$ ]]; then
		bad+=" ${f##*/}=$v"
	fi
done
tap_is "every readable attribute reads an integer afterwards" "$bad" ""
read -r t1 <"$H/temp1_input"
read -r t2 <"$H/temp2_input"
tap_is "the temperatures still read the chip" "$t1 $t2" "39625 45125"
attr_write "$H/temp1_crit" 85000
tap_is "a valid write lands: temp1_crit 85000 -> OT limit 03h" \
	"$WRITE_RES $(reg_get 0x03) $(cat "$H/temp1_crit")" "ok 0x55 85000"
tap_finish
