// SPDX-License-Identifier: GPL-2.0
/*
 * features - termios framing, break, CTS flow control, RS-485 ioctl, the
 * wire API, cross-connect, debugfs fault injection and the 8-port board.
 *
 * Framing: the TS-UART has no parity/stop-bit hardware; the driver builds
 * them inside an 8-bit or (MODE9) 9-bit character. The wire shows the exact
 * character, so each termios setting is checked bit for bit.
 */
#include <sys/ioctl.h>

#include "tsuart-lib.h"

static unsigned int parity8(unsigned int v)
{
	return __builtin_popcount(v & 0xff) & 1;
}

/* Send 'ch' with the given cflag and return the wire word (or 0xffff). */
static uint16_t tx_word(int port, tcflag_t cflag, uint8_t ch)
{
	int fd = tty_open(port, B115200, cflag, 0), wfd = wire_open(port, O_NONBLOCK);
	uint16_t w = 0xffff, drain[64];

	if (fd < 0 || wfd < 0)
		goto out;
	while (read(wfd, drain, sizeof(drain)) > 0)
		;
	tty_write_all(fd, &ch, 1);
	tcdrain(fd);
	if (wire_read_n(wfd, &w, 1, 2, NULL) != 1)
		w = 0xffff;
out:
	if (fd >= 0)
		close(fd);
	if (wfd >= 0)
		close(wfd);
	return w;
}

static void framing(void)
{
	uint8_t c = 0x35;	/* four ones: even parity bit 0, odd parity bit 1 */

	tap_ok(tx_word(0, 0, c) == c, "8N1: 8-bit character, 9th bit not sent");
	tap_ok(tx_word(0, PARENB, c) == (uint16_t)(c | parity8(c) << 8),
	       "8E1: MODE9, 9th bit = even parity");
	tap_ok(tx_word(0, PARENB | PARODD, c) == (uint16_t)(c | !parity8(c) << 8),
	       "8O1: MODE9, 9th bit = odd parity");
	tap_ok(tx_word(0, CSTOPB, c) == (0x100 | c), "8N2: MODE9, 9th bit = 1 (second stop bit)");
	tap_ok(tx_word(0, PARENB | CMSPAR | PARODD, c) == (0x100 | c),
	       "8 mark (CMSPAR|PARODD): 9th bit 1");
	tap_ok(tx_word(0, PARENB | CMSPAR, c) == c, "8 space (CMSPAR): 9th bit 0");
}

static void framing7(void)
{
	/* tty_open sets CS8; CS7 needs the size bits replaced. */
	int fd = tty_open(1, B115200, 0, 0), wfd = wire_open(1, O_NONBLOCK);
	uint16_t w[4];
	struct termios t;
	uint8_t c = 0x35 | 0x80;	/* bit 7 must not be sent in CS7 */
	size_t n;

	tcgetattr(fd, &t);
	t.c_cflag = (t.c_cflag & ~CSIZE) | CS7 | PARENB;		/* 7E1 */
	tcsetattr(fd, TCSANOW, &t);
	tty_write_all(fd, &c, 1);
	t.c_cflag |= CSTOPB;						/* 7E2 */
	tcsetattr(fd, TCSADRAIN, &t);
	tty_write_all(fd, &c, 1);
	t.c_cflag &= ~(PARENB | CSTOPB);				/* 7N1 */
	tcsetattr(fd, TCSADRAIN, &t);
	tty_write_all(fd, &c, 1);
	tcdrain(fd);
	n = wire_read_n(wfd, w, 3, 2, NULL);
	if (n < 3)
		memset(w + n, 0xff, (3 - n) * sizeof(w[0]));
	tap_ok(n == 3 && w[0] == (0x35 | (parity8(0x35) << 7)),
	       "7E1: 8-bit character, bit 7 = even parity (0x%03x)", w[0]);
	tap_ok(n == 3 && w[1] == (0x100 | 0x35 | (parity8(0x35) << 7)),
	       "7E2: MODE9, parity in bit 7, stop bit in bit 8 (0x%03x)", w[1]);
	tap_ok(n == 3 && w[2] == (0x80 | 0x35), "7N1: bit 7 is the stop bit (0x%03x)", w[2]);

	/* RX 7N1: a 0 where the stop bit belongs is a framing error. */
	{
		uint16_t in[2] = { 0x80 | 0x41, 0x42 }, got[2];

		t.c_iflag = INPCK | PARMRK;
		tcsetattr(fd, TCSANOW, &t);
		wire_write_all(wfd, in, 2);
		n = tty_read_words(fd, got, 2, 2, NULL);
		tap_ok(n == 2 && got[0] == 0x41 && got[1] == (0x100 | 0x42),
		       "7N1 receive: good stop bit plain, missing stop bit flagged (TTY_FRAME)");
	}
	close(fd);
	close(wfd);
}

static void rx_parity(void)
{
	int fd = tty_open(2, B115200, PARENB, 0), wfd = wire_open(2, 0);	/* 8E1 */
	uint16_t in[2], got[2];
	size_t n;

	in[0] = 0x35 | (parity8(0x35) << 8);		/* good parity */
	in[1] = 0x35 | (!parity8(0x35) << 8);		/* bad parity */
	wire_write_all(wfd, in, 2);
	n = tty_read_words(fd, got, 2, 2, NULL);
	tap_ok(n == 2 && got[0] == 0x35 && got[1] == (0x100 | 0x35),
	       "8E1 receive: parity checked in software, error flagged TTY_PARITY");
	close(fd);
	close(wfd);
}

static void breaks(void)
{
	int fd = tty_open(3, B9600, 0, 0), wfd = wire_open(3, 0);
	uint16_t w = 0, brk = TS7800_SIM_WORD_BREAK, ch = 'z';
	uint8_t buf[8];
	size_t n;

	tcsendbreak(fd, 0);
	n = wire_read_n(wfd, &w, 1, 2, NULL);
	tap_ok(n == 1 && w == TS7800_SIM_WORD_BREAK, "tcsendbreak: the wire sees a break (0x%03x)",
	       w);
	wire_write_all(wfd, &brk, 1);
	wire_write_all(wfd, &ch, 1);
	n = tty_read_n(fd, buf, 4, 2);
	tap_ok(n == 4 && !memcmp(buf, "\377\0\0z", 4),
	       "a break on the wire arrives as TTY_BREAK (PARMRK \\377 \\0 \\0) before the next character");
	close(fd);
	close(wfd);
}

static void flow_control(void)
{
	int fd = tty_open(4, B9600, CRTSCTS, 0), wfd = wire_open(4, 0);
	struct ts7800_sim_wire_stats st;
	unsigned int off = 0, on = 1;
	uint16_t w[20];
	int mctrl = 0;

	ioctl(wfd, TS7800_SIM_SET_CTS, &off);
	ioctl(fd, TIOCMGET, &mctrl);
	tap_ok(!(mctrl & TIOCM_CTS), "TIOCMGET shows CTS deasserted");
	ioctl(wfd, TS7800_SIM_RESET_STATS);
	tty_write_all(fd, (const uint8_t *)"0123456789", 10);
	usleep(300000);		/* 10 chars would take 10 ms */
	wire_stats(wfd, &st);
	tap_ok(st.to_wire == 0 && (st.ctrl & 0x4000), "CRTSCTS sets HWCTS: nothing is sent while CTS is off");
	ioctl(wfd, TS7800_SIM_SET_CTS, &on);
	tap_ok(wire_read_n(wfd, w, 10, 2, NULL) == 10 && w[0] == '0' && w[9] == '9',
	       "CTS on: the held characters go out");
	close(fd);
	close(wfd);
}

static void rs485(void)
{
	int fd = tty_open(5, B115200, 0, 0);
	struct serial_rs485 r = { .flags = SER_RS485_ENABLED | SER_RS485_RX_DURING_TX };
	struct serial_rs485 g = { 0 };

	tap_ok(ioctl(fd, TIOCSRS485, &r) == 0 && ioctl(fd, TIOCGRS485, &g) == 0 &&
	       (g.flags & SER_RS485_ENABLED), "TIOCSRS485 is accepted and read back");
	close(fd);
}

static void wire_api(void)
{
	int wfd = wire_open(6, O_NONBLOCK);
	uint16_t w[2];
	uint8_t odd[3] = { 0 };
	struct pollfd p = { .fd = wfd, .events = POLLIN | POLLOUT };

	tap_ok(read(wfd, w, sizeof(w)) < 0 && errno == EAGAIN, "wire: empty read gives EAGAIN");
	tap_ok(write(wfd, odd, 3) < 0 && errno == EINVAL, "wire: odd byte count gives EINVAL");
	tap_ok(poll(&p, 1, 0) == 1 && p.revents == POLLOUT, "wire: poll says writable, not readable");
	close(wfd);
}

static void cross_connect(void)
{
	int a = tty_open(7, B57600, PARENB | CMSPAR | PARODD, 0);
	int b = tty_open(8, B57600, PARENB | CMSPAR, 0);
	uint8_t msg[4] = { 0x10, 0x20, 0xff, 0x00 };
	uint16_t got[4];
	size_t n;

	debugfs_write(7, "peer", 8);
	tty_write_all(a, msg, 4);
	n = tty_read_words(b, got, 4, 2, NULL);
	tap_ok(n == 4 && got[0] == 0x110 && got[2] == 0x1ff && got[3] == 0x100,
	       "ports 7 and 8 cross-connected: mark-parity characters arrive flagged at a space-parity port");
	debugfs_write(7, "peer", -1);
	close(a);
	close(b);
}

static void faults(void)
{
	int fd = tty_open(9, B115200, 0, 0), wfd = wire_open(9, 0);
	uint16_t in[6] = { 'a', 'b', 'c', 'd', 'e', 'f' }, got[6];
	uint8_t buf[64];
	size_t n;

	debugfs_write(9, "rx_drop", 2);
	debugfs_write(9, "rx_corrupt", 1);
	debugfs_write(9, "rx_corrupt_xor", 0x20);
	wire_write_all(wfd, in, 6);
	n = tty_read_words(fd, got, 4, 2, NULL);
	tap_ok(n == 4 && got[0] == 'C' && got[1] == 'd' && got[3] == 'f',
	       "debugfs rx_drop 2 + rx_corrupt 1: the receiver gets C d e f");
	debugfs_write(9, "noise", 20);
	n = tty_read_n(fd, buf, 20, 2);
	tap_ok(n >= 20, "debugfs noise 20: 20 random characters arrive (%zu bytes)", n);
	close(fd);
	close(wfd);
}

int main(void)
{
	tap_plan(27);
	if (!tap_ok(sim_load("") == 0, "load ts_uart and ts7800_sim"))
		tap_bail("cannot continue without the simulator");
	framing();
	framing7();
	rx_parity();
	breaks();
	flow_control();
	rs485();
	wire_api();
	cross_connect();
	faults();
	tap_ok(sim_unload() == 0, "unload");

	tap_ok(sh("modprobe ts_uart && modprobe ts7800_sim pc104_rowc_bus=1") == 0 &&
	       wait_ports(8) == 0 && access("/dev/ttyTSU8", F_OK) != 0,
	       "PC/104 row C pins in bus use: only TS-UART 0..7 exist");
	tap_ok(sim_unload() == 0, "unload");
	return tap_finish();
}
