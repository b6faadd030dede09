/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The transmit buffer of a serial_core port: a circ_buf in uart_state until
 * 6.9, a kfifo in the tty_port since 6.10. uart_xmit_advance() exists in
 * both; these are the reads a driver needs besides it.
 */
#ifndef _COMPAT_SERIAL_XMIT_H
#define _COMPAT_SERIAL_XMIT_H

#include <linux/serial_core.h>
#include <linux/types.h>
#include <linux/version.h>

#if LINUX_VERSION_CODE >= KERNEL_VERSION(6, 10, 0)
#include <linux/kfifo.h>

/* The buffer exists (the port is started). */
static inline bool compat_uart_xmit_ready(struct uart_port *port)
{
	return kfifo_initialized(&port->state->port.xmit_fifo);
}

static inline unsigned int compat_uart_xmit_pending(struct uart_port *port)
{
	return kfifo_len(&port->state->port.xmit_fifo);
}

/* The next character to send, left in the buffer; false if there is none. */
static inline bool compat_uart_xmit_peek(struct uart_port *port, u8 *ch)
{
	return kfifo_peek(&port->state->port.xmit_fifo, ch);
}
#else
static inline bool compat_uart_xmit_ready(struct uart_port *port)
{
	return port->state->xmit.buf;
}

static inline unsigned int compat_uart_xmit_pending(struct uart_port *port)
{
	return uart_circ_chars_pending(&port->state->xmit);
}

static inline bool compat_uart_xmit_peek(struct uart_port *port, u8 *ch)
{
	struct circ_buf *xmit = &port->state->xmit;

	if (uart_circ_empty(xmit))
		return false;
	*ch = xmit->buf[xmit->tail];
	return true;
}
#endif

#endif
