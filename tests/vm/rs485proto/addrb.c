// SPDX-License-Identifier: GPL-2.0
/*
 * addrb - mainline's 9-bit addressing (ADDRB, SER_RS485_ADDR_*) on the
 * TS-UART, used by a program alone, without n_rs485: a raw tty, TIOCSRS485,
 * read() and write(). The test slave on the simulated wire is the BR board:
 * it sees every request's address with the 9th bit 1, answers, and the
 * answer's address arrives flagged (INPCK|PARMRK: \377 \0 ADDR). Also: the
 * destination address goes out in order with data queued before it, the
 * receive filter, and the errors of a port or termios that cannot do it.
 */
#include <linux/serial.h>

#include "rs485-lib.h"

#define PORT		0
#define STAT_MODE9	0x0100	/* TS7800_STAT_MODE9 (linux/ts7800-fpga.h) */
#define XFERS		200

/* Raw 115200 Bd tty, 8 bits plus @cflag, INPCK|PARMRK. */
static int raw_open(const char *path, tcflag_t cflag)
{
	struct termios t;
	int fd = open(path, O_RDWR | O_NOCTTY);

	if (fd < 0)
		return -1;
	if (tcgetattr(fd, &t)) {
		close(fd);
		return -1;
	}
	cfmakeraw(&t);
	t.c_iflag |= INPCK | PARMRK;
	t.c_cflag &= ~(CSIZE | PARENB | PARODD | CMSPAR | CSTOPB | CRTSCTS);
	t.c_cflag |= CS8 | CREAD | CLOCAL | cflag;
	cfsetspeed(&t, B115200);
	t.c_cc[VMIN] = 0;
	t.c_cc[VTIME] = 0;
	if (tcsetattr(fd, TCSANOW, &t)) {
		close(fd);
		return -1;
	}
	return fd;
}

static int set_rs485(int fd, uint32_t flags, uint8_t dest, uint8_t recv)
{
	struct serial_rs485 r;

	memset(&r, 0, sizeof(r));
	r.flags = flags;
	r.addr_dest = dest;
	r.addr_recv = recv;
	return ioctl(fd, TIOCSRS485, &r);
}

static tcflag_t cflag_of(int fd)
{
	struct termios t;

	return tcgetattr(fd, &t) ? 0 : t.c_cflag;
}

/*
 * Read one frame of @want characters (address included) from a PARMRK
 * stream: \377 \0 c is a flagged character (an address), \377 \377 a data
 * 0xff. Returns the characters read, bit 8 set on flagged ones.
 */
static size_t read_frame(int fd, uint16_t *w, size_t want, double timeout_s)
{
	double end = now_s() + timeout_s;
	uint8_t b[3];
	size_t n = 0, have = 0;

	while (n < want && now_s() < end) {
		if (read(fd, b + have, 1) != 1) {
			usleep(500);
			continue;
		}
		if (have == 0 && b[0] != 0xff) {
			w[n++] = b[0];
		} else if (have == 1 && b[1] == 0xff) {
			w[n++] = 0xff;
			have = 0;
		} else if (have == 2) {
			w[n++] = TS7800_SIM_WORD_BIT9 | b[2];
			have = 0;
		} else {
			have++;
		}
	}
	return n;
}

/* One request/response through ADDR_DEST + write + read; 0 if right. */
static int transaction(int fd, unsigned int seq)
{
	uint8_t body[4 + 8], f[N_RS485_MAX_FRAME];
	uint16_t w[16];
	size_t i, n;

	f[0] = SLAVE_ADDR;
	f[1] = I_ECHO;
	f[2] = 0;
	f[3] = 7;
	for (i = 0; i < 7; i++)
		f[4 + i] = (uint8_t)(seq * 13 + i * 0x55);	/* 0xff included */
	memcpy(body, f + 1, 10);
	body[10] = crc8_maxim(f, 11);
	if (set_rs485(fd, SER_RS485_ENABLED | SER_RS485_ADDRB | SER_RS485_ADDR_DEST,
		      SLAVE_ADDR, 0))
		return -1;
	if (write(fd, body, 11) != 11)
		return -2;
	n = read_frame(fd, w, 12, 2.0);
	if (n != 12 || w[0] != (TS7800_SIM_WORD_BIT9 | SLAVE_ADDR))
		return -3;
	f[0] = SLAVE_ADDR;
	for (i = 1; i < 12; i++) {
		if (w[i] > 0xff)
			return -4;
		f[i] = (uint8_t)w[i];
	}
	if (f[1] != I_ECHO || f[2] != N_RS485_RESP_ACK || f[3] != 7 ||
	    memcmp(f + 4, body + 3, 7) || crc8_maxim(f, 11) != f[11])
		return -5;
	return 0;
}

static long first_difference(const uint16_t *a, const uint16_t *b, size_t n)
{
	size_t i;

	for (i = 0; i < n; i++)
		if (a[i] != b[i])
			return (long)i;
	return -1;
}

/* Drain the wire of port @port into @w (up to @max words) for @timeout_s. */
static size_t wire_collect(int wfd, uint16_t *w, size_t max, size_t want, double timeout_s)
{
	double end = now_s() + timeout_s;
	size_t n = 0;
	ssize_t r;

	while (n < want && n < max && now_s() < end) {
		r = read(wfd, w + n, (max - n) * 2);
		if (r > 0)
			n += r / 2;
		else
			usleep(1000);
	}
	return n;
}

int main(void)
{
	struct ts7800_sim_line_gaps g;
	struct serial_rs485 r;
	uint16_t w[600], exp[600];
	uint8_t body[300];
	const char *other;
	struct slave s;
	unsigned int i, bad = 0, first_bad = 0;
	size_t n, k;
	int fd, wfd, sfd, ret, err;

	tap_plan(15);
	if (sim_load())
		tap_bail("cannot load ts_uart + ts7800_sim");

	/*
	 * A port without addressing: serial_core refuses TIOCSRS485 itself.
	 * The guest's console UART, which has hardware: the ARM guest's 8250
	 * driver registers ttyS0 without any (TIOCSRS485 there: EIO).
	 */
	other = access("/dev/ttyAMA0", F_OK) == 0 ? "/dev/ttyAMA0" : "/dev/ttyS0";
	sfd = open(other, O_RDWR | O_NOCTTY | O_NONBLOCK);
	if (sfd < 0) {
		tap_skip("no %s to try ADDRB on a port without it", other);
	} else {
		ret = set_rs485(sfd, SER_RS485_ENABLED | SER_RS485_ADDRB, 0, 0);
		err = errno;
		tap_ok(ret == -1 && (err == ENOTTY || err == EINVAL),
		       "%s (no ADDRB): TIOCSRS485 with ADDRB fails (%s)", other,
		       ret ? strerror(err) : "succeeded");
		close(sfd);
	}

	/* A termios without room for the address bit: EINVAL, nothing changes. */
	fd = raw_open("/dev/ttyTSU0", PARENB);
	if (fd < 0)
		tap_bail("open ttyTSU0");
	ret = set_rs485(fd, SER_RS485_ENABLED | SER_RS485_ADDRB, 0, 0);
	err = errno;
	tap_ok(ret == -1 && err == EINVAL && !(cflag_of(fd) & ADDRB),
	       "ADDRB with 8E1 is refused: %s", ret ? strerror(err) : "succeeded");
	close(fd);
	fd = raw_open("/dev/ttyTSU0", CSTOPB);
	ret = set_rs485(fd, SER_RS485_ENABLED | SER_RS485_ADDRB, 0, 0);
	err = errno;
	tap_ok(ret == -1 && err == EINVAL, "ADDRB with 8N2 is refused: %s",
	       ret ? strerror(err) : "succeeded");
	ret = set_rs485(fd, SER_RS485_ENABLED | SER_RS485_ADDR_DEST, SLAVE_ADDR, 0);
	err = errno;
	tap_ok(ret == -1 && err == EINVAL, "ADDR_DEST without ADDRB is refused: %s",
	       ret ? strerror(err) : "succeeded");
	close(fd);

	/* 8N1: ADDRB is taken, shows in termios, and termios cannot undo it. */
	fd = raw_open("/dev/ttyTSU0", 0);
	ret = set_rs485(fd, SER_RS485_ENABLED | SER_RS485_ADDRB, 0, 0);
	memset(&r, 0, sizeof(r));
	ioctl(fd, TIOCGRS485, &r);
	tap_ok(ret == 0 && (r.flags & SER_RS485_ADDRB) && (cflag_of(fd) & ADDRB),
	       "ADDRB on 8N1: taken (flags %#x), termios has ADDRB", r.flags);
	{
		struct termios t;

		tcgetattr(fd, &t);
		t.c_cflag |= PARENB | CSTOPB;
		t.c_cflag &= ~ADDRB;
		tcsetattr(fd, TCSANOW, &t);
	}
	tap_ok((cflag_of(fd) & (ADDRB | PARENB | CSTOPB)) == ADDRB,
	       "tcsetattr(PARENB|CSTOPB, no ADDRB) under ADDRB: termios reports ADDRB, no parity, 1 stop bit (c_cflag %#o)",
	       cflag_of(fd));

	/* Request/response with the test slave (the BR board). */
	if (slave_start(&s, PORT))
		tap_bail("slave");
	wire_reset_stats(s.wfd);
	for (i = 0; i < XFERS; i++) {
		ret = transaction(fd, i);
		if (ret && !bad++)
			first_bad = i;
		if (ret && bad == 1)
			tap_diag("transaction %u failed: step %d", i, ret);
	}
	tap_ok(!bad, "%u transactions through ADDR_DEST + write + read: %u failed (first %u)",
	       XFERS, bad, first_bad);
	tap_ok(s.requests == XFERS && s.bad_frames == 0,
	       "the slave saw %u valid requests, each with its address as the only 9th-bit-1 character (%u bad frames)",
	       s.requests, s.bad_frames);
	ret = wire_gaps(s.wfd, &g);
	tap_ok(ret == 0 && g.frames[TS7800_SIM_LOG_TX] == XFERS &&
	       g.chars[TS7800_SIM_LOG_TX] == XFERS * 11 && g.frames[TS7800_SIM_LOG_RX] == XFERS,
	       "line gaps: %llu frames sent, %llu other characters, %llu frames received",
	       (unsigned long long)g.frames[TS7800_SIM_LOG_TX],
	       (unsigned long long)g.chars[TS7800_SIM_LOG_TX],
	       (unsigned long long)g.frames[TS7800_SIM_LOG_RX]);
	tap_diag("idle line inside the frames sent: %.1f us in all, longest %.1f us; before them %.1f us per frame",
		 g.char_idle_ns[TS7800_SIM_LOG_TX] / 1e3, g.char_idle_max_ns[TS7800_SIM_LOG_TX] / 1e3,
		 g.frame_idle_ns[TS7800_SIM_LOG_TX] / 1e3 / XFERS);
	slave_stop(&s);

	/*
	 * Order: the transmitter is held (hardware CTS off), so everything
	 * stays queued: address A, 200 data bytes, address B (set while they
	 * wait), 3 more; a third address while B waits behind data is EBUSY.
	 */
	wfd = wire_open(PORT, O_NONBLOCK);
	{
		struct termios t;

		tcgetattr(fd, &t);
		t.c_cflag |= CRTSCTS;
		tcsetattr(fd, TCSANOW, &t);
	}
	ioctl(wfd, TS7800_SIM_SET_CTS, &(uint32_t){ 0 });
	for (i = 0; i < 200; i++)
		body[i] = (uint8_t)i;
	ret = set_rs485(fd, SER_RS485_ENABLED | SER_RS485_ADDRB | SER_RS485_ADDR_DEST, 0x21, 0);
	ret |= write(fd, body, 200) != 200;
	ret |= set_rs485(fd, SER_RS485_ENABLED | SER_RS485_ADDRB | SER_RS485_ADDR_DEST, 0x22, 0);
	k = set_rs485(fd, SER_RS485_ENABLED | SER_RS485_ADDRB | SER_RS485_ADDR_DEST, 0x23, 0);
	err = errno;
	tap_ok(k == (size_t)-1 && err == EBUSY,
	       "a destination address while the last one waits behind queued data: %s",
	       k ? strerror(err) : "accepted");
	ret |= write(fd, body + 10, 3) != 3;
	ioctl(wfd, TS7800_SIM_SET_CTS, &(uint32_t){ 1 });
	n = wire_collect(wfd, w, 600, 205, 5.0);
	k = 0;
	exp[k++] = TS7800_SIM_WORD_BIT9 | 0x21;
	for (i = 0; i < 200; i++)
		exp[k++] = i;
	exp[k++] = TS7800_SIM_WORD_BIT9 | 0x22;
	for (i = 0; i < 3; i++)
		exp[k++] = 10 + i;
	tap_ok(!ret && n == k && !memcmp(w, exp, k * 2),
	       "the wire carries A, 200 bytes, B, 3 bytes in that order (%zu of %zu words, first difference at %ld)",
	       n, k, n < k ? (long)n : first_difference(w, exp, k));
	{
		struct termios t;

		tcgetattr(fd, &t);
		t.c_cflag &= ~CRTSCTS;
		tcsetattr(fd, TCSANOW, &t);
	}

	/* Receive: addresses flagged, ADDR_RECV lets only its own frames through. */
	{
		uint16_t in[] = { TS7800_SIM_WORD_BIT9 | 0x31, 1, 2, TS7800_SIM_WORD_BIT9 | 0x32,
				  3, 0xff, TS7800_SIM_WORD_BIT9 | 0x31, 4 };
		uint16_t want_all[] = { TS7800_SIM_WORD_BIT9 | 0x31, 1, 2,
					TS7800_SIM_WORD_BIT9 | 0x32, 3, 0xff,
					TS7800_SIM_WORD_BIT9 | 0x31, 4 };
		uint16_t want_31[] = { TS7800_SIM_WORD_BIT9 | 0x31, 1, 2,
				       TS7800_SIM_WORD_BIT9 | 0x31, 4 };

		tcflush(fd, TCIFLUSH);
		set_rs485(fd, SER_RS485_ENABLED | SER_RS485_ADDRB, 0, 0);
		wire_write_all(wfd, in, 8);
		n = read_frame(fd, w, 8, 3.0);
		tap_ok(n == 8 && !memcmp(w, want_all, sizeof(want_all)),
		       "without ADDR_RECV every character arrives, addresses flagged (%zu of 8)", n);
		set_rs485(fd, SER_RS485_ENABLED | SER_RS485_ADDRB | SER_RS485_ADDR_RECV, 0, 0x31);
		wire_write_all(wfd, in, 8);
		n = read_frame(fd, w, 6, 3.0);
		tap_ok(n == 5 && !memcmp(w, want_31, sizeof(want_31)),
		       "ADDR_RECV 0x31: only the frames to 0x31 arrive (%zu characters, 5 expected)", n);
	}

	/* RS-485 off: ADDRB leaves termios, the port is 8N1 (8-bit) again. */
	ret = set_rs485(fd, 0, 0, 0);
	{
		struct ts7800_sim_wire_stats st;
		uint8_t c = 0x41;

		wire_stats(wfd, &st);
		tap_ok(ret == 0 && !(cflag_of(fd) & ADDRB) && !(st.ctrl & STAT_MODE9),
		       "RS-485 off: no ADDRB in termios, MODE9 off (STAT ctrl %#x)", st.ctrl);
		ret = write(fd, &c, 1);
		n = wire_collect(wfd, w, 600, 1, 3.0);
		tap_ok(ret == 1 && n == 1 && w[0] == 0x41, "and sends 8N1 (wire word %#x)",
		       n ? w[0] : 0);
	}
	close(wfd);
	close(fd);
	sim_unload();
	return tap_finish();
}
