// SPDX-License-Identifier: GPL-2.0
/*
 * rs485-tx.c - the line: termios on attach and detach, and sending one frame
 * on one of two paths (enum n_rs485_tx_path), chosen at attach.
 *
 * N_RS485_PATH_ADDRB, on a serial_core port that offers mainline's 9-bit
 * addressing (SER_RS485_ADDRB): the port runs in ADDRB mode, and each frame
 * is SER_RS485_ADDR_DEST with its address, which the UART sends before the
 * data written next (after anything still queued), then the rest of the
 * frame written in one go and one drain. serial_core takes TIOCSRS485 only
 * from a user pointer, so the discipline applies the setting the way
 * uart_set_rs485_config() does, under the port mutex and lock.
 *
 * N_RS485_PATH_PARITY, on every other UART:
 *
 * The address character goes out in mark parity (PARENB|CMSPAR|PARODD: 9th
 * bit 1), the rest in space parity (9th bit 0). Parity may only change when
 * the transmitter is empty, or the character being shifted out (or, on a
 * UART that encodes the 9th bit when a character enters its FIFO, the next
 * one) gets the wrong 9th bit. tty_wait_until_sent() guarantees that, but a
 * serial_core UART polls tx_empty() with a sleep of at least one jiffy (4 ms
 * at HZ=250): far longer than the character. So the worker first sleeps, with
 * hrtimer precision, the time the characters need on the line and only then
 * asks tty_wait_until_sent(), which then normally finds the transmitter empty
 * at once (rs485_drain()). Everything here sleeps: it runs only in the bus's
 * work item.
 */
#include <linux/hrtimer.h>
#include <linux/jiffies.h>
#include <linux/sched.h>
#include <linux/serial_core.h>

#include "n_rs485.h"

/* Upper bound for a frame to drain, also if flow control stalls the UART. */
#define RS485_DRAIN_TIMEOUT	(HZ / 2)
/* Characters a UART holds once the tty's buffer is empty (16550 FIFO). */
#define RS485_TX_FIFO_CHARS	16
/* Echo mode: how long the rest of the echo may lag behind the line. */
#define RS485_ECHO_WAIT_NS	(50 * NSEC_PER_MSEC)

static bool addrb = true;
module_param(addrb, bool, 0644);
MODULE_PARM_DESC(addrb,
		 "send the 9th bit by the UART's 9-bit addressing (SER_RS485_ADDRB) where it offers it (default 1); 0: always by mark/space parity; read at attach");

/*
 * The serial_core state of @tty, or NULL if it is not a serial_core port:
 * serial_core is the only user of tty_driver.driver_state, its uart_driver,
 * which points back to the tty_driver.
 */
static struct uart_state *rs485_uart_state(struct tty_struct *tty)
{
	struct uart_driver *drv = tty->driver->driver_state;

	if (!drv || drv->tty_driver != tty->driver)
		return NULL;
	return tty->driver_data;
}

/*
 * TIOCSRS485 from the kernel, as uart_set_rs485_config() does it for a user:
 * the driver's rs485_config() under the port mutex and lock; @termios the
 * tty's (its termios_rwsem held for writing) or NULL. Only while the port
 * is up if @up. @r is the setting the port stores.
 */
static int rs485_uart_config(struct rs485_bus *bus, struct serial_rs485 *r,
			     struct ktermios *termios, bool up)
{
	struct uart_state *state = rs485_uart_state(bus->tty);
	struct uart_port *uport;
	unsigned long flags;
	int ret = -EIO;

	if (!state)
		return -EOPNOTSUPP;
	mutex_lock(&state->port.mutex);
	uport = state->uart_port;
	if (uport && (!up || tty_port_initialized(&state->port))) {
		uart_port_lock_irqsave(uport, &flags);
		ret = uport->rs485_config(uport, termios, r);
		if (!ret)
			uport->rs485 = *r;
		uart_port_unlock_irqrestore(uport, flags);
	}
	mutex_unlock(&state->port.mutex);
	return ret;
}

/* As rs485_uart_config(), with the tty's termios (ADDRB switches there). */
static int rs485_uart_config_termios(struct rs485_bus *bus, struct serial_rs485 *r)
{
	struct tty_struct *tty = bus->tty;
	int ret;

	down_write(&tty->termios_rwsem);
	ret = rs485_uart_config(bus, r, &tty->termios, false);
	up_write(&tty->termios_rwsem);
	return ret;
}

/*
 * At attach: does the port offer SER_RS485_ADDRB? Then remember its
 * RS-485 setting and make the one the bus uses: RS-485 on (RTS as it was
 * set, else RTS on send: the transceiver's driver enable if it is wired to
 * RTS), ADDRB.
 */
static bool rs485_addrb_offered(struct rs485_bus *bus)
{
	struct uart_state *state = rs485_uart_state(bus->tty);
	struct uart_port *uport;
	bool offered = false;

	if (!addrb || !state)
		return false;
	mutex_lock(&state->port.mutex);
	uport = state->uart_port;
	if (uport && uport->rs485_config &&
	    (uport->rs485_supported.flags & SER_RS485_ADDRB)) {
		offered = true;
		bus->saved_rs485 = uport->rs485;
	}
	mutex_unlock(&state->port.mutex);
	if (!offered)
		return false;

	bus->rs485 = bus->saved_rs485;
	if (!(bus->rs485.flags & SER_RS485_ENABLED))
		bus->rs485.flags = SER_RS485_ENABLED | SER_RS485_RTS_ON_SEND;
	bus->rs485.flags &= ~(SER_RS485_ADDR_RECV | SER_RS485_ADDR_DEST);
	bus->rs485.flags |= SER_RS485_ADDRB;
	bus->rs485.addr_recv = 0;
	bus->rs485.addr_dest = 0;
	/* Restored at detach: a destination address there would be sent. */
	bus->saved_rs485.flags &= ~SER_RS485_ADDR_DEST;
	bus->saved_rs485.addr_dest = 0;
	return true;
}

static void rs485_termios_bus(struct rs485_bus *bus, struct ktermios *t, bool mark)
{
	t->c_cflag &= ~(CSIZE | CSTOPB | PARODD | CRTSCTS | HUPCL);
	t->c_cflag |= CS8 | PARENB | CMSPAR | CREAD | CLOCAL;
	/* ADDRB: the UART's address bit is the 9th bit, no parity. */
	if (bus->addrb)
		t->c_cflag &= ~(PARENB | CMSPAR);
	else if (mark)
		t->c_cflag |= PARODD;
	t->c_iflag &= ~(IGNPAR | PARMRK | ISTRIP | IXON | IXOFF | IXANY | IGNBRK);
	/*
	 * BRKINT: serial drivers flag a break TTY_BREAK only with it (or
	 * PARMRK), else it is a NUL data character; a break cuts a response
	 * short. Sending SIGINT on a break is n_tty's job, not this one's.
	 */
	t->c_iflag |= INPCK | BRKINT;
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

/* A termios switch for sending a frame (counted). */
static void rs485_switch_parity(struct rs485_bus *bus, bool mark)
{
	rs485_set_parity(bus, mark);
	rs485_count(bus, &bus->stats.termios_switches);
}

/*
 * Called from open(): remember the port's termios and take the bus over,
 * on the addressing path if the port offers it.
 */
int rs485_line_setup(struct rs485_bus *bus)
{
	struct tty_struct *tty = bus->tty;

	down_read(&tty->termios_rwsem);
	bus->saved_termios = tty->termios;
	up_read(&tty->termios_rwsem);
	bus->line_free = ktime_get();
	if (rs485_addrb_offered(bus)) {
		/* 8N1 first: the UART refuses ADDRB while parity is on. */
		bus->addrb = true;
		rs485_set_parity(bus, false);
		if (!rs485_uart_config_termios(bus, &bus->rs485) &&
		    (tty->termios.c_cflag & ADDRB)) {
			bus->stats.tx_path = N_RS485_PATH_ADDRB;
			return 0;
		}
		dev_warn(tty->dev, "n_rs485: 9-bit addressing refused, using mark/space parity\n");
		rs485_uart_config_termios(bus, &bus->saved_rs485);
		bus->addrb = false;
	}
	bus->stats.tx_path = N_RS485_PATH_PARITY;
	rs485_set_parity(bus, false);
	if (!(tty->termios.c_cflag & PARENB) || !(tty->termios.c_cflag & CMSPAR)) {
		/* The driver cleared them: this UART cannot carry the 9th bit. */
		rs485_line_restore(bus);
		return -EOPNOTSUPP;
	}
	return 0;
}

void rs485_line_restore(struct rs485_bus *bus)
{
	if (bus->addrb)
		rs485_uart_config_termios(bus, &bus->saved_rs485);
	tty_set_termios(bus->tty, &bus->saved_termios);
}

/* N_RS485_IOC_SET_CONFIG, under line_mutex: new rate on the line at once. */
int rs485_line_set_config(struct rs485_bus *bus, const struct n_rs485_config *cfg)
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
		/*
		 * The driver's buffer is full. tty_wakeup() and the kill path
		 * wake write_wait's interruptible sleepers only, so sleep
		 * interruptibly (a work item gets no signals).
		 */
		left = wait_event_interruptible_timeout(tty->write_wait,
							tty_write_room(tty) || READ_ONCE(bus->dead),
							left);
		if (left < 0)
			return -EINTR;
		if (!left)
			return -ETIMEDOUT;
	}
	return 0;
}

/*
 * Sleep until @end with hrtimer precision. fsleep() would allow up to twice
 * the time (usleep_range(us, 2 * us)), more than the characters take.
 */
static void rs485_sleep_until(struct rs485_bus *bus, ktime_t end)
{
	u64 slack = div_u64(rs485_char_ns(bus), 8);

	while (ktime_before(ktime_get(), end)) {
		set_current_state(TASK_UNINTERRUPTIBLE);
		schedule_hrtimeout_range(&end, slack, HRTIMER_MODE_ABS);
	}
}

/*
 * Wait until the @nchars just written have left the transmitter.
 *
 * tty_wait_until_sent() alone would be slow: serial_core polls tx_empty()
 * with msleep_interruptible() of at least one jiffy (4 ms at HZ=250), ten
 * characters' time at 115200 Bd, whenever the last character is still
 * shifting out when it first looks. So: first wait until the tty's buffer
 * is empty (every character has reached the UART), then sleep with hrtimer
 * precision for the time the characters still in the UART need on the line
 * (at most a 16550-sized FIFO of them, 11 bits each), and only then let
 * tty_wait_until_sent() confirm; it then normally finds the transmitter
 * empty at its first look. A deeper FIFO only makes it sleep again.
 */
static int rs485_drain(struct rs485_bus *bus, size_t nchars)
{
	struct tty_struct *tty = bus->tty;
	u64 char_ns = rs485_char_ns(bus);
	long left;

	rs485_count(bus, &bus->stats.drains);
	left = wait_event_interruptible_timeout(tty->write_wait,
						!tty_chars_in_buffer(tty) || READ_ONCE(bus->dead),
						RS485_DRAIN_TIMEOUT);
	if (left < 0)
		return -EINTR;
	if (!left)
		return -ETIMEDOUT;
	rs485_sleep_until(bus, ktime_add_ns(ktime_get(),
					    min_t(size_t, nchars, RS485_TX_FIFO_CHARS) * char_ns +
					    char_ns / 4));
	tty_wait_until_sent(tty, RS485_DRAIN_TIMEOUT);
	if (tty_chars_in_buffer(tty))
		return -ETIMEDOUT;
	return READ_ONCE(bus->dead) ? -EIO : 0;
}

static void rs485_rx_lenient(struct rs485_bus *bus, bool on)
{
	unsigned long flags;

	spin_lock_irqsave(&bus->lock, flags);
	bus->rx.lenient = on;
	spin_unlock_irqrestore(&bus->lock, flags);
}

/* N_RS485_CFG_ECHO: the next characters received must repeat @buf. */
static void rs485_echo_expect(struct rs485_bus *bus, const u8 *buf, size_t len)
{
	unsigned long flags;

	spin_lock_irqsave(&bus->lock, flags);
	memcpy(bus->echo_buf, buf, len);
	bus->echo_pos = 0;
	bus->echo_collided = false;
	bus->echo_len = len;
	spin_unlock_irqrestore(&bus->lock, flags);
}

static bool rs485_echo_complete(struct rs485_bus *bus)
{
	unsigned long flags;
	bool done;

	spin_lock_irqsave(&bus->lock, flags);
	done = bus->dead || bus->echo_pos >= bus->echo_len;
	spin_unlock_irqrestore(&bus->lock, flags);
	return done;
}

/*
 * Wait for the rest of the echo and stop expecting it; 0 if the bus carried
 * the frame as sent, -ECOMM if not (a collision). The echo's last character
 * ends with the frame's last stop bit, but a UART may hold it back (a 16550
 * reports a partly filled receive FIFO after 4 idle characters) and the flip
 * buffer work runs later still: RS485_ECHO_WAIT_NS covers that. It is spent
 * in full only when characters of the echo are missing.
 */
static int rs485_echo_check(struct rs485_bus *bus)
{
	unsigned long flags;
	bool collided;

	wait_event_hrtimeout(bus->resp_wait, rs485_echo_complete(bus),
			     ns_to_ktime(RS485_ECHO_WAIT_NS));
	spin_lock_irqsave(&bus->lock, flags);
	collided = bus->echo_collided || bus->echo_pos < bus->echo_len;
	bus->echo_len = 0;
	bus->echo_pos = 0;
	spin_unlock_irqrestore(&bus->lock, flags);
	return collided ? -ECOMM : 0;
}

/*
 * Wait until the line may carry the next request: the gap after the last
 * frame on the line, whichever direction, and after what a frame in
 * progress or a broken one may still send (rs485-rx.c). Characters that
 * arrive meanwhile move it on, and a frame's end comes closer once its LEN
 * has arrived: look again at least every gap. A cut response wakes the
 * worker from inside receive_buf, before that call has counted what may
 * still come: let it finish first. Returns early if the bus goes away.
 */
void rs485_line_wait(struct rs485_bus *bus)
{
	u64 gap_ns = bus->cfg.gap_chars * rs485_char_ns(bus);
	struct tty_port *port = bus->tty->port;
	ktime_t busy, start, now;
	unsigned long flags;

	if (port)
		flush_work(&port->buf.work);
	for (;;) {
		spin_lock_irqsave(&bus->lock, flags);
		busy = bus->rx_last;
		if (ktime_after(bus->rx_busy_until, busy))
			busy = bus->rx_busy_until;
		spin_unlock_irqrestore(&bus->lock, flags);
		start = ktime_add_ns(busy, gap_ns);
		if (ktime_before(start, bus->line_free))
			start = bus->line_free;
		now = ktime_get();
		if (!ktime_before(now, start) || READ_ONCE(bus->dead))
			return;
		rs485_sleep_until(bus, min_t(ktime_t, start, ktime_add_ns(now, gap_ns)));
	}
}

/*
 * Send one frame (ADDR ... CRC), right after rs485_line_wait(), and return
 * when its last character has left the UART (and, in echo mode, its echo
 * has come back): 0, -ECOMM (echo mode: collision) or another negative
 * error (detach, hangup, stuck transmitter).
 */
/*
 * N_RS485_PATH_ADDRB: the address as SER_RS485_ADDR_DEST (the UART sends it
 * after what is queued and before what is written next), the rest at once.
 */
static int rs485_tx_addrb(struct rs485_bus *bus, const u8 *buf, size_t len)
{
	struct serial_rs485 r = bus->rs485;
	int ret;

	r.flags |= SER_RS485_ADDR_DEST;
	r.addr_dest = buf[0];
	ret = rs485_uart_config(bus, &r, NULL, true);
	if (!ret)
		ret = rs485_write_all(bus, buf + 1, len - 1);
	if (!ret)
		ret = rs485_drain(bus, len);
	return ret;
}

/*
 * N_RS485_PATH_PARITY: address in mark parity, drain, data in space parity,
 * drain.
 */
static int rs485_tx_parity(struct rs485_bus *bus, const u8 *buf, size_t len)
{
	struct tty_port *port = bus->tty->port;
	int ret;

	rs485_rx_lenient(bus, true);
	rs485_switch_parity(bus, true);
	ret = rs485_write_all(bus, buf, 1);
	if (!ret) {
		ret = rs485_drain(bus, 1);
		rs485_count(bus, &bus->stats.addr_drains);
	}
	rs485_switch_parity(bus, false);
	if (!ret) {
		ret = rs485_write_all(bus, buf + 1, len - 1);
		if (!ret)
			ret = rs485_drain(bus, len - 1);
	}
	/*
	 * Everything flagged in mark parity was pushed by the UART before the
	 * switch back (or, from a receive FIFO, within the data characters'
	 * time): once the flip buffer work has run, the flags are exact again.
	 */
	if (port)
		flush_work(&port->buf.work);
	rs485_rx_lenient(bus, false);
	return ret;
}

int rs485_tx_frame(struct rs485_bus *bus, const u8 *buf, size_t len)
{
	u64 gap_ns = bus->cfg.gap_chars * rs485_char_ns(bus);
	bool echo = bus->cfg.flags & N_RS485_CFG_ECHO;
	unsigned long flags;
	int ret, echo_ret;

	if (echo)
		rs485_echo_expect(bus, buf, len);
	if (bus->addrb)
		ret = rs485_tx_addrb(bus, buf, len);
	else
		ret = rs485_tx_parity(bus, buf, len);
	if (echo) {
		echo_ret = rs485_echo_check(bus);
		if (!ret)
			ret = echo_ret;
	}

	/* This frame has left the line (or failed): the next one waits the gap. */
	bus->line_free = ktime_add_ns(ktime_get(), gap_ns);

	spin_lock_irqsave(&bus->lock, flags);
	bus->stats.tx_frames++;
	bus->stats.tx_bytes += len;
	spin_unlock_irqrestore(&bus->lock, flags);
	return ret;
}
