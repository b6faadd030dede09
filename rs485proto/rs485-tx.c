// SPDX-License-Identifier: GPL-2.0
/*
 * rs485-tx.c - the line: termios on attach and detach, and sending one frame
 * with the 9th bit carried by sticky parity.
 *
 * The address character goes out in mark parity (PARENB|CMSPAR|PARODD: 9th
 * bit 1), the rest in space parity (9th bit 0). Parity may only change when
 * the transmitter is empty, or the character being shifted out (or, on a
 * UART that encodes the 9th bit when a character enters its FIFO, the next
 * one) gets the wrong 9th bit. tty_wait_until_sent() guarantees that, but a
 * serial_core UART polls tx_empty() with a sleep of at least one jiffy (4 ms
 * at HZ=250): far longer than the character. So the worker first sleeps the
 * time the characters need on the line and only then asks
 * tty_wait_until_sent(), which then normally finds the transmitter empty at
 * once. Everything here sleeps: it runs only in the bus's work item.
 */
#include <linux/delay.h>
#include <linux/jiffies.h>

#include "n_rs485.h"

/* Upper bound for a frame to drain, also if flow control stalls the UART. */
#define RS485_DRAIN_TIMEOUT	(HZ / 2)

static void rs485_termios_bus(struct rs485_bus *bus, struct ktermios *t, bool mark)
{
	t->c_cflag &= ~(CSIZE | CSTOPB | PARODD | CRTSCTS | HUPCL);
	t->c_cflag |= CS8 | PARENB | CMSPAR | CREAD | CLOCAL;
	if (mark)
		t->c_cflag |= PARODD;
	t->c_iflag &= ~(IGNPAR | PARMRK | ISTRIP | IXON | IXOFF | IXANY | IGNBRK | BRKINT);
	t->c_iflag |= INPCK;
	tty_termios_encode_baud_rate(t, bus->cfg.baud, bus->cfg.baud);
}

static void rs485_set_parity(struct rs485_bus *bus, bool mark)
{
	struct tty_struct *tty = bus->tty;
	struct ktermios t;

	down_read(&tty->termios_rwsem);
	t = tty->termios;
	up_read(&tty->termios_rwsem);
	rs485_termios_bus(bus, &t, mark);
	tty_set_termios(tty, &t);
}

/* Called from open(): remember the port's termios and take the bus over. */
int rs485_line_setup(struct rs485_bus *bus)
{
	struct tty_struct *tty = bus->tty;

	down_read(&tty->termios_rwsem);
	bus->saved_termios = tty->termios;
	up_read(&tty->termios_rwsem);
	rs485_set_parity(bus, false);
	bus->line_free = ktime_get();
	if (!(tty->termios.c_cflag & PARENB) || !(tty->termios.c_cflag & CMSPAR)) {
		/* The driver cleared them: this UART cannot carry the 9th bit. */
		rs485_line_restore(bus);
		return -EOPNOTSUPP;
	}
	return 0;
}

void rs485_line_restore(struct rs485_bus *bus)
{
	tty_set_termios(bus->tty, &bus->saved_termios);
}

/* RS485_IOC_SET_CONFIG, under line_mutex: new rate on the line at once. */
int rs485_line_set_config(struct rs485_bus *bus, const struct rs485_config *cfg)
{
	unsigned long flags;

	spin_lock_irqsave(&bus->lock, flags);
	bus->cfg = *cfg;
	spin_unlock_irqrestore(&bus->lock, flags);
	rs485_set_parity(bus, false);
	return 0;
}

/* One character on the line: start + 8 data + 9th bit + stop. */
u64 rs485_char_ns(const struct rs485_bus *bus)
{
	return div_u64(11ULL * NSEC_PER_SEC, bus->cfg.baud);
}

static int rs485_write_all(struct rs485_bus *bus, const u8 *buf, size_t len)
{
	struct tty_struct *tty = bus->tty;
	long left = RS485_DRAIN_TIMEOUT;
	int n;

	while (len) {
		if (READ_ONCE(bus->dead) || test_bit(TTY_HUPPED, &tty->flags) ||
		    test_bit(TTY_IO_ERROR, &tty->flags))
			return -EIO;
		n = tty->ops->write(tty, buf, len);
		if (n < 0)
			return n;
		buf += n;
		len -= n;
		if (!len)
			break;
		/* The driver's buffer is full: tty_wakeup() wakes write_wait. */
		left = wait_event_timeout(tty->write_wait,
					  tty_write_room(tty) || READ_ONCE(bus->dead), left);
		if (!left)
			return -ETIMEDOUT;
	}
	return 0;
}

/* Wait until @nchars written at @start have left the transmitter. */
static int rs485_drain(struct rs485_bus *bus, ktime_t start, size_t nchars)
{
	u64 ns = (nchars + 1) * rs485_char_ns(bus);
	s64 left = ktime_to_ns(ktime_sub(ktime_add_ns(start, ns), ktime_get()));

	if (left > 0)
		fsleep(div_u64(left, NSEC_PER_USEC) + 1);
	tty_wait_until_sent(bus->tty, RS485_DRAIN_TIMEOUT);
	if (tty_chars_in_buffer(bus->tty))
		return -ETIMEDOUT;
	return READ_ONCE(bus->dead) ? -EIO : 0;
}

/*
 * Send one frame (ADDR ... CRC) and return when its last character has left
 * the UART; 0 or a negative error (detach, hangup, stuck transmitter).
 */
static void rs485_rx_lenient(struct rs485_bus *bus, bool on)
{
	unsigned long flags;

	spin_lock_irqsave(&bus->lock, flags);
	bus->rx.lenient = on;
	spin_unlock_irqrestore(&bus->lock, flags);
}

int rs485_tx_frame(struct rs485_bus *bus, const u8 *buf, size_t len)
{
	s64 gap = ktime_to_ns(ktime_sub(bus->line_free, ktime_get()));
	struct tty_port *port = bus->tty->port;
	unsigned long flags;
	ktime_t start;
	int ret;

	if (gap > 0)
		fsleep(div_u64(gap, NSEC_PER_USEC) + 1);

	rs485_rx_lenient(bus, true);
	rs485_set_parity(bus, true);
	start = ktime_get();
	ret = rs485_write_all(bus, buf, 1);
	if (!ret)
		ret = rs485_drain(bus, start, 1);
	rs485_set_parity(bus, false);
	if (!ret) {
		start = ktime_get();
		ret = rs485_write_all(bus, buf + 1, len - 1);
		if (!ret)
			ret = rs485_drain(bus, start, len - 1);
	}
	/*
	 * Everything flagged in mark parity was pushed by the UART before the
	 * switch back (or, from a receive FIFO, within the data characters'
	 * time): once the flip buffer work has run, the flags are exact again.
	 */
	if (port)
		flush_work(&port->buf.work);
	rs485_rx_lenient(bus, false);

	spin_lock_irqsave(&bus->lock, flags);
	bus->stats.tx_frames++;
	bus->stats.tx_bytes += len;
	spin_unlock_irqrestore(&bus->lock, flags);
	return ret;
}
