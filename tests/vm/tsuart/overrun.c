// SPDX-License-Identifier: GPL-2.0
/*
 * overrun - a receiver that is served too late must report the overrun.
 *
 * The simulator's irq_hold fault makes the CPU "not respond" while 40
 * characters arrive at a port with a 16-character FIFO: 24 are lost in the
 * hardware. After release the port must deliver exactly the first 16, count
 * the overrun in TIOCGICOUNT, pass a TTY_OVERRUN to the line discipline (N_TTY
 * logs "input overrun(s)") and then carry traffic normally again. Run for
 * both OERR clearing rules and both interrupt trigger rules.
 */
#include <sys/ioctl.h>

#include "tsuart-lib.h"

#define SENT 40

static const char *const params[] = {
	"fifo_depth=16",
	"fifo_depth=16 edge_irq=1 oerr_clear_on_data=1",
};

static int wait_line(int wfd, unsigned long long total, struct ts7800_sim_wire_stats *st)
{
	int i;

	for (i = 0; i < 300; i++) {
		if (wire_stats(wfd, st))
			return -1;
		if (st->from_wire + st->rx_overruns >= total)
			return 0;
		usleep(10000);
	}
	return -1;
}

static void run(const char *p, int port)
{
	struct serial_icounter_struct ic0, ic1;
	struct ts7800_sim_wire_stats st;
	uint16_t words[SENT], got[SENT];
	size_t n;
	int fd, wfd, i, ok;
	char cmd[96];

	if (!tap_ok(sim_load(p) == 0, "[%s] load", p))
		tap_bail("cannot continue without the simulator");
	fd = tty_open(port, B115200, 0, 0);
	wfd = wire_open(port, 0);
	if (fd < 0 || wfd < 0)
		tap_bail("open port %d", port);
	for (i = 0; i < SENT; i++)
		words[i] = (uint16_t)(0x41 + i);
	ioctl(fd, TIOCGICOUNT, &ic0);
	ioctl(wfd, TS7800_SIM_RESET_STATS);
	sh("dmesg -C");
	/* N_TTY logs overruns only once a second after open. */
	usleep(1100000);

	debugfs_write(-1, "irq_hold", 1);
	wire_write_all(wfd, words, SENT);
	ok = wait_line(wfd, SENT, &st) == 0;
	tap_ok(ok && st.from_wire == 16 && st.rx_overruns == SENT - 16,
	       "[%s] with the CPU held, 16 characters fill the FIFO and %d overrun (got %llu + %llu)",
	       p, SENT - 16, (unsigned long long)st.from_wire,
	       (unsigned long long)st.rx_overruns);
	debugfs_write(-1, "irq_hold", 0);

	n = tty_read_words(fd, got, SENT, 2, NULL);
	tap_ok(n == 16 && first_diff(words, got, 16) < 0,
	       "[%s] the tty delivers exactly the 16 characters the FIFO held (got %zu)", p, n);
	ioctl(fd, TIOCGICOUNT, &ic1);
	tap_ok(ic1.overrun - ic0.overrun >= 1 && ic1.rx - ic0.rx == 16,
	       "[%s] TIOCGICOUNT: overrun +%d, rx +%d", p, ic1.overrun - ic0.overrun,
	       ic1.rx - ic0.rx);
	snprintf(cmd, sizeof(cmd), "dmesg | grep -q 'ttyTSU%d: [0-9]* input overrun'", port);
	tap_ok(sh("%s", cmd) == 0, "[%s] the line discipline saw TTY_OVERRUN (kernel log)", p);

	for (i = 0; i < SENT; i++)
		words[i] = (uint16_t)(0x61 + i % 26);
	wire_write_all(wfd, words, SENT);
	n = tty_read_words(fd, got, SENT, 3, NULL);
	tap_ok(n == SENT && first_diff(words, got, SENT) < 0,
	       "[%s] afterwards the port carries traffic without loss (%zu of %d)", p, n, SENT);
	close(fd);
	close(wfd);
	tap_ok(sim_unload() == 0, "[%s] unload", p);
}

int main(void)
{
	tap_plan(2 * 7);
	run(params[0], 2);
	run(params[1], 7);
	return tap_finish();
}
