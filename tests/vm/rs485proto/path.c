// SPDX-License-Identifier: GPL-2.0
/*
 * path - the transmit path n_rs485 chooses at attach (n_rs485_stats.tx_path)
 * and what it costs per frame, from the discipline's own counters:
 * on the TS-UART, which offers 9-bit addressing, N_RS485_PATH_ADDRB with no
 * termios switch and no drain between address and data (one drain per
 * frame); with the module parameter addrb=0, N_RS485_PATH_PARITY with two
 * switches and two drains per frame, one between address and data. The
 * port's RS-485 setting is the user's again after detach, the statistics
 * request of a program built before the counters existed still works, and
 * the simulator's line shows the idle time inside the frames (reported).
 */
#include <linux/serial.h>

#include "rs485-lib.h"

#define PORT		0
/* transactions per path; VMTEST_APPEND=rs485_path_xfers=N changes it */
#define XFERS_DEFAULT	300

static unsigned int xfers;
/* N_RS485_IOC_GET_STATS as a program built before issue 20 has it */
#define GET_STATS_V1	_IOC(_IOC_READ, N_RS485_IOC_MAGIC, 4, 18 * 8)

static int set_addrb_param(int on)
{
	return sh("echo %d > /sys/module/n_rs485/parameters/addrb", on);
}

/* xfers echo transactions; returns how many failed. */
static unsigned int run_xfers(int fd)
{
	uint8_t data[8] = { 1, 2, 3, 4, 5, 6, 7, 8 };
	struct n_rs485_xfer x;
	unsigned int i, bad = 0;
	int ret;

	for (i = 0; i < xfers; i++) {
		data[0] = i;
		ret = xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, data, 8, 300000, 0);
		if (ret || x.status != N_RS485_OK || x.resp.len != 8 ||
		    memcmp(x.resp.data, data, 8)) {
			if (!bad++)
				tap_diag("transaction %u failed: ioctl %d, status %u, attempts %u, response length %u",
					 i, ret, x.status, x.attempts, x.resp.len);
		}
	}
	return bad;
}

static void report_gaps(struct slave *s, const char *path)
{
	struct ts7800_sim_line_gaps g;

	if (wire_gaps(s->wfd, &g))
		return;
	tap_diag("%s: line idle inside the requests %.2f us per frame (longest %.1f us), before them %.1f us per frame",
		 path, g.char_idle_ns[TS7800_SIM_LOG_TX] / 1e3 / xfers,
		 g.char_idle_max_ns[TS7800_SIM_LOG_TX] / 1e3,
		 g.frame_idle_ns[TS7800_SIM_LOG_TX] / 1e3 / xfers);
}

/* Switch @fd to discipline @ld; the port's RS-485 setting then in @r. */
static void rs485_after_ldisc(int fd, int ld, struct serial_rs485 *r)
{
	if (ioctl(fd, TIOCSETD, &ld))
		tap_diag("TIOCSETD %d: %s", ld, strerror(errno));
	memset(r, 0, sizeof(*r));
	ioctl(fd, TIOCGRS485, r);
}

/*
 * Attach with the module parameter addrb=@addrb, run the transactions
 * (one test point), report the line; the port's RS-485 setting and termios
 * while attached in @r and @t, the statistics in @st. Returns the fd.
 */
static int run_path(struct slave *s, int addrb, const char *name, struct serial_rs485 *r,
		    struct termios *t, struct n_rs485_stats *st)
{
	unsigned int bad;
	int fd;

	set_addrb_param(addrb);
	fd = bus_open(PORT);
	if (fd < 0)
		tap_bail("attach n_rs485 with addrb=%d", addrb);
	memset(r, 0, sizeof(*r));
	ioctl(fd, TIOCGRS485, r);
	tcgetattr(fd, t);
	wire_reset_stats(s->wfd);
	bad = run_xfers(fd);
	memset(st, 0, sizeof(*st));
	get_stats(fd, st);
	tap_ok(!bad && st->tx_frames == xfers, "%s: %u transactions, %u failed, %llu frames sent",
	       name, xfers, bad, (unsigned long long)st->tx_frames);
	report_gaps(s, name);
	return fd;
}

int main(void)
{
	struct n_rs485_stats st, old;
	struct serial_rs485 r;
	struct termios t;
	struct slave s;
	int fd;

	xfers = cmdline_ulong("rs485_path_xfers", XFERS_DEFAULT);
	if (!xfers)
		tap_bail("rs485_path_xfers=0");
	tap_plan(10);
	if (sim_load())
		tap_bail("cannot load ts_uart + ts7800_sim");
	if (slave_start(&s, PORT))
		tap_bail("slave");

	fd = bus_open(PORT);
	if (fd < 0)
		tap_bail("attach n_rs485");
	close(fd);
	/* attached with addrb=1, whatever the boot said */
	fd = run_path(&s, 1, "addressing path", &r, &t, &st);
	tap_ok(st.tx_path == N_RS485_PATH_ADDRB && (r.flags & SER_RS485_ADDRB) &&
	       (t.c_cflag & ADDRB) && !(t.c_cflag & PARENB),
	       "TS-UART: the addressing path (tx_path %llu, port RS-485 flags %#x, termios ADDRB %d, PARENB %d)",
	       (unsigned long long)st.tx_path, r.flags, !!(t.c_cflag & ADDRB), !!(t.c_cflag & PARENB));
	tap_ok(st.termios_switches == 0 && st.addr_drains == 0 && st.drains == st.tx_frames,
	       "per frame: %.2f termios switches, %.2f drains between address and data, %.2f drains",
	       (double)st.termios_switches / st.tx_frames, (double)st.addr_drains / st.tx_frames,
	       (double)st.drains / st.tx_frames);
	memset(&old, 0xa5, sizeof(old));
	tap_ok(ioctl(fd, GET_STATS_V1, &old) == 0 && old.tx_frames == st.tx_frames &&
	       old.tx_path == 0xa5a5a5a5a5a5a5a5ull,
	       "the 144-byte statistics request of an older program: its fields, nothing beyond");
	close(fd);

	fd = open("/dev/ttyTSU0", O_RDWR | O_NOCTTY);
	memset(&r, 0xff, sizeof(r));
	ioctl(fd, TIOCGRS485, &r);
	tcgetattr(fd, &t);
	tap_ok(fd >= 0 && r.flags == 0 && !(t.c_cflag & ADDRB),
	       "after detach the port's RS-485 setting is the user's again (flags %#x, ADDRB %d)",
	       r.flags, !!(t.c_cflag & ADDRB));
	close(fd);

	fd = run_path(&s, 0, "mark/space path", &r, &t, &st);
	tap_ok(st.tx_path == N_RS485_PATH_PARITY && !(r.flags & SER_RS485_ENABLED) &&
	       (t.c_cflag & (PARENB | CMSPAR)) == (PARENB | CMSPAR),
	       "addrb=0: the mark/space path (tx_path %llu, port RS-485 flags %#x)",
	       (unsigned long long)st.tx_path, r.flags);
	tap_ok(st.termios_switches == 2 * st.tx_frames && st.addr_drains == st.tx_frames &&
	       st.drains == 2 * st.tx_frames,
	       "per frame: %.2f termios switches, %.2f drains between address and data, %.2f drains",
	       (double)st.termios_switches / st.tx_frames, (double)st.addr_drains / st.tx_frames,
	       (double)st.drains / st.tx_frames);
	close(fd);
	set_addrb_param(1);

	/* A user's RS-485 setting (RTS after send) is kept while attached. */
	fd = open("/dev/ttyTSU0", O_RDWR | O_NOCTTY);
	memset(&r, 0, sizeof(r));
	r.flags = SER_RS485_ENABLED | SER_RS485_RTS_AFTER_SEND;
	ioctl(fd, TIOCSRS485, &r);
	rs485_after_ldisc(fd, N_RS485_DEFAULT_LDISC, &r);
	tap_ok((r.flags & (SER_RS485_RTS_AFTER_SEND | SER_RS485_RTS_ON_SEND | SER_RS485_ADDRB)) ==
	       (SER_RS485_RTS_AFTER_SEND | SER_RS485_ADDRB),
	       "attached over the user's RTS-after-send setting: kept, ADDRB added (flags %#x)",
	       r.flags);
	rs485_after_ldisc(fd, N_TTY, &r);
	tap_ok((r.flags & (SER_RS485_ENABLED | SER_RS485_RTS_AFTER_SEND | SER_RS485_ADDRB)) ==
	       (SER_RS485_ENABLED | SER_RS485_RTS_AFTER_SEND),
	       "and after detach exactly that again (flags %#x)", r.flags);
	r.flags = 0;
	ioctl(fd, TIOCSRS485, &r);
	close(fd);

	slave_stop(&s);
	sim_unload();
	return tap_finish();
}
