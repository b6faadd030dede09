// SPDX-License-Identifier: GPL-2.0
/*
 * TS-UART character framing (see ts-uart-frame.h).
 *
 * With PARENB | CMSPAR the parity bit is sticky: PARODD chooses the 9th bit
 * sent with CS8, and a received character whose sticky bit differs is a
 * parity error - the 8250 contract the RS-485 line discipline relies on.
 * With ADDRB the 9th bit is the address bit: 0 for data, 1 for an address.
 */
#include <linux/bitops.h>
#include <linux/bits.h>

#include "ts-uart-frame.h"

static enum ts_uart_parity ts_uart_parity_of(tcflag_t cflag)
{
	if (!(cflag & PARENB))
		return TS_UART_PARITY_NONE;
	if (cflag & CMSPAR)
		return (cflag & PARODD) ? TS_UART_PARITY_MARK : TS_UART_PARITY_SPACE;
	return (cflag & PARODD) ? TS_UART_PARITY_ODD : TS_UART_PARITY_EVEN;
}

/**
 * ts_uart_frame_init - derive the character layout from termios
 * @f: layout to fill
 * @cflag: termios c_cflag
 *
 * Return: @cflag as the hardware will really send it: CS5 and CS6 are not
 * supported and become CS8, and CSTOPB is dropped when data and parity fill
 * the 9-bit character (8 data bits with parity), leaving no bit for it.
 * With ADDRB, data, address bit and stop bit fill it: 8 data bits, no
 * parity, one stop bit.
 */
tcflag_t ts_uart_frame_init(struct ts_uart_frame *f, tcflag_t cflag)
{
	unsigned int used;

	f->addrb = cflag & ADDRB;
	if (f->addrb) {
		f->data_bits = 8;
		f->parity = TS_UART_PARITY_NONE;
		f->hw_bits = 9;
		f->fill = 0;
		return (cflag & ~TS_UART_ADDRB_CFLAG_CLEAR) | CS8;
	}
	if ((cflag & CSIZE) != CS7) {
		cflag &= ~CSIZE;
		cflag |= CS8;
	}
	f->data_bits = (cflag & CSIZE) == CS7 ? 7 : 8;
	f->parity = ts_uart_parity_of(cflag);
	used = f->data_bits + (f->parity != TS_UART_PARITY_NONE);
	if (used >= 9)
		cflag &= ~CSTOPB;
	f->hw_bits = used + !!(cflag & CSTOPB) > 8 ? 9 : 8;
	f->fill = used < f->hw_bits ? GENMASK(f->hw_bits - 1, used) : 0;
	return cflag;
}

static unsigned int ts_uart_parity_bit(const struct ts_uart_frame *f, u8 ch)
{
	switch (f->parity) {
	case TS_UART_PARITY_EVEN:
		return hweight8(ch) & 1;
	case TS_UART_PARITY_ODD:
		return !(hweight8(ch) & 1);
	case TS_UART_PARITY_MARK:
		return 1;
	default:
		return 0;
	}
}

u16 ts_uart_frame_encode(const struct ts_uart_frame *f, u8 ch)
{
	u16 word;

	if (f->addrb)
		return ch;
	ch &= GENMASK(f->data_bits - 1, 0);
	word = ch | f->fill;
	if (f->parity != TS_UART_PARITY_NONE)
		word |= ts_uart_parity_bit(f, ch) << f->data_bits;
	return word;
}

/* ADDRB: an address character (9th bit 1). */
u16 ts_uart_frame_encode_addr(u8 addr)
{
	return BIT(8) | addr;
}

unsigned int ts_uart_frame_decode(const struct ts_uart_frame *f, u16 word, u8 *ch)
{
	unsigned int pos = f->data_bits, err = 0;

	if (f->addrb) {
		*ch = word & 0xff;
		return (word & BIT(8)) ? TS_UART_RX_ADDRESS : 0;
	}
	*ch = word & GENMASK(f->data_bits - 1, 0);
	if (f->parity != TS_UART_PARITY_NONE) {
		if (((word >> pos) & 1) != ts_uart_parity_bit(f, *ch))
			err |= TS_UART_RX_PARITY;
		pos++;
	}
	/* Like a 16550, check the first stop bit only (if it is ours to see). */
	if (pos < f->hw_bits && !((word >> pos) & 1))
		err |= TS_UART_RX_FRAME;
	return err;
}
