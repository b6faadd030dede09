#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# demo-guest.sh: what `make demo` runs inside the VM until the live robot demo
# exists: load every module of the project, show what each one registered, and
# unload them again.
set -u
mods=()
while read -r ko; do [ -n "$ko" ] && mods+=("$(basename "$ko" .ko)"); done <"$VMTEST_MODULES"

echo "Advee low-level stack on $(uname -sr) ($(uname -m)), ${#mods[@]} project module(s)"
printf '%-14s %-9s %s\n' MODULE SIZE DESCRIPTION
before_dev=$(ls /dev | sort)
before_tty=$(ls /sys/class/tty | sort)
rc=0
for m in "${mods[@]}"; do
	if ! out=$(modprobe "$m" 2>&1); then
		printf '%-14s %-9s %s\n' "$m" "-" "LOAD FAILED: $out"
		rc=1
		continue
	fi
	size=$(awk -v m="${m//-/_}" '$1 == m { print $2 }' /proc/modules)
	printf '%-14s %-9s %s\n' "$m" "$size" "$(modinfo -F description "$m" | head -1)"
done
sleep 0.5	# devtmpfs and sysfs settle
echo
echo "New device nodes:   $(comm -13 <(echo "$before_dev") <(ls /dev | sort) | tr '\n' ' ')"
echo "New ttys:           $(comm -13 <(echo "$before_tty") <(ls /sys/class/tty | sort) | tr '\n' ' ')"
echo "Line disciplines:   $(tr '\n' ',' </proc/tty/ldiscs | sed 's/ \+/ /g; s/,$//')"
echo "hwmon chips:        $(cat /sys/class/hwmon/*/name 2>/dev/null | tr '\n' ' ')"
echo
for ((i = ${#mods[@]} - 1; i >= 0; i--)); do
	modprobe -r "${mods[i]}" 2>/dev/null
done
for m in "${mods[@]}"; do
	if grep -q "^${m//-/_} " /proc/modules; then
		echo "still loaded after unload: $m"
		rc=1
	fi
done
[ $rc = 0 ] && echo "All ${#mods[@]} modules loaded and unloaded cleanly."
exit $rc
