/* SPDX-License-Identifier: GPL-2.0 */
/*
 * TS-UART character framing: termios <-> DATA register words.
 *
 * The TS-UART has no parity or stop-bit settings; it shifts 8-bit or (MODE9)
 * 9-bit characters between one start and one stop bit. Parity and a second
 * stop bit are made in software inside that character, and MODE9 is used
 * whenever data + parity + extra stop bits exceed 8.
 *
 * With ADDRB (mainline's 9-bit addressing, set through TIOCSRS485) the 9th
 * bit is the address bit instead: 8 data bits, no parity, one stop bit.
 */
#ifndef TS_UART_FRAME_H
#define TS_UART_FRAME_H

#include <linux/termios.h>
#include <linux/types.h>

enum ts_uart_parity {
	TS_UART_PARITY_NONE,
	TS_UART_PARITY_EVEN,
	TS_UART_PARITY_ODD,
	TS_UART_PARITY_SPACE,	/* PARENB | CMSPAR: sticky 0 */
	TS_UART_PARITY_MARK,	/* PARENB | CMSPAR | PARODD: sticky 1 */
};

struct ts_uart_frame {
	u8 data_bits;		/* 7 or 8 */
	u8 hw_bits;		/* 8, or 9 in MODE9 */
	enum ts_uart_parity parity;
	u16 fill;		/* mark bits after data + parity (stop bits) */
	bool addrb;		/* ADDRB: the 9th bit is the address bit */
};

/* ts_uart_frame_decode() result bits */
#define TS_UART_RX_PARITY	BIT(0)
#define TS_UART_RX_FRAME	BIT(1)
#define TS_UART_RX_ADDRESS	BIT(2)	/* ADDRB: 9th bit 1 */

/* ADDRB: the character layout it allows (no parity, no second stop bit) */
#define TS_UART_ADDRB_CFLAG_CLEAR	(CSIZE | PARENB | PARODD | CMSPAR | CSTOPB)

tcflag_t ts_uart_frame_init(struct ts_uart_frame *f, tcflag_t cflag);
u16 ts_uart_frame_encode(const struct ts_uart_frame *f, u8 ch);
u16 ts_uart_frame_encode_addr(u8 addr);
unsigned int ts_uart_frame_decode(const struct ts_uart_frame *f, u16 word, u8 *ch);

static inline bool ts_uart_frame_mode9(const struct ts_uart_frame *f)
{
	return f->hw_bits == 9;
}

#endif /* TS_UART_FRAME_H */
