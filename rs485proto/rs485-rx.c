// SPDX-License-Identifier: GPL-2.0
/*
 * rs485-rx.c - the receive state machine: characters and their tty flags in,
 * frames out.
 *
 * The port receives in space parity (PARENB|CMSPAR, INPCK, !IGNPAR), so the
 * address character of every frame (9th bit 1) arrives flagged TTY_PARITY
 * and every other character unflagged. Any TTY_PARITY character starts a new
 * frame, whatever state the machine is in: that is the resynchronisation
 * rule of the protocol, and it means that garbage can cost at most the frame
 * it hits. Overruns, framing errors and breaks abort the frame being
 * received, because a character of it may be missing or wrong. Every way a
 * frame can end without being delivered (bad CRC, cut short by an address
 * character, an overrun, a framing error or a break) is reported to the
 * transaction (rs485_rx_corrupt_from()): if it was the awaited response, the
 * node has executed the request and the retry must be a RESEND.
 *
 * Sending the address character (mark parity) inverts the flags of what
 * arrives meanwhile on a full-duplex link. From just before that switch
 * until everything received up to the switch back has been seen, the machine
 * is lenient: it trusts the length field instead of the flags, so that an
 * event frame of the slave that overlaps the switch is not lost: inside a
 * frame every character is data, and outside one any character starts one.
 * The CRC still decides whether the frame is valid; a frame in which such a
 * guess mattered and that fails its CRC is parsed again by the flags.
 *
 * The next request waits until the line has been idle for the gap after
 * the end of every frame, whole or cut (spec "Timing and transactions").
 * receive_buf sees a character only some time after it ended (a receive
 * FIFO's trigger level or timeout, the interrupt, the flip buffer work), so
 * "no character seen for the gap" is not "idle for the gap" while more of
 * a frame may come. The machine therefore counts the characters that may
 * still come (rx->left): the rest of the frame in progress (a maximum frame
 * until its LEN has arrived), and after an overrun, a framing error or a
 * break a maximum frame, less what arrives after it. A UART reports an
 * overrun with the character it read when it noticed it, which arrived
 * before the lost one, so neither where the frame stopped being whole nor
 * how much of it is still to come is known, and the lost character may have
 * begun a new frame; a sender that broke its frame may go on with anything.
 * After each call the line counts as busy until those characters could
 * have passed after the last one seen (rx_busy_until); a sender that pauses
 * inside a frame moves that time on with every character it sends.
 *
 * Runs only from receive_buf (one call at a time per tty), so rx needs no
 * lock; what it hands on is passed under bus->lock.
 */
#include "n_rs485.h"

void rs485_rx_reset(struct rs485_bus *bus)
{
	bus->rx.state = RS485_RX_IDLE;
	bus->rx.pos = 0;
	bus->rx.left = 0;
}

static void rs485_rx_count(struct rs485_bus *bus, u64 *counter)
{
	unsigned long flags;

	spin_lock_irqsave(&bus->lock, flags);
	(*counter)++;
	spin_unlock_irqrestore(&bus->lock, flags);
}

/* A whole frame with a good CRC: to the waiting transaction or to read(). */
static void rs485_rx_deliver(struct rs485_bus *bus)
{
	const u8 *frame = bus->rx.buf;
	unsigned int len = bus->rx.pos;

	if (!rs485_rx_frame_for_xact(bus, frame, len, bus->rx.attempt))
		rs485_event_queue(bus, frame, len);
}

/* The frame in progress ends without a valid frame; @counter says how. */
static void rs485_rx_abort(struct rs485_bus *bus, u64 *counter)
{
	struct rs485_rx *rx = &bus->rx;

	rs485_rx_count(bus, counter);
	rs485_rx_corrupt_from(bus, rx->buf[0], rx->attempt);
	rs485_rx_reset(bus);
}

/*
 * A character was lost (TTY_OVERRUN) or arrived broken (TTY_FRAME,
 * TTY_BREAK), counted in @counter: the frame in progress is aborted, and a
 * maximum frame may still come (see the top of this file).
 */
static void rs485_rx_broken(struct rs485_bus *bus, u64 *counter)
{
	rs485_rx_count(bus, counter);
	if (bus->rx.state != RS485_RX_IDLE)
		rs485_rx_abort(bus, &bus->stats.rx_truncated);
	bus->rx.left = RS485_WIRE_MAX - 1;
}

static void rs485_rx_replay(struct rs485_bus *bus);

static void rs485_rx_start(struct rs485_bus *bus, u8 addr)
{
	struct rs485_rx *rx = &bus->rx;

	/* A guessed frame cut short may have swallowed the start of others. */
	if (rx->state != RS485_RX_IDLE && rx->guessed)
		rs485_rx_replay(bus);
	if (rx->state != RS485_RX_IDLE)
		rs485_rx_abort(bus, &bus->stats.rx_truncated);
	rx->buf[0] = addr;
	rx->pos = 1;
	rx->left = RS485_WIRE_MAX - 1;	/* until LEN says how many */
	rx->state = RS485_RX_HEADER;
	rx->guessed = false;
	rx->nraw = 0;
	rx->attempt = rs485_rx_addr_seen(bus, addr);
}

static void rs485_rx_char(struct rs485_bus *bus, u8 c, bool parity, bool lenient);

/* Parse the characters of a failed frame again, after its first, by their flags. */
static void rs485_rx_replay(struct rs485_bus *bus)
{
	struct rs485_rx *rx = &bus->rx;
	unsigned int i, n = rx->nraw;

	memcpy(rx->replay, rx->raw, n);
	memcpy(rx->replay_parity, rx->raw_parity, n * sizeof(rx->raw_parity[0]));
	rs485_rx_reset(bus);
	for (i = 1; i < n; i++)
		rs485_rx_char(bus, rx->replay[i], rx->replay_parity[i], false);
}

static void rs485_rx_crc(struct rs485_bus *bus, u8 c)
{
	struct rs485_rx *rx = &bus->rx;

	rx->state = RS485_RX_IDLE;
	rx->left = 0;
	if (rs485_crc(rx->buf, rx->pos) == c) {
		rs485_rx_deliver(bus);
		return;
	}
	if (rx->guessed) {
		rs485_rx_replay(bus);
		return;
	}
	rs485_rx_abort(bus, &bus->stats.rx_crc_errors);
}

static void rs485_rx_data(struct rs485_bus *bus, u8 c)
{
	struct rs485_rx *rx = &bus->rx;

	if (rx->left)
		rx->left--;
	switch (rx->state) {
	case RS485_RX_IDLE:
		rs485_rx_count(bus, &bus->stats.rx_noise);
		return;
	case RS485_RX_HEADER:
		rx->buf[rx->pos++] = c;
		if (rx->pos < N_RS485_HEADER_LEN)
			return;
		rx->left = c + 1;	/* DATA CRC */
		rx->state = c ? RS485_RX_DATA : RS485_RX_CRC;
		return;
	case RS485_RX_DATA:
		rx->buf[rx->pos++] = c;
		if (rx->pos == N_RS485_HEADER_LEN + rx->buf[3])
			rx->state = RS485_RX_CRC;
		return;
	case RS485_RX_CRC:
		rs485_rx_crc(bus, c);
		return;
	}
}

/* One character without an error flag; @parity: it came flagged TTY_PARITY. */
static void rs485_rx_char(struct rs485_bus *bus, u8 c, bool parity, bool lenient)
{
	struct rs485_rx *rx = &bus->rx;
	bool start = lenient ? rx->state == RS485_RX_IDLE : parity;

	if (start)
		rs485_rx_start(bus, c);
	if (rx->state != RS485_RX_IDLE) {
		rx->guessed |= start != parity;
		rx->raw[rx->nraw] = c;
		rx->raw_parity[rx->nraw] = parity;
		rx->nraw++;
	}
	if (!start)
		rs485_rx_data(bus, c);
}

/*
 * N_RS485_CFG_ECHO: while the worker expects the echo of the frame it sends,
 * the first characters received are that echo, not frames. Each is compared
 * with the character sent (the 8 data bits: the parity flag depends on when
 * the driver read it, before or after the switch back to space); a
 * difference or an error flag marks a collision. Returns how many of the
 * @count characters were the echo.
 */
static int rs485_rx_echo(struct rs485_bus *bus, const u8 *cp, const u8 *fp, int count)
{
	unsigned long flags;
	bool done = false;
	int i = 0;

	spin_lock_irqsave(&bus->lock, flags);
	if (bus->echo_pos < bus->echo_len) {
		for (; i < count && bus->echo_pos < bus->echo_len; i++) {
			u8 flag = fp ? fp[i] : TTY_NORMAL;

			if ((flag != TTY_NORMAL && flag != TTY_PARITY) ||
			    cp[i] != bus->echo_buf[bus->echo_pos])
				bus->echo_collided = true;
			bus->echo_pos++;
		}
		done = bus->echo_pos == bus->echo_len;
	}
	spin_unlock_irqrestore(&bus->lock, flags);
	if (done)
		wake_up_all(&bus->resp_wait);
	return i;
}

void rs485_rx_chars(struct rs485_bus *bus, const u8 *cp, const u8 *fp, int count)
{
	ktime_t now = ktime_get();	/* every character of this call has ended */
	unsigned long flags;
	bool lenient;
	int i, echo;

	/*
	 * The characters of this call were flagged before the call: if the
	 * worker was not lenient yet, they were flagged before its switch.
	 */
	spin_lock_irqsave(&bus->lock, flags);
	bus->stats.rx_bytes += count;
	bus->rx_last = now;
	lenient = bus->rx.lenient;
	if (bus->rx_flush) {
		/* TCIFLUSH: the frame in progress is gone (rs485_flush_buffer()). */
		bus->rx_flush = false;
		rs485_rx_reset(bus);
	}
	spin_unlock_irqrestore(&bus->lock, flags);

	echo = rs485_rx_echo(bus, cp, fp, count);
	for (i = echo; i < count; i++) {
		u8 flag = fp ? fp[i] : TTY_NORMAL;

		switch (flag) {
		case TTY_NORMAL:
		case TTY_PARITY:
			rs485_rx_char(bus, cp[i], flag == TTY_PARITY, lenient);
			break;
		case TTY_OVERRUN:
			/* An extra NUL: a character was lost before this point. */
			rs485_rx_broken(bus, &bus->stats.rx_overruns);
			break;
		default:	/* TTY_FRAME, TTY_BREAK */
			rs485_rx_broken(bus, &bus->stats.rx_framing);
			break;
		}
	}

	/* Each of the characters that may still come takes its time after now. */
	spin_lock_irqsave(&bus->lock, flags);
	bus->rx_busy_until = ktime_add_ns(now, bus->rx.left * rs485_char_ns(bus));
	spin_unlock_irqrestore(&bus->lock, flags);
}
