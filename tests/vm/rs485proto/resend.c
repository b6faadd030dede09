// SPDX-License-Identifier: GPL-2.0
/*
 * resend - a response that starts but is cut short is followed by RESEND,
 * never by a fresh request (issue 18, item 2; spec "Timing and
 * transactions"): once the node's address character has arrived the node
 * has executed the request. The slave cuts its first answer short after 6
 * characters by silence, by another node's address character, by a break,
 * or by an overrun of the UART's RX FIFO (the simulated CPU ignores
 * interrupts meanwhile); the retry must be a RESEND, the instruction runs
 * once. RESEND, once set, stays set for later retries (also after a timeout
 * of the RESEND). A whole frame of the node that is not the response (an
 * event) does not count as its start: the retry is then a plain repeat.
 * The last attempt's cut response ends as N_RS485_BADCRC.
 * Every request, retries included, follows the previous frame after at
 * least 2 idle characters and overlaps no received character (line log of
 * the wire): also when the rest of an overrun response is still on the line
 * (the long answer of I_CUT_OVERRUN).
 * An overrun that cuts an event frame of the node while its whole answer
 * follows in the same FIFO (I_EVENT_OVERRUN): the answer is taken, nothing
 * is sent again, and no response goes to read(), here or in any case above.
 */
#include "rs485-lib.h"

#define PORT		0
#define LONG_US		300000

static struct line_scan ls;

/*
 * The overrun cuts an event frame of the node during the transaction, and
 * its whole answer follows (as in the concurrency test under load): the
 * cut frame made the transaction "corrupt", but the answer that came whole
 * is its answer. No RESEND, no response in read(), and the next
 * transaction (while the second event's cut frame is still open) gets its
 * own answer in one attempt.
 */
static void event_overrun_case(int fd, struct slave *s)
{
	unsigned int e0 = s->executions[I_EVENT_OVERRUN], r0 = s->resends, responses;
	uint8_t data[5] = { 1, 2, 3, 4, 5 };
	struct n_rs485_stats st0, st1;
	struct n_rs485_xfer x, y;
	int ret, ret2;

	if (get_stats(fd, &st0))
		tap_bail("N_RS485_IOC_GET_STATS");
	ret = xfer(fd, &x, SLAVE_ADDR, I_EVENT_OVERRUN, 0, NULL, 0, LONG_US, 2);
	if (get_stats(fd, &st1))
		tap_bail("N_RS485_IOC_GET_STATS");
	ret2 = xfer(fd, &y, SLAVE_ADDR, I_ECHO, 0, data, sizeof(data), LONG_US, 2);
	line_scan_read(&ls);
	read_queue_drain(fd, &responses);
	tap_diag("event cut by an overrun: overruns +%llu, truncated +%llu, noise +%llu",
		 (unsigned long long)(st1.rx_overruns - st0.rx_overruns),
		 (unsigned long long)(st1.rx_truncated - st0.rx_truncated),
		 (unsigned long long)(st1.rx_noise - st0.rx_noise));
	tap_ok(ret == 0 && x.status == N_RS485_OK && x.resp.flags == N_RS485_RESP_ACK &&
	       x.resp.len == 0 && st1.rx_overruns > st0.rx_overruns &&
	       st1.rx_truncated > st0.rx_truncated && x.attempts == 1 &&
	       s->executions[I_EVENT_OVERRUN] - e0 == 1 && s->resends == r0,
	       "an overrun cuts an event frame of the node, its answer follows whole: taken "
	       "(status %u, attempts %u, executed %u time(s), %u RESEND(s))", x.status,
	       x.attempts, s->executions[I_EVENT_OVERRUN] - e0, s->resends - r0);
	tap_ok(ret2 == 0 && y.status == N_RS485_OK && y.attempts == 1 &&
	       y.resp.len == sizeof(data) && !memcmp(y.resp.data, data, sizeof(data)),
	       "...the next transaction gets its own answer (status %u, attempts %u)",
	       y.status, y.attempts);
	tap_ok(responses == 0, "...and no response went to read() (%u)", responses);
}

/* One cut-short case: status, attempts, executions and RESENDs as expected. */
static void cut_case(int fd, struct slave *s, uint8_t instr, const char *how, uint32_t retries,
		     unsigned int mute, uint32_t want_status, uint32_t want_attempts)
{
	unsigned int e0 = s->executions[instr], r0 = s->resends, g0 = ls.ngaps, i;
	struct n_rs485_stats st0, st1;
	struct n_rs485_xfer x;
	int ret;

	s->mute_resends = mute;
	if (get_stats(fd, &st0))
		tap_bail("N_RS485_IOC_GET_STATS");
	ret = xfer(fd, &x, SLAVE_ADDR, instr, 0, NULL, 0, LONG_US, retries);
	line_scan_read(&ls);
	if (get_stats(fd, &st1))
		tap_bail("N_RS485_IOC_GET_STATS");
	for (i = g0; i < ls.ngaps; i++)
		tap_diag("cut by %s: its request %u follows a response after %.0f us idle", how,
			 i - g0 + 1, ls.gap_ns[i] / 1e3);
	/* The cut itself, as the discipline saw it. */
	if (instr == I_CUT_BREAK && st1.rx_framing == st0.rx_framing)
		tap_diag("the break did not reach the discipline as a break");
	if (instr == I_CUT_OVERRUN && st1.rx_overruns == st0.rx_overruns)
		tap_diag("the overrun did not reach the discipline");
	tap_ok(ret == 0 && x.status == want_status && x.attempts == want_attempts &&
	       (instr != I_CUT_BREAK || st1.rx_framing > st0.rx_framing) &&
	       (instr != I_CUT_OVERRUN || st1.rx_overruns > st0.rx_overruns) &&
	       s->executions[instr] - e0 == 1 && s->resends - r0 == want_attempts - 1,
	       "cut by %s%s: status %u (want %u), attempts %u (want %u), executed %u time(s), "
	       "%u RESEND(s)", how, mute ? " + RESEND unanswered" : "", x.status, want_status,
	       x.attempts, want_attempts, s->executions[instr] - e0, s->resends - r0);
	if (want_status == N_RS485_OK)
		tap_ok(ret == 0 && x.status == N_RS485_OK &&
		       x.resp.len == (instr == I_CUT_OVERRUN ? OVERRUN_DATA : CUT_DATA) &&
		       x.resp.data[0] == instr, "...and the RESEND's answer is the whole response");
	s->mute_resends = 0;
}

int main(void)
{
	struct n_rs485_stats st;
	struct slave s;
	int fd, wfd;
	int64_t min;

	tap_plan(21);
	fd = bus_logged_setup(PORT, &s, &wfd);
	line_scan_start(&ls, wfd);

	cut_case(fd, &s, I_CUT_SILENT, "silence", 2, 0, N_RS485_OK, 2);
	cut_case(fd, &s, I_CUT_ADDR, "an address character", 2, 0, N_RS485_OK, 2);
	cut_case(fd, &s, I_CUT_BREAK, "a break", 2, 0, N_RS485_OK, 2);
	cut_case(fd, &s, I_CUT_OVERRUN, "an RX FIFO overrun", 2, 0, N_RS485_OK, 2);
	event_overrun_case(fd, &s);
	tap_ok(s.overrun_missed == 0, "the overruns happened (UART reported them in time: %u missed)",
	       s.overrun_missed);
	/* sticky RESEND: cut, the RESEND times out, the next retry is a RESEND again */
	cut_case(fd, &s, I_CUT_ADDR, "an address character", 2, 1, N_RS485_OK, 3);
	cut_case(fd, &s, I_CUT_SILENT, "silence", 2, 2, N_RS485_TIMEOUT, 3);
	/* an event frame of the node is not its response: after it, a plain repeat */
	{
		unsigned int e0 = s.executions[I_EVENT_SILENT], r0 = s.resends;
		struct n_rs485_xfer x;
		int ret;

		ret = xfer(fd, &x, SLAVE_ADDR, I_EVENT_SILENT, 0, NULL, 0, LONG_US, 2);
		line_scan_read(&ls);
		tap_ok(ret == 0 && x.status == N_RS485_OK && x.attempts == 2 &&
		       s.executions[I_EVENT_SILENT] - e0 == 2 && s.resends == r0,
		       "an event frame of the node, then no answer: the retry repeats the request "
		       "(status %u, attempts %u, executed %u times, %u RESENDs)", x.status,
		       x.attempts, s.executions[I_EVENT_SILENT] - e0, s.resends - r0);
	}
	/* no retry left: the cut response is the outcome */
	cut_case(fd, &s, I_CUT_BREAK, "a break", 0, 0, N_RS485_BADCRC, 1);

	line_scan_read(&ls);
	min = line_report("idle before a request after a response", ls.gap_ns, ls.ngaps);
	line_report("idle before a request after a request", ls.silent_ns, ls.nsilent);
	line_report("idle before a request after a response the simulator stalled in (excused)",
		    ls.excused_ns, ls.nexcused);
	tap_ok(ls.dropped == 0 && ls.ngaps >= 10 && min >= 2 * (int64_t)ls.char_ns &&
	       !ls.overlaps,
	       "every request after a response starts >= 2 characters (%u ns) after it "
	       "(min %lld ns, %u gaps, %u characters overlapped the other direction, "
	       "%u log events dropped; %u excused after a stalled response)", 2 * ls.char_ns,
	       (long long)min, ls.ngaps, ls.overlaps, ls.dropped, ls.nexcused);
	if (get_stats(fd, &st))
		tap_bail("N_RS485_IOC_GET_STATS");
	tap_ok(st.xfers == st.xfers_ok + st.xfers_failed,
	       "statistics add up (xfers %llu, truncated %llu, overruns %llu, framing %llu)",
	       (unsigned long long)st.xfers, (unsigned long long)st.rx_truncated,
	       (unsigned long long)st.rx_overruns, (unsigned long long)st.rx_framing);
	tap_ok(s.bad_frames == 0, "no malformed frame on the wire (%u)", s.bad_frames);
	{
		unsigned int responses, frames = read_queue_drain(fd, &responses);

		tap_ok(responses == 0, "no response of any case went to read() (%u of %u frames)",
		       responses, frames);
	}
	bus_logged_teardown(fd, wfd, &s);
	return tap_finish();
}
