// SPDX-License-Identifier: GPL-2.0
/*
 * rs485-crc.c - the frame check of the protocol: CRC-8/MAXIM (polynomial
 * x^8+x^5+x^4+1 reflected, 0x8C LSB first, initial value 0, no final XOR),
 * computed with the kernel's crc8 library.
 */
#include <linux/crc8.h>

#include "n_rs485.h"

#define RS485_CRC_POLY_LSB	0x8c
#define RS485_CRC_INIT		0x00

static u8 rs485_crc_table[CRC8_TABLE_SIZE];

void rs485_crc_init(void)
{
	crc8_populate_lsb(rs485_crc_table, RS485_CRC_POLY_LSB);
}

u8 rs485_crc(const u8 *buf, size_t len)
{
	return crc8(rs485_crc_table, buf, len, RS485_CRC_INIT);
}
