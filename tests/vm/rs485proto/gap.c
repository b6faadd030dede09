// SPDX-License-Identifier: GPL-2.0
/*
 * gap - the inter-frame gap and the response timeout, measured on the wire
 * (issue 18, item 3; spec "Timing and transactions"), at 9600 and 115200 Bd.
 * The simulator's line log gives every character's end with its time:
 *
 *  - at least 2 idle characters between the end of any frame and the next
 *    request: after a good response (back-to-back transactions), after a
 *    bad-CRC response (the RESEND), and after a request that timed out
 *    sooner than 2 characters (100 us: the repeat waits the gap from the
 *    end of the request);
 *  - the response timeout runs from the end of the request: a request to a
 *    silent node is repeated no sooner than the timeout after its end; a
 *    response that started well within the timeout (the wire says when) is
 *    taken.
 *
 * The lower limits are exact (the master can only learn of a character after
 * it ended). The "well within" margin is 50 ms: the emulated CPU's interrupt
 * and flip-buffer latency, not the discipline's. Measured values are
 * reported.
 */
#include "rs485-lib.h"

#define PORT		0
#define LONG_US		300000
#define ROUNDS		10
#define TIMEOUT_US	100000	/* the measured response timeout */
#define DELAY_US	5000	/* I_DELAY: the slave answers this late */
#define MARGIN_NS	50000000LL

static struct line_scan ls;

static int set_baud(int fd, uint32_t baud)
{
	struct n_rs485_config c;

	if (ioctl(fd, N_RS485_IOC_GET_CONFIG, &c))
		return -1;
	c.baud = baud;
	return ioctl(fd, N_RS485_IOC_SET_CONFIG, &c);
}

static void at_rate(int fd, int wfd, struct slave *s, uint32_t baud)
{
	unsigned int i, bad = 0, late = 0, early = 0, taken = 0;
	int64_t min, two;
	struct n_rs485_xfer x;
	char what[96];

	if (set_baud(fd, baud))
		tap_bail("N_RS485_IOC_SET_CONFIG %u Bd", baud);

	/* after good responses and after bad-CRC responses (RESEND) */
	line_scan_start(&ls, wfd);
	for (i = 0; i < ROUNDS; i++) {
		bad += xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, "gap", 3, LONG_US, 0) ||
		       x.status != N_RS485_OK;
		bad += xfer(fd, &x, SLAVE_ADDR, I_CORRUPT, 0, NULL, 0, LONG_US, 2) ||
		       x.status != N_RS485_BADCRC || x.attempts != 3;
		line_scan_read(&ls);
	}
	two = 2 * (int64_t)ls.char_ns;
	snprintf(what, sizeof(what), "%u Bd: idle before a request after a response", baud);
	min = line_report(what, ls.gap_ns, ls.ngaps);
	/* a response the simulator stalled in is not judged (rs485-lib.h), but most are */
	tap_ok(!bad && !ls.dropped && ls.ngaps + ls.nexcused >= 3 * ROUNDS &&
	       ls.ngaps >= 2 * ROUNDS && min >= two,
	       "%u Bd: every request (RESEND included) starts >= 2 characters (%lld us) after "
	       "the response before it: min %.0f us over %u (%u failed transactions, %u excused "
	       "after a stalled response)", baud, (long long)two / 1000, min / 1e3, ls.ngaps, bad,
	       ls.nexcused);

	/* after a timeout shorter than 2 characters */
	line_scan_start(&ls, wfd);
	for (i = 0, bad = 0; i < ROUNDS; i++) {
		bad += xfer(fd, &x, SLAVE_ADDR, I_SILENT, 0, NULL, 0, 100, 2) ||
		       x.status != N_RS485_TIMEOUT || x.attempts != 3;
		line_scan_read(&ls);
	}
	snprintf(what, sizeof(what), "%u Bd: idle before a repeat after a 100 us timeout", baud);
	min = line_report(what, ls.silent_ns, ls.nsilent);
	tap_ok(!bad && !ls.dropped && ls.nsilent >= 3 * ROUNDS - 1 && min >= two,
	       "%u Bd: after a 100 us timeout the repeat still waits 2 characters (%lld us) "
	       "from the end of the request: min %.0f us over %u", baud, (long long)two / 1000,
	       min / 1e3, ls.nsilent);

	/* the response timeout: a silent node, and a node that answers in time */
	line_scan_start(&ls, wfd);
	for (i = 0, bad = 0; i < ROUNDS; i++) {
		bad += xfer(fd, &x, SLAVE_ADDR, I_SILENT, 0, NULL, 0, TIMEOUT_US, 1) ||
		       x.status != N_RS485_TIMEOUT || x.attempts != 2;
		line_scan_read(&ls);
	}
	snprintf(what, sizeof(what), "%u Bd: request end to repeat, %u us timeout", baud,
		 TIMEOUT_US);
	min = line_report(what, ls.silent_ns, ls.nsilent);
	tap_ok(!bad && !ls.dropped && ls.nsilent >= 2 * ROUNDS - 1 &&
	       min >= (int64_t)TIMEOUT_US * 1000,
	       "%u Bd: no repeat before the %u us timeout has run from the end of the request: "
	       "min %.0f us over %u", baud, TIMEOUT_US, min / 1e3, ls.nsilent);

	s->delay_us = DELAY_US;
	line_scan_start(&ls, wfd);
	for (i = 0; i < ROUNDS; i++) {
		unsigned int n0 = ls.nresp;
		int ok;

		ok = !xfer(fd, &x, SLAVE_ADDR, I_DELAY, 0, NULL, 0, TIMEOUT_US, 0) &&
		     x.status == N_RS485_OK;
		line_scan_read(&ls);
		if (ls.nresp != n0 + 1 ||
		    ls.resp_ns[n0] > (int64_t)TIMEOUT_US * 1000 - MARGIN_NS) {
			late++;		/* the slave thread itself was late: no verdict */
			continue;
		}
		taken += ok;
		early += !ok;
		if (!ok)
			tap_diag("response %.1f ms after the request not taken: status %u, attempts %u",
				 ls.resp_ns[n0] / 1e6, x.status, x.attempts);
	}
	snprintf(what, sizeof(what), "%u Bd: request end to response start", baud);
	line_report(what, ls.resp_ns, ls.nresp);
	tap_ok(!early && taken >= ROUNDS / 2,
	       "%u Bd: a response starting more than 50 ms before the %u us timeout ends is "
	       "taken (%u taken, %u lost, %u not decidable: the slave was late)", baud,
	       TIMEOUT_US, taken, early, late);
}

int main(void)
{
	struct slave s;
	int fd, wfd;

	tap_plan(9);
	fd = bus_logged_setup(PORT, &s, &wfd);

	at_rate(fd, wfd, &s, 9600);
	at_rate(fd, wfd, &s, 115200);

	tap_ok(s.bad_frames == 0, "no malformed frame on the wire (%u)", s.bad_frames);
	bus_logged_teardown(fd, wfd, &s);
	return tap_finish();
}
