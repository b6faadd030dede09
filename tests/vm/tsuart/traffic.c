// SPDX-License-Identifier: GPL-2.0
/*
 * traffic - 8-bit and 9-bit traffic both ways at every supported rate, on the
 * simulated FPGA with level and edge interrupts and with FIFO depths 16 and 1.
 *
 * Transmit: bytes written to /dev/ttyTSUn must appear on the wire byte-exact;
 * in 9-bit mode (PARENB|CMSPAR) the 9th bit must be PARODD (an address byte in
 * mark, then data in space, as the RS-485 protocol sends frames).
 * Receive: words written to the wire must reach the tty byte-exact; in 9-bit
 * mode (space parity, INPCK|PARMRK) exactly the words with the 9th bit set
 * arrive flagged as parity errors.
 * With FIFO depth 1 the receiver has one character time to be served, which
 * an emulated CPU cannot promise: there every character must arrive or be
 * reported lost as an overrun (in order, none altered, none silently lost).
 * The same rule holds at FIFO depth 16 when the handler is threaded
 * (PREEMPT_RT): an emulated CPU cannot promise that a thread runs within 16
 * character times (1.4 ms at 115200 Bd) either; the losses are reported.
 * Timing: with FIFO depth 16, carrying N characters must take
 * N x bits-per-char / rate within 2 %, measured both by the simulator's line
 * clock and by this program's wall clock.
 */
#include "tsuart-lib.h"

#define SECONDS_PER_TRANSFER	0.6
#define MAX_CHARS		8192
#define TOLERANCE		0.02

struct config {
	const char *params;
	const char *name;
	int timed;
};

static const struct config configs[] = {
	{ "fifo_depth=16", "level irq, FIFO 16", 1 },
	{ "fifo_depth=16 edge_irq=1", "edge irq, FIFO 16", 1 },
	{ "fifo_depth=1", "level irq, FIFO 1", 0 },
	{ "fifo_depth=1 edge_irq=1 oerr_clear_on_data=1", "edge irq, FIFO 1", 0 },
};

#define NCONFIGS (sizeof(configs) / sizeof(configs[0]))
#define NRATES (sizeof(rates) / sizeof(rates[0]))

static uint32_t rng = 0x12345678;

static uint32_t rnd(void)
{
	rng ^= rng << 13;
	rng ^= rng >> 17;
	rng ^= rng << 5;
	return rng;
}

/*
 * A timed transfer lasts SECONDS_PER_TRANSFER so that 2 % of it is well
 * above the guest's timer jitter; an untimed one (FIFO depth 1: every
 * character there or reported lost) needs no length of its own: a fifth
 * of that (26 characters at 2400 Bd to 1382 at 115200 Bd) still gives the
 * receiver hundreds of chances at the fast rates to miss its one character
 * time, where overruns happen (they were half of this program's wire time).
 */
static size_t chars_for(const struct config *c, unsigned int baud, unsigned int bits)
{
	size_t n = (size_t)(baud / bits * SECONDS_PER_TRANSFER / (c->timed ? 1 : 5));

	return n > MAX_CHARS ? MAX_CHARS : n;
}

/*
 * The line time is the simulator's own clock from the first start bit to the
 * last stop bit, less the time it stood still because the simulator itself
 * was not running (a stalled virtual CPU under TCG, see ts7800_sim.h). The
 * wall clock of this program is reported for comparison.
 */
static void check_time(const struct config *c, const char *what, double span_s,
		       double stall_s, double wall_s, double expect_s)
{
	double line_s = span_s - stall_s;
	double le = line_s / expect_s - 1, we = wall_s / expect_s - 1;

	tap_diag("%s: expected %.4f s, line %.4f s (%+.2f %%; stalls %.4f s), wall %.4f s (%+.2f %%)",
		 what, expect_s, line_s, le * 100, stall_s, wall_s, we * 100);
	if (!c->timed)
		return;
	tap_ok(le > -TOLERANCE && le < TOLERANCE,
	       "%s: line time within 2 %% of N x bits / rate", what);
}

static void tx_test(const struct config *c, int port, const struct rate *r, int nine)
{
	static uint16_t expect[MAX_CHARS + 1], got[MAX_CHARS + 1];
	static uint8_t bytes[MAX_CHARS + 1];
	unsigned int bits = nine ? 11 : 10;
	size_t n = chars_for(c, r->baud, bits), total = n + !!nine, i;
	struct ts7800_sim_wire_stats st;
	struct collector col;
	struct termios t;
	char what[96];
	double t0 = 0;
	int fd, wfd, ok;

	snprintf(what, sizeof(what), "%s: port %d TX %s %u Bd, %zu chars", c->name, port,
		 nine ? "9-bit" : "8-bit", r->baud, n);
	fd = tty_open(port, r->speed, nine ? PARENB | CMSPAR | PARODD : 0, 0);
	wfd = wire_open(port, 0);
	if (fd < 0 || wfd < 0) {
		tap_ok(0, "%s: open tty and wire", what);
		if (c->timed)
			tap_ok(0, "%s: timing", what);
		goto out;
	}
	for (i = 0; i < total; i++) {
		bytes[i] = rnd();
		expect[i] = bytes[i];
	}
	if (nine)
		expect[0] |= TS7800_SIM_WORD_BIT9;	/* address byte in mark */

	collector_start(&col, wfd, 1, got, total, 3);
	if (nine) {
		tty_write_all(fd, bytes, 1);
		tcdrain(fd);
		tcgetattr(fd, &t);
		t.c_cflag &= ~PARODD;			/* data bytes in space */
		tcsetattr(fd, TCSANOW, &t);
	}
	ioctl(wfd, TS7800_SIM_RESET_STATS);
	t0 = now_s();
	tty_write_all(fd, bytes + !!nine, n);
	collector_join(&col);
	wire_stats(wfd, &st);

	ok = col.got == total && first_diff(expect, got, total) < 0;
	if (!ok && col.got)
		tap_diag("got %zu of %zu words, first difference at %ld", col.got, total,
			 first_diff(expect, got, col.got));
	tap_ok(ok, "%s: wire shows every character byte-exact%s", what,
	       nine ? " with the 9th bit = PARODD" : "");
	check_time(c, what, (st.to_wire_last_ns - st.to_wire_first_ns) / 1e9,
		   st.to_wire_stall_ns / 1e9, col.t_last - t0, (double)n * bits / r->baud);
out:
	if (fd >= 0)
		close(fd);
	if (wfd >= 0)
		close(wfd);
}

static void rx_test(const struct config *c, int port, const struct rate *r, int nine)
{
	struct serial_icounter_struct ic0, ic1;
	static uint16_t words[MAX_CHARS], got[MAX_CHARS];
	unsigned int bits = nine ? 11 : 10;
	size_t n = chars_for(c, r->baud, bits), i, flagged = 0;
	struct ts7800_sim_wire_stats st;
	struct collector col;
	char what[96];
	int fd, wfd, ok, threaded;
	double t0;

	snprintf(what, sizeof(what), "%s: port %d RX %s %u Bd, %zu chars", c->name, port,
		 nine ? "9-bit" : "8-bit", r->baud, n);
	fd = tty_open(port, r->speed, nine ? PARENB | CMSPAR : 0, 0);
	wfd = wire_open(port, 0);
	if (fd < 0 || wfd < 0) {
		tap_ok(0, "%s: open tty and wire", what);
		if (c->timed)
			tap_ok(0, "%s: timing", what);
		goto out;
	}
	threaded = tty_irq_thread(fd) > 0;
	for (i = 0; i < n; i++) {
		words[i] = rnd() & 0xff;
		if (nine && !(rnd() % 8)) {
			words[i] |= TS7800_SIM_WORD_BIT9;
			flagged++;
		}
	}
	ioctl(wfd, TS7800_SIM_RESET_STATS);
	ioctl(fd, TIOCGICOUNT, &ic0);
	collector_start(&col, fd, 0, got, n, 3);
	t0 = now_s();
	wire_write_all(wfd, words, n);
	collector_join(&col);
	wire_stats(wfd, &st);
	ioctl(fd, TIOCGICOUNT, &ic1);

	ok = col.got == n && first_diff(words, got, n) < 0;
	if (!ok && col.got)
		tap_diag("got %zu of %zu characters, first difference at %ld", col.got, n,
			 first_diff(words, got, col.got));
	if (!c->timed || threaded) {
		/* Losses allowed, but only as reported overruns. */
		ok = is_subsequence(got, col.got, words, n) &&
		     n - col.got == st.rx_overruns &&
		     (col.got == n || ic1.overrun > ic0.overrun);
		tap_ok(ok, "%s: %zu delivered in order and unaltered, %llu lost, all reported (overrun +%d)",
		       what, col.got, (unsigned long long)st.rx_overruns,
		       ic1.overrun - ic0.overrun);
	} else if (nine)
		tap_ok(ok, "%s: tty gets every character, exactly the %zu with 9th bit set flagged",
		       what, flagged);
	else
		tap_ok(ok, "%s: tty gets every character byte-exact", what);
	check_time(c, what, (st.from_wire_last_ns - st.from_wire_first_ns) / 1e9,
		   st.from_wire_stall_ns / 1e9, col.t_last - t0, (double)n * bits / r->baud);
out:
	if (fd >= 0)
		close(fd);
	if (wfd >= 0)
		close(wfd);
}

int main(void)
{
	unsigned int ci, ri, plan = 0;
	int nine;

	for (ci = 0; ci < NCONFIGS; ci++)
		plan += 2 + NRATES * 4 * (1 + configs[ci].timed);
	tap_plan(plan);

	for (ci = 0; ci < NCONFIGS; ci++) {
		const struct config *c = &configs[ci];

		if (!tap_ok(sim_load(c->params) == 0, "%s: load ts_uart and ts7800_sim %s",
			    c->name, c->params))
			tap_bail("cannot continue without the simulator");
		for (ri = 0; ri < NRATES; ri++) {
			for (nine = 0; nine < 2; nine++) {
				tx_test(c, (ri + ci) % NPORTS, &rates[ri], nine);
				rx_test(c, (ri + ci + 5) % NPORTS, &rates[ri], nine);
			}
		}
		tap_ok(sim_unload() == 0, "%s: unload", c->name);
	}
	return tap_finish();
}
