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

/* @count characters back to back from l->t, the first with the 9th bit set. */
static void chars(struct line *l, uint8_t dir, unsigned int count)
{
	for (unsigned int i = 0; i < count; i++) {
		struct ts7800_sim_line_event *e = &l->ev[l->n++];

		memset(e, 0, sizeof(*e));
		e->char_ns = CHAR_NS;
		e->end_ns = (uint64_t)(l->t + CHAR_NS);
		e->word = i == 0 ? TS7800_SIM_WORD_BIT9 : 0;
		e->dir = dir;
		l->t += CHAR_NS;
	}
}

static void idle(struct line *l, double characters)
{
	l->t += (int64_t)(characters * CHAR_NS);
}

/* A request, then a response; returns with l->t at the response's end. */
static void transaction(struct line *l)
{
	chars(l, TS7800_SIM_LOG_TX, 6);
	idle(l, 3);
	chars(l, TS7800_SIM_LOG_RX, 6);
}

static void scan(struct line_scan *ls, struct line *l)
{
	line_scan_init(ls, -1);
	line_scan_feed(ls, l->ev, l->n);
}

int main(void)
{
	struct line_scan ls;
	struct line l;

	tap_plan(4);

	memset(&l, 0, sizeof(l));
	l.t = T0_NS;
	transaction(&l);
	idle(&l, 3);
	chars(&l, TS7800_SIM_LOG_TX, 6);
	scan(&ls, &l);
	tap_ok(ls.requests == 2 && ls.ngaps == 1 && ls.gap_ns[0] == 3 * CHAR_NS &&
	       !ls.overlaps && !ls.nexcused,
	       "a request 3 characters after a response: one gap of 3 characters, no overlap "
	       "(%u requests, %u gaps, first %lld ns, %u overlaps, %u excused)", ls.requests,
	       ls.ngaps, ls.ngaps ? (long long)ls.gap_ns[0] : -1LL, ls.overlaps, ls.nexcused);

	memset(&l, 0, sizeof(l));
	l.t = T0_NS;
	transaction(&l);
	idle(&l, 1);
	chars(&l, TS7800_SIM_LOG_TX, 6);
	scan(&ls, &l);
	tap_ok(ls.ngaps == 1 && ls.gap_ns[0] == CHAR_NS && !ls.nexcused && !ls.overlaps,
	       "a request 1 character after a whole response: a gap of 1 character, not excused "
	       "(%u gaps, first %lld ns, %u excused, %u overlaps)", ls.ngaps,
	       ls.ngaps ? (long long)ls.gap_ns[0] : -1LL, ls.nexcused, ls.overlaps);

	/*
	 * The response: 3 characters, a 30-character stall, 1 character; the
	 * request starts half-way into that character, the response's last
	 * character overlaps the request's second.
	 */
	memset(&l, 0, sizeof(l));
	l.t = T0_NS;
	chars(&l, TS7800_SIM_LOG_TX, 6);
	idle(&l, 3);
	chars(&l, TS7800_SIM_LOG_RX, 3);
	idle(&l, 30);
	chars(&l, TS7800_SIM_LOG_RX, 1);
	l.ev[l.n - 1].word = 0;
	l.t -= CHAR_NS / 2;
	chars(&l, TS7800_SIM_LOG_TX, 6);
	l.t -= 5 * CHAR_NS + CHAR_NS / 2;
	chars(&l, TS7800_SIM_LOG_RX, 1);
	l.ev[l.n - 1].word = 0;
	scan(&ls, &l);
	tap_ok(ls.requests == 2 && ls.nexcused == 1 && !ls.overlaps && !ls.ngaps,
	       "a request into the tail of a response stalled for 30 characters: excused, no "
	       "overlap counted (%u excused, %u overlaps, %u gaps)", ls.nexcused, ls.overlaps,
	       ls.ngaps);

	/* the same overlap after a response that never paused */
	memset(&l, 0, sizeof(l));
	l.t = T0_NS;
	transaction(&l);
	l.t -= CHAR_NS / 2;
	chars(&l, TS7800_SIM_LOG_TX, 6);
	scan(&ls, &l);
	tap_ok(!ls.nexcused && ls.overlaps >= 1 && ls.ngaps == 1 && ls.gap_ns[0] < 0,
	       "a request into a response that never paused: not excused, the overlap counted "
	       "(%u excused, %u overlaps, gap %lld ns)", ls.nexcused, ls.overlaps,
	       ls.ngaps ? (long long)ls.gap_ns[0] : 0LL);
	return tap_finish();
}
