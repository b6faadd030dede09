// SPDX-License-Identifier: GPL-2.0
/*
 * TS-UART: serial_core driver for the TS-7800 FPGA UARTs.
 *
 * One tty (ttyTSUn) per hardware port and one receive path: only the ISR of
 * the open port reads DATA, which fixes the vendor driver's 8-bit/9-bit twin
 * devices stealing each other's characters. 9-bit characters use standard
 * termios: PARENB | CMSPAR sends PARODD as the 9th bit and flags received
 * characters with the other 9th bit as TTY_PARITY (see ts-uart-frame.c).
 * Or mainline's 9-bit addressing: TIOCSRS485 with SER_RS485_ADDRB makes the
 * 9th bit an address bit (docs/tsuart.md, "9-bit addressing").
 *
 * The port is a child of the FPGA core (or of the simulator): registers are
 * reached through the parent's regmap, the interrupt is the parent's.
 */
#include <linux/bitfield.h>
#include <linux/hrtimer.h>
#include <linux/interrupt.h>
#include <linux/mod_devicetable.h>
#include <linux/module.h>
#include <linux/platform_device.h>
#include <linux/regmap.h>
#include <linux/serial.h>
#include <linux/serial_core.h>
#include <linux/tty.h>
#include <linux/tty_flip.h>
#include <linux/ts7800-fpga.h>
#include <compat/platform_remove.h>
#include <compat/serial_xmit.h>

#include "ts-uart-frame.h"

#define TS_UART_DRV_NAME	"ts-uart"
#define TS_UART_DEV_NAME	"ttyTSU"
/*
 * serial_core's port type (TIOCGSERIAL, sysfs "type"). Mainline assigns the
 * PORT_* numbers in include/uapi/linux/serial_core.h (0..123 in 6.1); an
 * out-of-tree driver has none, so it takes a number far above that range
 * instead of posing as one of them (1 is PORT_8250). PORT_UNKNOWN (0) is no
 * choice: serial_core refuses to open such a port.
 */
#define TS_UART_PORT_TYPE	7800
#define TS_UART_MIN_BAUD	2400
#define TS_UART_MAX_BAUD	115200
/* Nominal FIFO size advertised to serial_core (the real depth is unknown). */
#define TS_UART_FIFO_SIZE	16
/*
 * Upper bound of STAT reads per interrupt. Characters arrive far slower than
 * the ISR reads them, so the bound is never reached in practice; it only
 * stops a broken device from locking up the CPU.
 */
#define TS_UART_ISR_BUDGET	4096
#define TS_UART_FLUSH_BUDGET	256

/* Driver-private status bits for read/ignore_status_mask and uart_insert_char. */
#define TS_UART_ST_DR		BIT(0)
#define TS_UART_ST_PE		BIT(1)
#define TS_UART_ST_FE		BIT(2)
#define TS_UART_ST_BRK		BIT(3)
#define TS_UART_ST_OE		BIT(4)

struct ts_uart {
	struct uart_port port;
	struct regmap *map;
	unsigned int stat_reg;
	unsigned int data_reg;
	u16 ctrl;			/* control bits of STAT; port lock */
	bool oerr;			/* OERR seen, not yet reported; port lock */
	struct ts_uart_frame frame;	/* port lock */
	/* RS-485: RTS is at its "on send" level; port lock */
	bool rs485_sending;
	/* RS-485: polls TRE after the last character went into the FIFO */
	struct hrtimer rs485_timer;
	/*
	 * ADDRB (port lock): SER_RS485_ADDR_DEST's address goes out once the
	 * addr_after characters queued before it have gone, together with the
	 * first character written after it (so that no idle line separates
	 * them, however late the writer comes); addr_recv is
	 * SER_RS485_ADDR_RECV's address (-1: none) and rx_match says whether
	 * the last address received was it.
	 */
	bool addr_pending;
	u8 addr_dest;
	unsigned int addr_after;
	int addr_recv;
	bool rx_match;
};

static inline struct ts_uart *to_ts_uart(struct uart_port *port)
{
	return container_of(port, struct ts_uart, port);
}

/*
 * A STAT read may consume one-shot indications (OERR and the TX event may
 * clear on read), so every read happens under the port lock, OERR is latched
 * here until reported, and code outside the ISR that needs STAT serves the
 * whole port (ts_uart_service()) instead of looking at one bit.
 */
static int ts_uart_read_stat(struct ts_uart *up, unsigned int *stat)
{
	int ret = regmap_read(up->map, up->stat_reg, stat);

	if (!ret && (*stat & TS7800_STAT_OERR))
		up->oerr = true;
	return ret;
}

/* STAT status bits ignore writes, so the control shadow is written whole. */
static void ts_uart_write_ctrl(struct ts_uart *up)
{
	regmap_write(up->map, up->stat_reg, up->ctrl);
}

static void ts_uart_overrun(struct ts_uart *up)
{
	struct uart_port *port = &up->port;

	up->oerr = false;
	port->icount.overrun++;
	if (!(port->ignore_status_mask & TS_UART_ST_OE))
		tty_insert_flip_char(&port->state->port, 0, TTY_OVERRUN);
}

/* RTS level: asserted or not (STAT RTS is the line's level). */
static void ts_uart_set_rts(struct ts_uart *up, bool on)
{
	if (on)
		up->ctrl |= TS7800_STAT_RTS;
	else
		up->ctrl &= ~TS7800_STAT_RTS;
	ts_uart_write_ctrl(up);
}

static bool ts_uart_rs485_on(struct uart_port *port)
{
	return port->rs485.flags & SER_RS485_ENABLED;
}

/*
 * RS-485 direction control. The TS-UART has no driver-enable output of its
 * own (ts7800-notes 1.10), so the transceiver is driven from RTS, switched
 * by the driver as mainline's software RS-485 does: RTS goes to its "on
 * send" level before the first character enters the FIFO and back once the
 * transmitter is completely idle (STAT TRE) after the last one.
 */
static void ts_uart_rs485_start(struct ts_uart *up)
{
	struct uart_port *port = &up->port;

	if (!ts_uart_rs485_on(port) || up->rs485_sending)
		return;
	hrtimer_try_to_cancel(&up->rs485_timer);
	up->rs485_sending = true;
	ts_uart_set_rts(up, port->rs485.flags & SER_RS485_RTS_ON_SEND);
}

static void ts_uart_rs485_idle(struct ts_uart *up)
{
	struct uart_port *port = &up->port;

	up->rs485_sending = false;
	ts_uart_set_rts(up, port->rs485.flags & SER_RS485_RTS_AFTER_SEND);
}

/* @chars character times (at least one): when TRE is worth reading again. */
static ktime_t ts_uart_rs485_period(struct uart_port *port, unsigned int chars)
{
	return ns_to_ktime(max_t(u64, READ_ONCE(port->frame_time), NSEC_PER_USEC) *
			   max(chars, 1U));
}

/*
 * Nothing more to send: release the line when the stop bit of the last
 * character is out, else look again later (the TS-UART has no "transmitter
 * idle" interrupt): first after the time of the @written characters just
 * put into the FIFO less the one that may be on the line already, at the
 * earliest the line can be idle, then every character time. Reading TRE
 * every character time from the start cost a timer interrupt and a STAT
 * read per character of every RS-485 transmission.
 */
static void ts_uart_rs485_done(struct ts_uart *up, unsigned int stat, unsigned int written)
{
	struct uart_port *port = &up->port;

	if (!up->rs485_sending || compat_uart_xmit_pending(port))
		return;
	if (stat & TS7800_STAT_TRE)
		ts_uart_rs485_idle(up);
	else if (!hrtimer_active(&up->rs485_timer))
		hrtimer_start(&up->rs485_timer,
			      ts_uart_rs485_period(port, written ? written - 1 : 1),
			      HRTIMER_MODE_REL);
}

static enum hrtimer_restart ts_uart_rs485_poll(struct hrtimer *t)
{
	struct ts_uart *up = container_of(t, struct ts_uart, rs485_timer);
	struct uart_port *port = &up->port;
	enum hrtimer_restart again = HRTIMER_NORESTART;
	unsigned long flags;
	unsigned int stat;

	uart_port_lock_irqsave(port, &flags);
	if (up->rs485_sending && !ts_uart_read_stat(up, &stat)) {
		if (stat & TS7800_STAT_TRE) {
			if (!compat_uart_xmit_pending(port))
				ts_uart_rs485_idle(up);
		} else {
			hrtimer_forward_now(t, ts_uart_rs485_period(port, 1));
			again = HRTIMER_RESTART;
		}
	}
	uart_port_unlock_irqrestore(port, flags);
	return again;
}

/*
 * ADDRB with SER_RS485_ADDR_RECV: only an address character equal to
 * addr_recv and the characters after it up to the next address pass.
 */
static bool ts_uart_addr_match(struct ts_uart *up, u8 ch, bool is_addr)
{
	if (up->addr_recv < 0)
		return true;
	if (is_addr)
		up->rx_match = ch == up->addr_recv;
	return up->rx_match;
}

/* Read one character; stat is the STAT value that showed DR. */
static void ts_uart_rx_char(struct ts_uart *up, unsigned int stat)
{
	struct uart_port *port = &up->port;
	unsigned int word, status = TS_UART_ST_DR, err = 0;
	char flag = TTY_NORMAL;
	u8 ch;

	if (regmap_read(up->map, up->data_reg, &word))
		return;
	port->icount.rx++;

	if (stat & TS7800_STAT_RXBRK) {
		ch = 0;
		status |= TS_UART_ST_BRK;
		port->icount.brk++;
		if (uart_handle_break(port))
			return;
	} else {
		err = ts_uart_frame_decode(&up->frame, word, &ch);
		if (err & TS_UART_RX_PARITY) {
			status |= TS_UART_ST_PE;
			port->icount.parity++;
		}
		if (err & TS_UART_RX_FRAME) {
			status |= TS_UART_ST_FE;
			port->icount.frame++;
		}
	}
	if (up->oerr) {
		up->oerr = false;
		status |= TS_UART_ST_OE;
		port->icount.overrun++;
	}
	/* stop_rx(): keep draining the FIFO, deliver nothing. */
	if (!(port->read_status_mask & TS_UART_ST_DR))
		return;
	if (!(status & TS_UART_ST_BRK) &&
	    !ts_uart_addr_match(up, ch, err & TS_UART_RX_ADDRESS)) {
		if ((status & TS_UART_ST_OE) && !(port->ignore_status_mask & TS_UART_ST_OE))
			tty_insert_flip_char(&port->state->port, 0, TTY_OVERRUN);
		return;
	}

	status &= port->read_status_mask;
	if (status & TS_UART_ST_BRK)
		flag = TTY_BREAK;
	else if (status & TS_UART_ST_PE)
		flag = TTY_PARITY;
	else if (status & TS_UART_ST_FE)
		flag = TTY_FRAME;
	else if (err & TS_UART_RX_ADDRESS)
		flag = TTY_PARITY;	/* ADDRB: an address, whatever INPCK says */

	if (uart_prepare_sysrq_char(port, ch))
		return;
	uart_insert_char(port, status, TS_UART_ST_OE, ch, flag);
}

/*
 * Called with the port lock held and *stat just read showing TBRE; leaves
 * the last STAT read in *stat. Return: true if a character was written.
 */
static bool ts_uart_tx_chars(struct ts_uart *up, unsigned int *stat)
{
	struct uart_port *port = &up->port;
	unsigned int written = 0;
	u16 word;
	u8 ch;

	/* tx_empty() may serve a port that is not started (no buffer). */
	if (!compat_uart_xmit_ready(port))
		return false;
	while (*stat & TS7800_STAT_TBRE) {
		if (port->x_char) {
			word = ts_uart_frame_encode(&up->frame, port->x_char);
			port->x_char = 0;
			port->icount.tx++;
		} else if (uart_tx_stopped(port)) {
			break;
		} else if (up->addr_pending && !up->addr_after &&
			   compat_uart_xmit_pending(port)) {
			word = ts_uart_frame_encode_addr(up->addr_dest);
			up->addr_pending = false;
			port->icount.tx++;
		} else if (compat_uart_xmit_peek(port, &ch)) {
			word = ts_uart_frame_encode(&up->frame, ch);
			uart_xmit_advance(port, 1);
			if (up->addr_pending)
				up->addr_after--;
		} else {
			break;
		}
		ts_uart_rs485_start(up);
		if (regmap_write(up->map, up->data_reg, word))
			break;
		written++;
		if (ts_uart_read_stat(up, stat))
			break;
	}
	if (compat_uart_xmit_pending(port) < WAKEUP_CHARS)
		uart_write_wakeup(port);
	ts_uart_rs485_done(up, *stat, written);
	return written > 0;
}

/*
 * Serve the port until it has nothing more to say: no received character
 * left and no room or nothing to transmit. Ending only then makes the ISR
 * correct for level-triggered and for edge-triggered (event) sources.
 * Called with the port lock held; pushes received characters to the tty.
 * *stat is the last STAT value read (0 if the register could not be read).
 * Return: true if there was something to do (a character received or sent,
 * an overrun reported), the ISR's IRQ_HANDLED.
 */
static bool ts_uart_service(struct ts_uart *up, unsigned int *stat)
{
	bool rx = false, tx = false;
	unsigned int n;

	*stat = 0;
	for (n = 0; n < TS_UART_ISR_BUDGET; n++) {
		if (ts_uart_read_stat(up, stat))
			break;
		if (*stat & TS7800_STAT_DR) {
			ts_uart_rx_char(up, *stat);
			rx = true;
			continue;
		}
		if (up->oerr) {
			ts_uart_overrun(up);
			rx = true;
		}
		if (*stat & TS7800_STAT_TBRE)
			tx = ts_uart_tx_chars(up, stat);
		break;
	}
	if (n == TS_UART_ISR_BUDGET)
		dev_err_ratelimited(up->port.dev, "receive data ready never clears\n");
	if (rx)
		tty_flip_buffer_push(&up->port.state->port);
	return rx || tx;
}

static irqreturn_t ts_uart_isr(int irq, void *dev_id)
{
	struct ts_uart *up = dev_id;
	unsigned long flags;
	unsigned int stat;
	bool handled;

	uart_port_lock_irqsave(&up->port, &flags);
	handled = ts_uart_service(up, &stat);
	/* A sysrq character is handled after the port lock is dropped. */
	uart_unlock_and_check_sysrq_irqrestore(&up->port, flags);
	return IRQ_RETVAL(handled);
}

static unsigned int ts_uart_tx_empty(struct uart_port *port)
{
	struct ts_uart *up = to_ts_uart(port);
	unsigned long flags;
	unsigned int stat;

	uart_port_lock_irqsave(port, &flags);
	ts_uart_service(up, &stat);
	uart_unlock_and_check_sysrq_irqrestore(port, flags);
	return (stat & TS7800_STAT_TRE) ? TIOCSER_TEMT : 0;
}

static void ts_uart_set_mctrl(struct uart_port *port, unsigned int mctrl)
{
	struct ts_uart *up = to_ts_uart(port);

	/* In RS-485 mode RTS is the transceiver's driver enable. */
	if (ts_uart_rs485_on(port))
		return;
	ts_uart_set_rts(up, mctrl & TIOCM_RTS);
}

static unsigned int ts_uart_get_mctrl(struct uart_port *port)
{
	struct ts_uart *up = to_ts_uart(port);
	unsigned int mctrl = TIOCM_CAR | TIOCM_DSR;
	unsigned int stat;

	/* The port has no DCD/DSR lines: report them asserted, like a 3-wire port. */
	ts_uart_service(up, &stat);
	if (stat & TS7800_STAT_CTS)
		mctrl |= TIOCM_CTS;
	return mctrl;
}

/* TCOFLUSH: what was queued before a pending address is gone; it goes first. */
static void ts_uart_flush_buffer(struct uart_port *port)
{
	to_ts_uart(port)->addr_after = 0;
}

/* No transmit interrupt to disable: the FIFO just runs dry. */
static void ts_uart_stop_tx(struct uart_port *port)
{
}

static void ts_uart_start_tx(struct uart_port *port)
{
	unsigned int stat;

	ts_uart_service(to_ts_uart(port), &stat);
}

static void ts_uart_stop_rx(struct uart_port *port)
{
	port->read_status_mask &= ~TS_UART_ST_DR;
}

static void ts_uart_break_ctl(struct uart_port *port, int break_state)
{
	struct ts_uart *up = to_ts_uart(port);
	unsigned long flags;

	uart_port_lock_irqsave(port, &flags);
	if (break_state)
		up->ctrl |= TS7800_STAT_TXBRK;
	else
		up->ctrl &= ~TS7800_STAT_TXBRK;
	ts_uart_write_ctrl(up);
	uart_port_unlock_irqrestore(port, flags);
}

/* Discard what arrived while the port was closed (and a stale OERR). */
static void ts_uart_flush_rx(struct ts_uart *up)
{
	unsigned int stat, word, n;

	for (n = 0; n < TS_UART_FLUSH_BUDGET; n++) {
		if (ts_uart_read_stat(up, &stat) || !(stat & TS7800_STAT_DR))
			break;
		if (regmap_read(up->map, up->data_reg, &word))
			break;
	}
	up->oerr = false;
}

/*
 * serial_core's tty driver belongs to serial_core, so an open port does not
 * pin this module: without a reference of our own, unloading it while a port
 * is open frees the uart_state the open tty still uses. startup and shutdown
 * are paired by serial_core (under the port mutex, which uart_remove_one_port
 * also takes), so the reference lives exactly while the port is up.
 */
static int ts_uart_startup(struct uart_port *port)
{
	struct ts_uart *up = to_ts_uart(port);
	unsigned long flags;
	unsigned int stat;
	int ret;

	if (!try_module_get(THIS_MODULE))
		return -ENODEV;

	uart_port_lock_irqsave(port, &flags);
	ts_uart_flush_rx(up);
	uart_port_unlock_irqrestore(port, flags);

	ret = request_irq(port->irq, ts_uart_isr, 0, port->name, up);
	if (ret) {
		module_put(THIS_MODULE);
		return ret;
	}

	/*
	 * An event-triggered source may have fired while it was masked; serve
	 * the port once so that nothing waits for an interrupt that is gone.
	 */
	uart_port_lock_irqsave(port, &flags);
	ts_uart_service(up, &stat);
	uart_unlock_and_check_sysrq_irqrestore(port, flags);
	return 0;
}

static void ts_uart_shutdown(struct uart_port *port)
{
	struct ts_uart *up = to_ts_uart(port);
	unsigned long flags;

	free_irq(port->irq, up);
	hrtimer_cancel(&up->rs485_timer);
	uart_port_lock_irqsave(port, &flags);
	up->ctrl &= ~TS7800_STAT_TXBRK;
	up->addr_pending = false;	/* its transmission is gone */
	if (up->rs485_sending)
		ts_uart_rs485_idle(up);
	else
		ts_uart_write_ctrl(up);
	uart_port_unlock_irqrestore(port, flags);
	module_put(THIS_MODULE);
}

/* Nearest rate of the board-wide divisor table. */
static unsigned int ts_uart_baud_code(unsigned int baud)
{
	unsigned int code, best = 0, best_diff = UINT_MAX, diff;

	for (code = 0; code < TS7800_UART_NR_CODES; code++) {
		diff = max(baud, ts7800_uart_rates[code].baud) -
		       min(baud, ts7800_uart_rates[code].baud);
		if (diff < best_diff) {
			best_diff = diff;
			best = code;
		}
	}
	return best;
}

static void ts_uart_set_status_masks(struct uart_port *port, tcflag_t iflag)
{
	port->read_status_mask = TS_UART_ST_DR | TS_UART_ST_OE;
	if (iflag & INPCK)
		port->read_status_mask |= TS_UART_ST_PE | TS_UART_ST_FE;
	if (iflag & (IGNBRK | BRKINT | PARMRK))
		port->read_status_mask |= TS_UART_ST_BRK;

	port->ignore_status_mask = 0;
	if (iflag & IGNPAR)
		port->ignore_status_mask |= TS_UART_ST_PE | TS_UART_ST_FE;
	if (iflag & IGNBRK) {
		port->ignore_status_mask |= TS_UART_ST_BRK;
		/* Ignoring parity and break: ignore overruns too (as 8250). */
		if (iflag & IGNPAR)
			port->ignore_status_mask |= TS_UART_ST_OE;
	}
}

static void ts_uart_set_termios(struct uart_port *port, struct ktermios *termios,
				const struct ktermios *old)
{
	struct ts_uart *up = to_ts_uart(port);
	unsigned int baud, code;
	unsigned long flags;

	baud = uart_get_baud_rate(port, termios, old, TS_UART_MIN_BAUD, TS_UART_MAX_BAUD);
	code = ts_uart_baud_code(baud);
	baud = ts7800_uart_rates[code].baud;

	uart_port_lock_irqsave(port, &flags);
	/*
	 * ADDRB is switched by TIOCSRS485 only (ts_uart_rs485_config()); while
	 * it is on, the character is 8 data bits and the address bit, and the
	 * termios reported back says so.
	 */
	if (up->frame.addrb)
		termios->c_cflag |= ADDRB;
	else
		termios->c_cflag &= ~ADDRB;
	termios->c_cflag = ts_uart_frame_init(&up->frame, termios->c_cflag);
	uart_update_timeout(port, termios->c_cflag, baud);
	ts_uart_set_status_masks(port, termios->c_iflag);
	if (!(termios->c_cflag & CREAD))
		port->ignore_status_mask |= TS_UART_ST_DR;

	up->ctrl &= ~(TS7800_STAT_BAUD | TS7800_STAT_MODE9 | TS7800_STAT_HWCTS |
		      TS7800_STAT_DIV8);
	up->ctrl |= FIELD_PREP(TS7800_STAT_BAUD, code);
	if (ts_uart_frame_mode9(&up->frame))
		up->ctrl |= TS7800_STAT_MODE9;
	if (termios->c_cflag & CRTSCTS) {
		up->ctrl |= TS7800_STAT_HWCTS;
		port->status |= UPSTAT_AUTOCTS;
	} else {
		port->status &= ~UPSTAT_AUTOCTS;
	}
	ts_uart_write_ctrl(up);
	uart_port_unlock_irqrestore(port, flags);

	if (tty_termios_baud_rate(termios))
		tty_termios_encode_baud_rate(termios, baud, baud);
}

/* MODE9 and the character time after the character layout changed. */
static void ts_uart_frame_apply(struct ts_uart *up, tcflag_t cflag)
{
	unsigned int code = FIELD_GET(TS7800_STAT_BAUD, up->ctrl);

	if (ts_uart_frame_mode9(&up->frame))
		up->ctrl |= TS7800_STAT_MODE9;
	else
		up->ctrl &= ~TS7800_STAT_MODE9;
	if (code < TS7800_UART_NR_CODES)
		uart_update_timeout(&up->port, cflag, ts7800_uart_rates[code].baud);
	ts_uart_write_ctrl(up);
}

/*
 * ADDRB part of TIOCSRS485 (port lock held). @termios is the tty's, or NULL
 * when serial_core applies the port's stored setting again (then @rs485 is
 * &port->rs485, and its destination address was sent already).
 * Errors: -EINVAL if the character layout leaves no room for the address
 * bit (parity, CS7, CSTOPB), -EBUSY if the last destination address still
 * waits behind queued data.
 */
static int ts_uart_addrb_config(struct ts_uart *up, struct ktermios *termios,
				struct serial_rs485 *rs485)
{
	struct uart_port *port = &up->port;
	tcflag_t cflag = termios ? termios->c_cflag : CS8;
	bool on = (rs485->flags & SER_RS485_ENABLED) && (rs485->flags & SER_RS485_ADDRB);
	bool fits;
	int recv;

	if (!on) {
		if (termios)
			termios->c_cflag &= ~ADDRB;
		up->addr_pending = false;
		up->addr_recv = -1;
		if (up->frame.addrb) {
			ts_uart_frame_init(&up->frame, cflag & ~ADDRB);
			ts_uart_frame_apply(up, cflag & ~ADDRB);
		}
		return 0;
	}
	/* No room for the address bit: refused, not a silent change of layout. */
	if (up->frame.addrb)
		fits = true;
	else if (termios)
		fits = !(cflag & (PARENB | CSTOPB)) && (cflag & CSIZE) == CS8;
	else
		fits = up->frame.hw_bits == 8 && up->frame.data_bits == 8;
	if (!fits)
		return -EINVAL;
	if ((rs485->flags & SER_RS485_ADDR_DEST) && rs485 != &port->rs485) {
		if (up->addr_pending && up->addr_after)
			return -EBUSY;
		up->addr_pending = true;
		up->addr_dest = rs485->addr_dest;
		up->addr_after = compat_uart_xmit_ready(port) ? compat_uart_xmit_pending(port) : 0;
	}
	recv = (rs485->flags & SER_RS485_ADDR_RECV) ? rs485->addr_recv : -1;
	if (up->addr_recv != recv)
		up->rx_match = false;	/* nothing passes before its address */
	up->addr_recv = recv;
	if (termios)
		termios->c_cflag |= ADDRB;
	if (!up->frame.addrb) {
		up->rx_match = false;
		ts_uart_frame_init(&up->frame, cflag | ADDRB);
		ts_uart_frame_apply(up, CS8 | ADDRB);
	}
	return 0;
}

/*
 * Called with the port lock held (or before the port is up). RTS drives
 * the transceiver: put it at the idle level of the new setting, or give it
 * back to TIOCM when RS-485 is switched off (serial_core then calls
 * set_mctrl). The TS-UART's receiver cannot be switched off while sending,
 * so RX_DURING_TX is what the port does in any case and is reported so.
 */
static int ts_uart_rs485_config(struct uart_port *port, struct ktermios *termios,
				struct serial_rs485 *rs485)
{
	struct ts_uart *up = to_ts_uart(port);
	int ret;

	ret = ts_uart_addrb_config(up, termios, rs485);
	if (ret)
		return ret;
	if (!(rs485->flags & SER_RS485_ENABLED)) {
		up->rs485_sending = false;
		return 0;
	}
	rs485->flags |= SER_RS485_RX_DURING_TX;
	if (!up->rs485_sending)
		ts_uart_set_rts(up, rs485->flags & SER_RS485_RTS_AFTER_SEND);
	return 0;
}

static const char *ts_uart_type(struct uart_port *port)
{
	return port->type == TS_UART_PORT_TYPE ? "TS-UART" : NULL;
}

static void ts_uart_release_port(struct uart_port *port)
{
}

static int ts_uart_request_port(struct uart_port *port)
{
	return 0;
}

static void ts_uart_config_port(struct uart_port *port, int flags)
{
	if (flags & UART_CONFIG_TYPE)
		port->type = TS_UART_PORT_TYPE;
}

static int ts_uart_verify_port(struct uart_port *port, struct serial_struct *ser)
{
	if (ser->type != PORT_UNKNOWN && ser->type != TS_UART_PORT_TYPE)
		return -EINVAL;
	return 0;
}

static const struct uart_ops ts_uart_ops = {
	.tx_empty	= ts_uart_tx_empty,
	.set_mctrl	= ts_uart_set_mctrl,
	.get_mctrl	= ts_uart_get_mctrl,
	.flush_buffer	= ts_uart_flush_buffer,
	.stop_tx	= ts_uart_stop_tx,
	.start_tx	= ts_uart_start_tx,
	.stop_rx	= ts_uart_stop_rx,
	.break_ctl	= ts_uart_break_ctl,
	.startup	= ts_uart_startup,
	.shutdown	= ts_uart_shutdown,
	.set_termios	= ts_uart_set_termios,
	.type		= ts_uart_type,
	.release_port	= ts_uart_release_port,
	.request_port	= ts_uart_request_port,
	.config_port	= ts_uart_config_port,
	.verify_port	= ts_uart_verify_port,
};

static struct uart_driver ts_uart_driver = {
	.owner		= THIS_MODULE,
	.driver_name	= TS_UART_DRV_NAME,
	.dev_name	= TS_UART_DEV_NAME,
	.nr		= TS7800_UART_MAX_PORTS,
};

static int ts_uart_probe(struct platform_device *pdev)
{
	struct device *dev = &pdev->dev;
	struct uart_port *port;
	struct resource *res;
	struct ts_uart *up;
	int irq;

	if (pdev->id < 0 || pdev->id >= TS7800_UART_MAX_PORTS)
		return dev_err_probe(dev, -EINVAL, "bad port number %d\n", pdev->id);

	up = devm_kzalloc(dev, sizeof(*up), GFP_KERNEL);
	if (!up)
		return -ENOMEM;

	up->map = dev_get_regmap(dev->parent, NULL);
	if (!up->map)
		return dev_err_probe(dev, -ENODEV, "parent has no regmap\n");
	res = platform_get_resource(pdev, IORESOURCE_REG, 0);
	if (!res || resource_size(res) < TS7800_UART_REGS_SIZE)
		return dev_err_probe(dev, -EINVAL, "no register block\n");
	irq = platform_get_irq(pdev, 0);
	if (irq < 0)
		return irq;

	up->stat_reg = res->start + TS7800_UART_STAT;
	up->data_reg = res->start + TS7800_UART_DATA;
	ts_uart_frame_init(&up->frame, CS8);

	port = &up->port;
	port->dev = dev;
	port->line = pdev->id;
	port->irq = irq;
	/* Register offset in the FPGA window; shown by the core, never mapped. */
	port->mapbase = res->start;
	port->iotype = UPIO_MEM16;
	port->ops = &ts_uart_ops;
	port->fifosize = TS_UART_FIFO_SIZE;
	port->flags = UPF_BOOT_AUTOCONF;
	port->uartclk = TS7800_UART_BITCLK_HZ;
	port->has_sysrq = IS_ENABLED(CONFIG_SERIAL_CORE_CONSOLE);
	port->rs485_config = ts_uart_rs485_config;
	port->rs485_supported.flags = SER_RS485_ENABLED | SER_RS485_RTS_ON_SEND |
				      SER_RS485_RTS_AFTER_SEND | SER_RS485_RX_DURING_TX |
				      SER_RS485_ADDRB | SER_RS485_ADDR_DEST |
				      SER_RS485_ADDR_RECV;
	up->addr_recv = -1;
	hrtimer_init(&up->rs485_timer, CLOCK_MONOTONIC, HRTIMER_MODE_REL);
	up->rs485_timer.function = ts_uart_rs485_poll;

	platform_set_drvdata(pdev, up);
	return uart_add_one_port(&ts_uart_driver, port);
}

static void ts_uart_remove(struct platform_device *pdev)
{
	struct ts_uart *up = platform_get_drvdata(pdev);

	uart_remove_one_port(&ts_uart_driver, &up->port);
}

static const struct platform_device_id ts_uart_ids[] = {
	{ .name = TS7800_UART_DEV_NAME },
	{ }
};
MODULE_DEVICE_TABLE(platform, ts_uart_ids);

static struct platform_driver ts_uart_platform_driver = {
	.probe		= ts_uart_probe,
	.PLATFORM_DRIVER_REMOVE = ts_uart_remove,
	.id_table	= ts_uart_ids,
	.driver		= {
		.name	= TS_UART_DRV_NAME,
	},
};

static int __init ts_uart_init(void)
{
	int ret;

	ret = uart_register_driver(&ts_uart_driver);
	if (ret)
		return ret;
	ret = platform_driver_register(&ts_uart_platform_driver);
	if (ret)
		uart_unregister_driver(&ts_uart_driver);
	return ret;
}
module_init(ts_uart_init);

static void __exit ts_uart_exit(void)
{
	platform_driver_unregister(&ts_uart_platform_driver);
	uart_unregister_driver(&ts_uart_driver);
}
module_exit(ts_uart_exit);

MODULE_DESCRIPTION("TS-7800 FPGA UART (TS-UART) serial driver with 9-bit mode");
MODULE_LICENSE("GPL");
