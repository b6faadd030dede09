#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# The register cache works: counted with the i2c tracepoints, a second full
# `sensors` run reads no non-volatile register from the chip, while every
# volatile one is still read. "Without cache" is measured on the same device
# through regmap's debugfs cache_bypass switch, and must equal the cached
# run's chip reads plus its cache hits (the regmap_reg_read_cache event).
. "$(dirname "$0")/lib.sh"
trap cleanup_all EXIT

CONF=$VMTEST_REPO/i2c-max6615/advee-max6615.conf
DEBUGFS=/sys/kernel/debug
DEBUGFS_MOUNTED_BY_US=0

tap_header
stub_load 0x18 || { tap_diag "cannot load i2c-stub"; exit 1; }
image_load || { tap_diag "cannot preload the register image"; exit 1; }
modprobe max6615 || { tap_diag "cannot load max6615"; exit 1; }
tap_ok "bound" driver_bound
CHIP=max6615-i2c-$STUB_BUS-18
trace_setup || { tap_diag "cannot set up i2c tracing"; exit 1; }

run_sensors() { sensors -c "$CONF" "$CHIP" >/dev/null; }

# nonvolatile_reads: chip reads in TRACE_LOG of registers that may be cached
nonvolatile_reads() {
	n=0
	for r in $(trace_read_regs); do
		is_volatile "$r" || n=$((n + 1))
	done
	echo "$n"
}
volatile_set() { trace_read_regs | sort -u | tr '\n' ' '; }

trace_run run_sensors
cold_reads=$(trace_count smbus_read)
cold_nonvolatile=$(nonvolatile_reads)
tap_diag "sensors run 1 (cache filled by this run): $cold_reads SMBus reads, $cold_nonvolatile of cacheable registers"

trace_run run_sensors
warm_reads=$(trace_count smbus_read)
warm_nonvolatile=$(nonvolatile_reads)
warm_hits=$(trace_count regmap_reg_read_cache)
warm_regs=$(volatile_set)
tap_diag "sensors run 2 (cache warm): $warm_reads SMBus reads ($warm_regs), $warm_hits served from the cache"
tap_is "run 2 reads no cacheable register from the chip" "$warm_nonvolatile" 0
tap_ok "run 1 read the cacheable registers once" test "$cold_nonvolatile" -gt 0
tap_ok "run 2 still reads temperatures, tachs and status from the chip" \
	sh -c "echo '$warm_regs' | grep -q '^0 1 18 19 1c 1e 1f 5 \$'"
tap_is "run 2 writes nothing" "$(trace_data_writes)" 0

if [ ! -d "$DEBUGFS/regmap" ]; then
	mount -t debugfs none "$DEBUGFS" && DEBUGFS_MOUNTED_BY_US=1
fi
BYPASS=$DEBUGFS/regmap/$(client_name)/cache_bypass
if [ -w "$BYPASS" ]; then
	echo Y >"$BYPASS"
	trace_run run_sensors
	bypass_reads=$(trace_count smbus_read)
	echo N >"$BYPASS"
	tap_diag "sensors run 3 (cache bypassed): $bypass_reads SMBus reads"
	tap_is "without cache = chip reads + cache hits of the cached run" \
		"$bypass_reads" "$((warm_reads + warm_hits))"
	tap_ok "the cache saves SMBus transactions ($warm_reads < $bypass_reads)" \
		test "$warm_reads" -lt "$bypass_reads"
else
	tap_skip "without cache = chip reads + cache hits" "no regmap debugfs ($BYPASS)"
	tap_skip "the cache saves SMBus transactions" "no regmap debugfs"
fi
[ "$DEBUGFS_MOUNTED_BY_US" = 1 ] && umount "$DEBUGFS"

# Writes go through the cache: a limit written is read back without the chip.
H=$(hwmon_dir)
echo 75000 >"$H/temp1_crit"
trace_run cat "$H/temp1_crit"
tap_is "a written limit is served from the cache" "$(trace_count smbus_read)" 0

tap_done
