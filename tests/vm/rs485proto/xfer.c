// SPDX-License-Identifier: GPL-2.0
/*
 * xfer - every transaction outcome of the protocol over the simulated
 * TS-UART, with a slave program on the wire: OK, TIMEOUT (plain repeats),
 * BADCRC (RESEND, the slave does not execute twice), UNKINSTR, DEVERR,
 * broadcast and NOACK, an event frame before the response (never taken as
 * the response, reaches read() byte-exact), a response from the wrong node,
 * the per-node error counters, statistics, read()/poll() semantics, and the
 * termios the discipline sets on attach and restores on detach.
 */
#include "rs485-lib.h"

#define PORT	0
#define LONG_US	300000		/* an emulated CPU may answer late */

static int check_frame_read(int fd, const uint8_t *expect, size_t n, const char *what)
{
	struct pollfd p = { .fd = fd, .events = POLLIN };
	uint8_t buf[N_RS485_MAX_FRAME];
	ssize_t r;

	if (poll(&p, 1, 2000) != 1)
		return tap_ok(0, "%s: poll reports a frame", what);
	r = read(fd, buf, sizeof(buf));
	if (r != (ssize_t)n || memcmp(buf, expect, n)) {
		tap_diag("read returned %zd (want %zu)", r, n);
		return tap_ok(0, "%s: read() returns the frame byte-exact", what);
	}
	return tap_ok(1, "%s: read() returns the frame byte-exact", what);
}

int main(void)
{
	struct termios before, during, after;
	struct n_rs485_stats st;
	tcflag_t ninth;
	struct n_rs485_xfer x;
	struct n_rs485_node node;
	struct slave s;
	uint8_t data[255], ev[6];
	unsigned int i, e0;
	int fd, ld = 0, ret;

	tap_plan(44);
	if (sim_load())
		tap_bail("cannot load ts_uart + ts7800_sim");
	fd = open("/dev/ttyTSU0", O_RDWR | O_NOCTTY);
	if (fd < 0)
		tap_bail("open /dev/ttyTSU0");
	tcgetattr(fd, &before);
	ld = N_RS485_DEFAULT_LDISC;
	tap_ok(ioctl(fd, TIOCSETD, &ld) == 0, "TIOCSETD 29 attaches (module autoloaded)");
	ld = 0;
	tap_ok(ioctl(fd, TIOCGETD, &ld) == 0 && ld == N_RS485_DEFAULT_LDISC, "TIOCGETD says 29");
	/* the 9th bit: space parity, or on the addressing path ADDRB without parity */
	memset(&st, 0, sizeof(st));
	get_stats(fd, &st);
	ninth = st.tx_path == N_RS485_PATH_ADDRB ? ADDRB : PARENB | CMSPAR;
	tap_ok(tcgetattr(fd, &during) == 0 &&
	       (during.c_cflag & (CSIZE | PARENB | CMSPAR | PARODD | ADDRB)) == (CS8 | ninth) &&
	       (during.c_iflag & INPCK) && !(during.c_iflag & IGNPAR) &&
	       cfgetospeed(&during) == B115200,
	       "attach sets 115200 Bd, CS8, %s, INPCK, no IGNPAR (tcgetattr works)",
	       st.tx_path == N_RS485_PATH_ADDRB ? "ADDRB (addressing path)" : "space parity");
	if (slave_start(&s, PORT))
		tap_bail("slave on the wire");

	for (i = 0; i < sizeof(data); i++)
		data[i] = i * 7 + 3;

	/* OK, with the largest payload and with none */
	ret = xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, data, 255, LONG_US, 0);
	tap_ok(ret == 0 && x.status == N_RS485_OK && x.attempts == 1 && x.resp.addr == SLAVE_ADDR &&
	       x.resp.instr == I_ECHO && x.resp.flags == N_RS485_RESP_ACK && x.resp.len == 255 &&
	       !memcmp(x.resp.data, data, 255),
	       "OK: 255 data bytes echoed byte-exact (status %u, attempts %u)", x.status,
	       x.attempts);
	pthread_mutex_lock(&s.last_lock);
	tap_ok(s.last_len == 259 && s.last[0] == SLAVE_ADDR && s.last[1] == I_ECHO &&
	       s.last[2] == 0 && !memcmp(s.last + 4, data, 255),
	       "the slave saw the request with a good CRC and the 9th bit on the address only");
	pthread_mutex_unlock(&s.last_lock);
	ret = xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, NULL, 0, LONG_US, 0);
	tap_ok(ret == 0 && x.status == N_RS485_OK && x.resp.len == 0, "OK: no data");
	tap_ok(s.bad_frames == 0, "no malformed frame on the wire (%u)", s.bad_frames);

	/* TIMEOUT: the request is repeated as it was */
	e0 = s.executions[I_SILENT];
	ret = xfer(fd, &x, SLAVE_ADDR, I_SILENT, 0, NULL, 0, 20000, 2);
	tap_ok(ret == 0 && x.status == N_RS485_TIMEOUT && x.attempts == 3,
	       "TIMEOUT after 1 + 2 retries (status %u, attempts %u)", x.status, x.attempts);
	tap_ok(s.executions[I_SILENT] - e0 == 3, "a retry after a timeout repeats the request (%u)",
	       s.executions[I_SILENT] - e0);
	ret = xfer(fd, &x, 0x42, I_ECHO, 0, NULL, 0, 5000, 0);
	tap_ok(ret == 0 && x.status == N_RS485_TIMEOUT && x.attempts == 1,
	       "TIMEOUT from an absent node, no retries");

	/* BADCRC then RESEND */
	e0 = s.resends;
	ret = xfer(fd, &x, SLAVE_ADDR, I_CORRUPT_ONCE, 0, NULL, 0, LONG_US, 2);
	tap_ok(ret == 0 && x.status == N_RS485_OK && x.attempts == 2 && x.resp.len == 1 &&
	       x.resp.data[0] == 0x5a,
	       "corrupted response: RESEND gets the good one (status %u, attempts %u)", x.status,
	       x.attempts);
	tap_ok(s.executions[I_CORRUPT_ONCE] == 1 && s.resends - e0 == 1,
	       "the slave saw RESEND and executed once (%u executions, %u resends)",
	       s.executions[I_CORRUPT_ONCE], s.resends - e0);
	e0 = s.resends;
	ret = xfer(fd, &x, SLAVE_ADDR, I_CORRUPT, 0, NULL, 0, LONG_US, 2);
	tap_ok(ret == 0 && x.status == N_RS485_BADCRC && x.attempts == 3,
	       "BADCRC after retries (status %u, attempts %u)", x.status, x.attempts);
	tap_ok(s.executions[I_CORRUPT] == 1 && s.resends - e0 == 2,
	       "...every retry was a RESEND (%u executions, %u resends)", s.executions[I_CORRUPT],
	       s.resends - e0);

	/* UNKINSTR, DEVERR */
	ret = xfer(fd, &x, SLAVE_ADDR, I_UNKNOWN, 0, NULL, 0, LONG_US, 2);
	tap_ok(ret == 0 && x.status == N_RS485_UNKINSTR && x.attempts == 1, "UNKINSTR, not retried");
	ret = xfer(fd, &x, SLAVE_ADDR, I_DEVERR, 0, NULL, 0, LONG_US, 2);
	tap_ok(ret == 0 && x.status == N_RS485_DEVERR && x.resp.len == 2 && x.resp.data[0] == 0xde &&
	       x.resp.data[1] == 0xad, "DEVERR with its data");

	/* broadcast and NOACK: back when the frame is on the wire */
	e0 = s.broadcasts;
	ret = xfer(fd, &x, N_RS485_ADDR_BROADCAST, I_ECHO, 0, data, 3, LONG_US, 2);
	tap_ok(ret == 0 && x.status == N_RS485_OK && x.attempts == 1, "broadcast: OK, one attempt");
	e0 = s.executions[I_ECHO];
	ret = xfer(fd, &x, SLAVE_ADDR, I_ECHO, N_RS485_REQ_NOACK, data, 3, LONG_US, 2);
	tap_ok(ret == 0 && x.status == N_RS485_OK && x.attempts == 1, "NOACK: OK, one attempt");
	usleep(50000);
	tap_ok(s.executions[I_ECHO] - e0 == 1 && s.broadcasts >= 1,
	       "the slave got the broadcast and the NOACK request");
	ret = xfer(fd, &x, SLAVE_ADDR, I_ECHO, N_RS485_REQ_RESEND, NULL, 0, LONG_US, 2);
	tap_ok(ret == -1 && errno == EINVAL, "RESEND from the caller is refused (EINVAL)");

	/* an event before the response: never the response, reaches read() */
	ret = xfer(fd, &x, SLAVE_ADDR, I_EVENT_FIRST, 0, data, 9, LONG_US, 0);
	tap_ok(ret == 0 && x.status == N_RS485_OK && x.resp.flags == N_RS485_RESP_ACK &&
	       x.resp.len == 9 && !memcmp(x.resp.data, data, 9),
	       "event frame before the response: the transaction gets the response (ret %d, status %u, attempts %u, %u bytes)",
	       ret, x.status, x.attempts, (unsigned int)x.resp.len);
	ev[0] = SLAVE_ADDR;
	ev[1] = I_EVENT_FIRST;
	ev[2] = N_RS485_RESP_EVENT;
	ev[3] = 2;
	ev[4] = 9;
	ev[5] = 0xee;
	check_frame_read(fd, ev, 6, "event");

	/* response from the wrong node: a timeout, the frame goes to read() */
	ret = xfer(fd, &x, SLAVE_ADDR, I_WRONG_ADDR, 0, NULL, 0, 30000, 0);
	tap_ok(ret == 0 && x.status == N_RS485_TIMEOUT, "response from another node: TIMEOUT");
	ev[0] = OTHER_ADDR;
	ev[1] = I_WRONG_ADDR;
	ev[2] = N_RS485_RESP_ACK;
	ev[3] = 0;
	check_frame_read(fd, ev, 4, "unexpected frame");

	/* read() semantics */
	{
		struct pollfd p = { .fd = fd, .events = POLLIN };
		uint8_t small[3];
		int fl = fcntl(fd, F_GETFL);

		fcntl(fd, F_SETFL, fl | O_NONBLOCK);
		ret = read(fd, small, sizeof(small));
		tap_ok(ret == -1 && errno == EAGAIN, "O_NONBLOCK read with no frame: EAGAIN");
		tap_ok(poll(&p, 1, 0) == 0, "poll: nothing to read");
		xfer(fd, &x, SLAVE_ADDR, I_EVENT_FIRST, 0, data, 1, LONG_US, 0);
		poll(&p, 1, 2000);
		ioctl(fd, FIONREAD, &ld);
		tap_ok(ld == 6, "FIONREAD gives the size of the next frame (%d)", ld);
		ret = read(fd, small, sizeof(small));
		tap_ok(ret == -1 && errno == EOVERFLOW, "short buffer: EOVERFLOW");
		ret = read(fd, small, sizeof(small));
		tap_ok(ret == -1 && errno == EAGAIN, "...and the frame is gone");
		fcntl(fd, F_SETFL, fl);
	}

	/* write(): a raw request frame */
	{
		uint8_t raw[8] = { SLAVE_ADDR, I_ECHO, 0, 2, 0xab, 0xcd };
		uint8_t want[6] = { SLAVE_ADDR, I_ECHO, N_RS485_RESP_ACK, 2, 0xab, 0xcd };

		tap_ok(write(fd, raw, 6) == 6, "write() of a raw request frame");
		check_frame_read(fd, want, 6, "response to a raw write");
		tap_ok(write(fd, raw, 5) == -1 && errno == EINVAL, "write() with a wrong length: EINVAL");
	}

	/* node error counters */
	memset(&node, 0, sizeof(node));
	node.addr = SLAVE_ADDR;
	ret = ioctl(fd, N_RS485_IOC_RESET_NODE, &node);
	for (i = 0; i < 16; i++)
		xfer(fd, &x, SLAVE_ADDR, I_SILENT, 0, NULL, 0, 1000, 0);
	node.addr = SLAVE_ADDR;
	ret |= ioctl(fd, N_RS485_IOC_GET_NODE, &node);
	tap_ok(ret == 0 && node.errors == 128 && node.state == N_RS485_NODE_PASSIVE,
	       "16 failures: counter 128, error-passive (%u, state %u)", node.errors, node.state);
	for (i = 0; i < 20; i++)
		xfer(fd, &x, SLAVE_ADDR, I_SILENT, 0, NULL, 0, 1000, 0);
	ioctl(fd, N_RS485_IOC_GET_NODE, &node);
	tap_ok(node.errors == 256 && node.state == N_RS485_NODE_OFF, "36 failures: off (%u)",
	       node.errors);
	xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, NULL, 0, LONG_US, 0);
	ioctl(fd, N_RS485_IOC_GET_NODE, &node);
	tap_ok(x.status == N_RS485_OK && node.errors == 0 && node.state == N_RS485_NODE_ACTIVE,
	       "a good answer brings an off node back (%u)", node.errors);
	for (i = 0; i < 3; i++)
		xfer(fd, &x, SLAVE_ADDR, I_SILENT, 0, NULL, 0, 1000, 0);
	xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, NULL, 0, LONG_US, 0);
	ioctl(fd, N_RS485_IOC_GET_NODE, &node);
	tap_ok(node.errors == 23, "+8 per failure, -1 per success (%u)", node.errors);
	ioctl(fd, N_RS485_IOC_RESET_NODE, &node);
	ioctl(fd, N_RS485_IOC_GET_NODE, &node);
	tap_ok(node.errors == 0, "N_RS485_IOC_RESET_NODE clears it");

	/* configuration */
	{
		struct n_rs485_config c, c2;

		memset(&c, 0, sizeof(c));
		tap_ok(ioctl(fd, N_RS485_IOC_GET_CONFIG, &c) == 0 && c.baud == 115200 &&
		       c.timeout_us == 10000 && c.retries == 2 && c.gap_chars == 2,
		       "default config: 115200 Bd, 10 ms, 2 retries, gap 2");
		c2 = c;
		c2.baud = 57600;
		c2.gap_chars = 1;
		tap_ok(ioctl(fd, N_RS485_IOC_SET_CONFIG, &c2) == -1 && errno == EINVAL,
		       "gap below 2 characters: EINVAL");
		c2.gap_chars = 4;
		ret = ioctl(fd, N_RS485_IOC_SET_CONFIG, &c2);
		tcgetattr(fd, &during);
		tap_ok(ret == 0 && cfgetospeed(&during) == B57600, "SET_CONFIG 57600 Bd reaches the port");
		ret = xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, data, 20, LONG_US, 0);
		tap_ok(ret == 0 && x.status == N_RS485_OK && !memcmp(x.resp.data, data, 20),
		       "a transaction at 57600 Bd");
		ioctl(fd, N_RS485_IOC_SET_CONFIG, &c);
	}

	/* statistics add up */
	get_stats(fd, &st);
	tap_diag("stats: xfers %llu ok %llu failed %llu tx %llu rx %llu crc %llu timeouts %llu retries %llu events %llu unexpected %llu",
		 (unsigned long long)st.xfers, (unsigned long long)st.xfers_ok,
		 (unsigned long long)st.xfers_failed, (unsigned long long)st.tx_frames,
		 (unsigned long long)st.rx_frames, (unsigned long long)st.rx_crc_errors,
		 (unsigned long long)st.timeouts, (unsigned long long)st.retries,
		 (unsigned long long)st.events, (unsigned long long)st.unexpected);
	tap_ok(st.xfers == st.xfers_ok + st.xfers_failed && st.xfers > 40 &&
	       st.rx_crc_errors == 4 && st.events >= 3 && st.unexpected >= 2,
	       "statistics: xfers = ok + failed, 4 CRC errors, events counted");

	slave_stop(&s);
	ld = N_TTY;
	tap_ok(ioctl(fd, TIOCSETD, &ld) == 0 && tcgetattr(fd, &after) == 0 &&
	       after.c_cflag == before.c_cflag && after.c_iflag == before.c_iflag &&
	       cfgetospeed(&after) == cfgetospeed(&before),
	       "detach restores the termios of before");
	close(fd);
	tap_ok(sh("modprobe -r n_rs485") == 0, "n_rs485 unloads after detach");
	sim_unload();
	return tap_finish();
}
