// SPDX-License-Identifier: GPL-2.0
/*
 * allports - regression test for the vendor driver's lost 9-bit data.
 *
 * The vendor driver had a closed 8-bit twin read DATA first and drop the
 * character. Here all ten ports receive full-rate (115200 Bd) traffic at once
 * while only half of them are open; the open ones also transmit. Every open
 * port must deliver exactly its own wire's characters (byte-exact, 9th bit as
 * TTY_PARITY in space parity, or plain bytes in 8-bit mode), its wire must
 * show exactly what was written to it with the 9th bit = PARODD, and nothing
 * of the closed ports may appear anywhere - also not after they are opened
 * in the second round.
 *
 * The test is about routing, not about how fast an emulated CPU answers
 * interrupts: with ten ports at full rate under TCG on a shared host a
 * virtual CPU can be descheduled for milliseconds while it holds a port's
 * interrupt, so the FIFOs are 64 deep here (any loss would still be an
 * overrun and fail the test). When the handler is threaded (PREEMPT_RT),
 * ten ports' interrupt threads on one emulated CPU with the debug kernel's
 * checks cannot promise that much either: there characters may be lost, but
 * only as overruns the simulator counted on that very port, and what arrives
 * must be the port's own characters in order and unaltered (tsuart/traffic
 * has the same rule), so a character routed to the wrong port still fails.
 */
#include "tsuart-lib.h"

#define K 3000			/* characters per port and direction, ~0.3 s */
/* How long a closed port's line may take to carry its K characters. */
#define CLOSED_LINE_S	10.0

struct port_run {
	int open;
	int nine;		/* 9-bit (CMSPAR) or 8-bit mode */
	int mark;		/* 9-bit TX: PARODD */
	int fd, wfd;
	uint16_t rx_sent[K], rx_got[K];
	uint16_t tx_expect[K], tx_got[K];
	uint8_t tx_bytes[K];
	struct collector rx_col, tx_col;
};

static struct port_run runs[NPORTS];
static uint32_t rng = 0xc0ffee;

static uint32_t rnd(void)
{
	rng ^= rng << 13;
	rng ^= rng >> 17;
	rng ^= rng << 5;
	return rng;
}

static void round_run(int open_parity)
{
	double timeout = 3;	/* without progress */
	struct ts7800_sim_wire_stats st;
	int p, i, wires_ok = 1;
	double end;

	for (p = 0; p < NPORTS; p++) {
		struct port_run *r = &runs[p];

		memset(r, 0, sizeof(*r));
		r->open = (p % 2) == open_parity;
		r->nine = p % 4 != 1;		/* ports 1, 5 and 9 run 8-bit */
		r->mark = (p / 2) % 2;
		r->fd = -1;
		r->wfd = wire_open(p, 0);
		if (r->wfd < 0)
			wires_ok = 0;
		else
			ioctl(r->wfd, TS7800_SIM_RESET_STATS);
		for (i = 0; i < K; i++) {
			r->rx_sent[i] = rnd() & 0xff;
			if (r->nine && !(rnd() % 4))
				r->rx_sent[i] |= TS7800_SIM_WORD_BIT9;
			r->tx_bytes[i] = rnd();
			r->tx_expect[i] = r->tx_bytes[i] |
					  (r->nine && r->mark ? TS7800_SIM_WORD_BIT9 : 0);
		}
		if (!r->open)
			continue;
		r->fd = tty_open(p, B115200,
				 r->nine ? PARENB | CMSPAR | (r->mark ? PARODD : 0) : 0, 0);
	}
	if (!tap_ok(wires_ok, "round %d: all ten wires open", open_parity))
		return;

	for (p = 0; p < NPORTS; p++) {
		struct port_run *r = &runs[p];

		if (r->open && r->fd >= 0) {
			/*
			 * In 9-bit mark mode the tty's own sticky bit is 1, so
			 * received words are flagged when their 9th bit is 0.
			 */
			collector_start(&r->rx_col, r->fd, 0, r->rx_got, K, timeout);
			collector_start(&r->tx_col, r->wfd, 1, r->tx_got, K, timeout);
		}
	}
	for (p = 0; p < NPORTS; p++)
		wire_write_all(runs[p].wfd, runs[p].rx_sent, K);
	for (p = 0; p < NPORTS; p++)
		if (runs[p].open && runs[p].fd >= 0)
			tty_write_all(runs[p].fd, runs[p].tx_bytes, K);

	for (p = 0; p < NPORTS; p++) {
		struct port_run *r = &runs[p];
		uint16_t expect[K];
		long d;

		if (!r->open)
			continue;
		if (r->fd < 0) {
			tap_ok(0, "round %d: port %d opens", open_parity, p);
			tap_ok(0, "round %d: port %d transmits", open_parity, p);
			continue;
		}
		collector_join(&r->rx_col);
		collector_join(&r->tx_col);
		wire_stats(r->wfd, &st);
		for (i = 0; i < K; i++) {
			expect[i] = r->rx_sent[i];
			if (r->nine && r->mark)
				expect[i] ^= TS7800_SIM_WORD_BIT9;	/* flag = differs from mark */
		}
		d = first_diff(expect, r->rx_got, K);
		if (r->rx_col.got != K || d >= 0)
			tap_diag("port %d: received %zu of %d, first difference at %ld, %llu overruns",
				 p, r->rx_col.got, K, d, (unsigned long long)st.rx_overruns);
		if (tty_irq_thread(r->fd) > 0)
			tap_ok(is_subsequence(r->rx_got, r->rx_col.got, expect, K) &&
			       K - r->rx_col.got == st.rx_overruns,
			       "round %d: open port %d (%s, threaded handler) receives its own %d characters in order%s, %zu delivered, the %llu lost all overruns",
			       open_parity, p,
			       r->nine ? (r->mark ? "9-bit mark" : "9-bit space") : "8-bit",
			       K, r->nine ? ", 9th bit as parity flag" : "", r->rx_col.got,
			       (unsigned long long)(K - r->rx_col.got));
		else
			tap_ok(r->rx_col.got == K && d < 0,
			       "round %d: open port %d (%s) receives exactly its own %d characters%s",
			       open_parity, p,
			       r->nine ? (r->mark ? "9-bit mark" : "9-bit space") : "8-bit",
			       K, r->nine ? ", 9th bit as parity flag" : "");
		d = first_diff(r->tx_expect, r->tx_got, K);
		tap_ok(r->tx_col.got == K && d < 0,
		       "round %d: port %d's wire shows its %d transmitted characters%s",
		       open_parity, p, K, r->nine ? " with the 9th bit = PARODD" : "");
	}

	for (p = 0; p < NPORTS; p++) {
		struct port_run *r = &runs[p];

		if (r->open)
			continue;
		/*
		 * Its line carries K characters (0.29 s at 115200 Bd, behind
		 * the other ports' when the simulator ran late): wait until
		 * all of them have reached the UART or were counted overrun,
		 * with a deadline, then look at its counters.
		 */
		for (end = now_s() + CLOSED_LINE_S; ; usleep(10000)) {
			wire_stats(r->wfd, &st);
			if (st.from_wire + st.rx_overruns >= K || now_s() > end)
				break;
		}
		tap_ok(st.to_wire == 0 && st.from_wire + st.rx_overruns == K &&
		       st.from_wire <= st.fifo_depth,
		       "round %d: closed port %d: transmits nothing, its %d characters end in its own FIFO (%llu) or overrun (%llu)",
		       open_parity, p, K, (unsigned long long)st.from_wire,
		       (unsigned long long)st.rx_overruns);
	}
	for (p = 0; p < NPORTS; p++) {
		if (runs[p].fd >= 0)
			close(runs[p].fd);
		close(runs[p].wfd);
	}
}

int main(void)
{
	/* per round: wires + 5 open x 2 + 5 closed */
	tap_plan(2 + 2 * (1 + 5 * 2 + 5));

	if (!tap_ok(sim_load("fifo_depth=64") == 0, "load ts_uart and ts7800_sim fifo_depth=64"))
		tap_bail("cannot continue without the simulator");
	round_run(0);	/* even ports open */
	round_run(1);	/* odd ports open: their stale FIFO data must not show */
	tap_ok(sim_unload() == 0, "unload");
	return tap_finish();
}
