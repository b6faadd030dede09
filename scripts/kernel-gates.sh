#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# kernel-gates.sh: the kernel quality gates of the project, on every kernel
# source file (kernel/ tsuart-fix/ rs485proto/ i2c-max6615/ tests/kmod/ and
# the other Kbuild dirs in KSRC_DIRS):
#   1. W=1 builds without warnings for every supported kernel: amd64 6.1
#      (x86_64), 6.12 and 6.12 PREEMPT_RT (x86_64-6.12, x86_64-6.12-rt; from
#      bookworm-backports), armhf (armmp), armel (marvell, the TS-7800's)
#      and armel rpi (the kernel the armel VM lane boots) 6.1, each
#      checking ts-can1's copy of struct sja1000_priv against that kernel's
#      sja1000.h (ts7800-can/sja1000-layout.c), and a self-test that this
#      check rejects an altered copy;
#   2. checkpatch.pl --strict (from the newest source, bookworm-backports'
#      linux-source-6.12, extracted at build time) reports no error, warning
#      or check; the version checks of kernel/include/compat/ (one header
#      per API that differs between the kernels) are the only ones allowed;
#   3. sparse (make C=2) reports nothing, on each amd64 kernel;
#   4. one access width on the FPGA window (scripts/fpga-access-width.sh):
#      no MMIO accessor in the FPGA drivers but those on the SoC's doorbell.
# Each gate is one row of build/results/gates.tsv; exit 1 if any fails.
set -uo pipefail
. "$(dirname "$0")/lib.sh"

mkdir -p "$BUILD/results"
rows=$BUILD/results/gates.tsv
: >"$rows"
failed=0
row() {	# row NAME ok|fail REASON
	if [ "$2" = ok ]; then
		printf 'gates: %s\t1\t0\t0\tok\t\n' "$1" >>"$rows"
		echo "ok - $1"
	else
		printf 'gates: %s\t0\t1\t0\tfail\t%s\n' "$1" "$3" >>"$rows"
		echo "not ok - $1: $3"
		failed=1
	fi
}

# 1. W=1 (build-kmod.sh fails on any compiler warning)
amd64_targets=$(for k in $AMD64_KERNELS; do amd64_target "$k"; done)
for t in $amd64_targets armhf armel armel-rpi; do
	start=$(date +%s)
	if out=$("$TOP/scripts/build-kmod.sh" "$t" 2>&1); then
		row "W=1 build, $t" ok
		echo "# $t: $(($(date +%s) - start)) s"
	else
		echo "$out" | tail -20
		row "W=1 build, $t" fail "compiler warnings or errors (build/kmod/$t/build.log)"
	fi
done

# 1b. the struct sja1000_priv layout check (part of every W=1 build above) can fail
if out=$("$TOP/scripts/sja1000-layout-selftest.sh" 2>&1); then
	row "struct sja1000_priv layout check rejects a changed copy" ok
else
	echo "$out" | tail -5
	row "struct sja1000_priv layout check rejects a changed copy" fail "$(echo "$out" | tail -1)"
fi

# 2. checkpatch --strict
src=$("$TOP/scripts/kernel-source.sh" 6.12)
checkpatch=$src/scripts/checkpatch.pl
mapfile -t files < <(cd "$TOP" && git ls-files -co --exclude-standard -- $KSRC_DIRS | grep -E '\.[ch]$' | sort)
log=$BUILD/results/checkpatch.log
: >"$log"
cp_bad=0
for f in "${files[@]}"; do
	ignore=()
	case $f in
	kernel/include/compat/*) ignore=(--ignore LINUX_VERSION_CODE,CONSTANT_COMPARISON) ;;
	# checkpatch 6.12 wants every struct regmap_config const; the
	# simulator's is the FPGA's const one with the model's accessors,
	# assembled in its probe.
	tests/sim/ts7800-sim-main.c) ignore=(--ignore CONST_STRUCT) ;;
	esac
	out=$(cd "$TOP" && perl "$checkpatch" --strict --quiet --no-tree --no-summary --show-types \
		"${ignore[@]}" -f "$f" 2>&1)
	if [ -n "$out" ]; then
		printf '%s\n' "$out" >>"$log"
		cp_bad=$((cp_bad + 1))
	fi
done
if [ "$cp_bad" = 0 ]; then
	row "checkpatch --strict (${#files[@]} files)" ok
else
	grep -E '^(ERROR|WARNING|CHECK):|^#[0-9]+: FILE:' "$log" | head -30
	row "checkpatch --strict (${#files[@]} files)" fail "$cp_bad file(s) with findings ($log)"
fi

# 3. sparse (C=2 checks every file, compiled or not)
for t in $amd64_targets; do
	kdir=$(cat "$BUILD/kmod/$t/kdir" 2>/dev/null)
	slog=$BUILD/results/sparse-$t.log
	if [ -n "$kdir" ] && make -C "$kdir" M="$BUILD/kmod/$t" C=2 modules >"$slog" 2>&1; then
		if grep -E '(warning|error):' "$slog" | grep -v 'Skipping BTF'; then
			row "sparse (C=2), $t" fail "sparse findings ($slog)"
		else
			row "sparse (C=2), $t" ok
		fi
	else
		tail -20 "$slog"
		row "sparse (C=2), $t" fail "sparse run failed ($slog)"
	fi
done

# 4. the FPGA window only through its 16-bit regmap
if "$TOP/scripts/fpga-access-width.sh"; then
	row "FPGA window: 16-bit regmap only" ok
else
	row "FPGA window: 16-bit regmap only" fail "MMIO accessors on the FPGA window (above)"
fi
exit $failed
