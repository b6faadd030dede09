#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# cross-modpost.sh HEADERS CROSS_COMPILE OUTDIR: build a host modpost for a
# foreign target kernel and a kbuild scripts dir that uses it.
#
# Why: Debian's amd64 linux-kbuild-6.1 ships modpost with the device-table
# offsets of amd64 (struct of_device_id is 200 bytes there, 196 on ARM), so
# every ARM module with an of_device_id table fails modpost. modpost gets its
# offsets from devicetable-offsets.c compiled for the target; we do exactly that
# with the cross compiler and the target's own headers.
# Result: OUTDIR/scripts (a copy of /usr/lib/linux-kbuild-6.1/scripts as
# symlinks, with mod/modpost replaced).
set -euo pipefail
. "$(dirname "$0")/lib.sh"

hdr=${1:?headers dir} cross=${2:?cross prefix} out=${3:?output dir}
common=$(sed -n 's/^include \(.*\)\/Makefile$/\1/p' "$hdr/Makefile")
[ -d "$common/include" ] || die "cannot find the -common headers of $hdr"
src=$("$TOP/scripts/kernel-source.sh")
kbuild=/usr/lib/linux-kbuild-6.1/scripts
work=$out/modpost-build
mkdir -p "$work"

# 1. device-table offsets, as Kbuild computes them, for the target.
inc=(-nostdinc -I"$common/arch/arm/include" -I"$hdr/arch/arm/include/generated" -I"$common/include"
	-I"$hdr/include" -I"$common/arch/arm/include/uapi" -I"$hdr/arch/arm/include/generated/uapi"
	-I"$common/include/uapi" -I"$hdr/include/generated/uapi"
	-include "$common/include/linux/kconfig.h" -D__KERNEL__)
"${cross}gcc" "${inc[@]}" -S -o "$work/devicetable-offsets.s" "$src/scripts/mod/devicetable-offsets.c"
sed -ne 's:^[[:space:]]*\.ascii[[:space:]]*"\(.*\)".*:\1:; /^->/{s:->#\(.*\):/* \1 */:; s:^->\([^ ]*\) [\$#]*\([^ ]*\) \(.*\):#define \1 \2 /* \3 */:; s:->::; p;}' \
	"$work/devicetable-offsets.s" >"$work/devicetable-offsets.h"
grep -q SIZE_of_device_id "$work/devicetable-offsets.h" || die "no device-table offsets computed"

# 2. ELF class and endianness of the target.
gcc -O2 -o "$work/mk_elfconfig" "$src/scripts/mod/mk_elfconfig.c"
"${cross}gcc" -c -o "$work/empty.o" "$src/scripts/mod/empty.c"
"$work/mk_elfconfig" <"$work/empty.o" >"$work/elfconfig.h"

# 3. modpost itself, for the host. mod_devicetable.h comes from the target's
# headers through a private include/linux next to a copy of scripts/mod.
mkdir -p "$work/scripts/mod" "$work/include/linux"
cp "$src"/scripts/mod/*.[ch] "$work/scripts/mod/"
cp "$work/devicetable-offsets.h" "$work/elfconfig.h" "$work/scripts/mod/"
cp "$common/include/linux/mod_devicetable.h" "$src/include/linux/license.h" "$work/include/linux/"
gcc -O2 -o "$work/modpost" "$work"/scripts/mod/{modpost,file2alias,sumversion}.c

# 4. a kbuild scripts dir with our modpost.
rm -rf "$out/scripts"
mkdir -p "$out/scripts/mod"
for e in "$kbuild"/*; do
	[ "$(basename "$e")" = mod ] || ln -s "$e" "$out/scripts/$(basename "$e")"
done
for e in "$kbuild"/mod/*; do
	case $(basename "$e") in modpost*) ;; *) ln -s "$e" "$out/scripts/mod/$(basename "$e")" ;; esac
done
cp "$work/modpost" "$out/scripts/mod/modpost"
echo "$out/scripts"
