#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# The bit-banged adapter on DIO_1 (SCL) / DIO_3 (SDA) against the simulated
# MAX6615: i2cdetect finds exactly the chip, i2cdump reads the register
# model, byte writes land in it, other addresses and read-only registers
# behave as on the chip, and the lines show up as used in gpioinfo.
. "$(dirname "$0")/lib.sh"
trap cleanup_all EXIT

tap_plan 11
sim_load || { tap_diag "cannot load ts7800_dio + ts7800_sim"; exit 1; }
adapter_load || { tap_diag "cannot load ts7800_dio_i2c"; exit 1; }
tap_diag "adapter i2c-$I2C_BUS: $(cat /sys/bus/i2c/devices/i2c-$I2C_BUS/name)"

tap_ok "gpioinfo shows DIO_1/DIO_3 taken by the adapter" \
	sh -c "gpioinfo $DIO_CHIP | grep -q '\"DIO_1\".*\"i2c-scl\"' && gpioinfo $DIO_CHIP | grep -q '\"DIO_3\".*\"i2c-sda\"'"
tap_is "the bus idles released (SCL and SDA high)" "$(pin_level $SCL_OFF)$(pin_level $SDA_OFF)" 11

found=$(i2cdetect -y "$I2C_BUS" | awk 'NR > 1 { for (i = 2; i <= NF; i++) if ($i != "--") printf "%s ", $i }')
tap_is "i2cdetect finds the simulated chip at 0x18 and nothing else" "$found" "18 "

# i2cdump (SMBus byte-data, one transfer per register) against the model.
dump=$(i2cdump -y "$I2C_BUS" "$CHIP_ADDR" b | awk 'NR > 1 { for (i = 2; i <= 17; i++) printf "%s ", $i; print "" }')
model=$(awk '{ for (i = 1; i <= NF; i++) printf "%s ", $i; print "" }' "$CHIPFS/regs")
tap_is "i2cdump matches the register model (256 registers)" "$dump" "$model"
tap_is "identity registers FD/FE/FF = 01 68 4d" \
	"$(for r in 0xfd 0xfe 0xff; do i2cget -y "$I2C_BUS" "$CHIP_ADDR" $r; done | tr '\n' ' ')" "0x01 0x68 0x4d "

# Temperature through the bus: 37.625 C = 0x25 + 5/8 in 1Eh bits 7..5.
chip_set temp1 37625
tap_is "a simulated temperature reads back over the bus (00h, 1Eh)" \
	"$(i2cget -y "$I2C_BUS" "$CHIP_ADDR" 0x00) $(i2cget -y "$I2C_BUS" "$CHIP_ADDR" 0x1e)" "0x25 0xa0"

i2cset -y "$I2C_BUS" "$CHIP_ADDR" 0x03 0x4b
tap_is "a byte write reaches the model (OT1 limit 03h = 4b)" "$(model_reg 0x03)" 4b
tap_is "and reads back over the bus" "$(i2cget -y "$I2C_BUS" "$CHIP_ADDR" 0x03)" 0x4b
i2cset -y "$I2C_BUS" "$CHIP_ADDR" 0x00 0x10
tap_is "a write to the read-only TEMP1 is ignored" "$(i2cget -y "$I2C_BUS" "$CHIP_ADDR" 0x00)" 0x25

nacks0=$(awk '/addr_nacks/ { print $2 }' "$CHIPFS/bus")
i2cget -y "$I2C_BUS" 0x19 0x00 >/dev/null 2>&1; rc=$?
nacks1=$(awk '/addr_nacks/ { print $2 }' "$CHIPFS/bus")
tap_diag "i2cget 0x19: exit status $rc, $((nacks1 - nacks0)) address NACK(s) (i2c-algo-bit retries)"
tap_ok "another address is not acknowledged (i2cget fails, the slave saw it)" \
	sh -c "[ $rc -ne 0 ] && [ $((nacks1 - nacks0)) -ge 1 ]"
tap_is "the bus is released after all that" "$(pin_level $SCL_OFF)$(pin_level $SDA_OFF)" 11

tap_finish
