// SPDX-License-Identifier: GPL-2.0
/*
 * scan - the line scan of rs485-lib.h (what gap and resend judge the
 * discipline's timing with) on made-up lines whose verdict is known:
 *
 *  - a request 3 characters after a response: one gap, no overlap;
 *  - a request 1 character after a whole response: an early request the
 *    gap check must see (not excused);
 *  - a response the simulator stalled in the middle of, the master's next
 *    request (after its timeout) overlapping the response's tail: excused,
 *    and nothing of it counted as an overlap. On the code before 2aca023
 *    the request's own address character was counted as an overlap of the
 *    run: the failure resend point 18 showed under load ("1 characters
 *    overlapped" next to the request it had excused);
 *  - a request that overlaps a response that never paused: counted.
 *
 * No module and no wire: the events are fed to line_scan_feed() directly.
 */
#include "rs485-lib.h"

#define CHAR_NS		95486	/* 11 bits at 115200 Bd */
#define T0_NS		1000000000LL

struct line {
	struct ts7800_sim_line_event ev[64];
	unsigned int n;
	int64_t t;		/* where the next character starts */
};

/*
 * @count characters back to back from l->t; a frame's first one (@frame_start)
 * carries the 9th bit, which is what makes a transmitted character a request.
 */
static void chars(struct line *l, uint8_t dir, unsigned int count, int frame_start)
{
	for (unsigned int i = 0; i < count; i++) {
		struct ts7800_sim_line_event *e = &l->ev[l->n++];

		memset(e, 0, sizeof(*e));
		e->char_ns = CHAR_NS;
		e->end_ns = (uint64_t)(l->t + CHAR_NS);
		e->word = frame_start && i == 0 ? TS7800_SIM_WORD_BIT9 : 0;
		e->dir = dir;
		l->t += CHAR_NS;
	}
}

/* Moves the start of the next character by @characters (negative: overlap). */
static void idle(struct line *l, double characters)
{
	l->t += (int64_t)(characters * CHAR_NS);
}

static void line_begin(struct line *l)
{
	memset(l, 0, sizeof(*l));
	l->t = T0_NS;
	chars(l, TS7800_SIM_LOG_TX, 6, 1);	/* the first request */
	idle(l, 3);
}

/* A whole response, then the next request @after characters after its end. */
static void scan_request_after(struct line_scan *ls, double after)
{
	struct line l;

	line_begin(&l);
	chars(&l, TS7800_SIM_LOG_RX, 6, 1);
	idle(&l, after);
	chars(&l, TS7800_SIM_LOG_TX, 6, 1);
	line_scan_init(ls, -1);
	line_scan_feed(ls, l.ev, l.n);
}

int main(void)
{
	struct line_scan ls;
	struct line l;

	tap_plan(4);

	scan_request_after(&ls, 3);
	tap_ok(ls.requests == 2 && ls.ngaps == 1 && ls.gap_ns[0] == 3 * CHAR_NS &&
	       !ls.overlaps && !ls.nexcused,
	       "a request 3 characters after a response: one gap of 3 characters, no overlap "
	       "(%u requests, %u gaps, first %lld ns, %u overlaps, %u excused)", ls.requests,
	       ls.ngaps, ls.ngaps ? (long long)ls.gap_ns[0] : -1LL, ls.overlaps, ls.nexcused);

	scan_request_after(&ls, 1);
	tap_ok(ls.ngaps == 1 && ls.gap_ns[0] == CHAR_NS && !ls.nexcused && !ls.overlaps,
	       "a request 1 character after a whole response: a gap of 1 character, not excused "
	       "(%u gaps, first %lld ns, %u excused, %u overlaps)", ls.ngaps,
	       ls.ngaps ? (long long)ls.gap_ns[0] : -1LL, ls.nexcused, ls.overlaps);

	/*
	 * The response: 3 characters, a 30-character stall, 1 character; the
	 * request starts half-way into that character, the response's last
	 * character overlaps the request's second.
	 */
	line_begin(&l);
	chars(&l, TS7800_SIM_LOG_RX, 3, 1);
	idle(&l, 30);
	chars(&l, TS7800_SIM_LOG_RX, 1, 0);
	idle(&l, -0.5);
	chars(&l, TS7800_SIM_LOG_TX, 6, 1);
	idle(&l, -5.5);
	chars(&l, TS7800_SIM_LOG_RX, 1, 0);
	line_scan_init(&ls, -1);
	line_scan_feed(&ls, l.ev, l.n);
	tap_ok(ls.requests == 2 && ls.nexcused == 1 && !ls.overlaps && !ls.ngaps,
	       "a request into the tail of a response stalled for 30 characters: excused, no "
	       "overlap counted (%u excused, %u overlaps, %u gaps)", ls.nexcused, ls.overlaps,
	       ls.ngaps);

	scan_request_after(&ls, -0.5);
	tap_ok(!ls.nexcused && ls.overlaps >= 1 && ls.ngaps == 1 && ls.gap_ns[0] < 0,
	       "a request into a response that never paused: not excused, the overlap counted "
	       "(%u excused, %u overlaps, gap %lld ns)", ls.nexcused, ls.overlaps,
	       ls.ngaps ? (long long)ls.gap_ns[0] : 0LL);
	return tap_finish();
}
