// SPDX-License-Identifier: GPL-2.0
/*
 * concurrency - 8 processes share one bus for 60 s (RS485_CONCURRENCY_S
 * overrides it, e.g. for a quick run) while the slave also sends
 * unsolicited event frames (a full-duplex link): every transaction gets its
 * own response byte-exact, every event reaches read() in order and
 * byte-exact (only frames hit by a reported UART overrun may be missing) and
 * none reaches a transaction, the statistics add up (xfers = ok + failed),
 * and the processes got turns fairly.
 *
 * One exception, a limit of the protocol (no sequence numbers): a response
 * that comes after its request timed out (an emulated CPU stalled for the
 * whole 1 s timeout, seen on the debug kernel on a loaded host) and after
 * the repeat went out is taken for the repeat's, whose response is then one
 * too many: it goes to read() if it arrives before the next request goes
 * out, else the next transaction to the same node and instruction takes it
 * and its own response is the one too many, and so on. Such "late" answers
 * are allowed only after a timeout the bus counted and must each carry
 * another request of this test. Every response that reaches read() is one
 * too many of that kind, or the answer to a request that went out before
 * its transaction failed locally (N_RS485_ERROR: a transmitter that stalled
 * for the 500 ms drain limit on a loaded host): at most one per timeout or
 * failed transaction.
 */
#include "rs485-lib.h"

#define PORT		0
#define NPROC		8
#define DEFAULT_DURATION_S	30
#define EVENT_PERIOD_US	20000

#define XFER_TIMEOUT_US	1000000

struct result {
	unsigned int ok, late, wrong, failed;
	/* the last failure: ioctl errno (0: none) and status */
	int fail_errno;
	uint32_t fail_status;
};

static unsigned int duration_s = DEFAULT_DURATION_S;

/*
 * RS485_CONCURRENCY_S: seconds of hammering (1..3600), default 30 (several
 * hundred transactions on every lane); soaks ask for more.
 */
static void duration_from_env(void)
{
	const char *s = getenv("RS485_CONCURRENCY_S");
	char *end;
	unsigned long v;

	if (!s || !*s)
		return;
	v = strtoul(s, &end, 10);
	if (*end || v < 1 || v > 3600)
		tap_bail("RS485_CONCURRENCY_S=%s: want seconds, 1..3600", s);
	duration_s = v;
}

static void child(int fd, int id, int out)
{
	struct result res = { 0 };
	struct n_rs485_xfer x;
	uint8_t data[64];
	double end = now_s() + duration_s;
	uint32_t seq = 0, len;

	srand(id * 7919 + 1);
	while (now_s() < end) {
		len = 5 + rand() % 50;
		data[0] = id;
		memcpy(data + 1, &seq, 4);
		for (uint32_t i = 5; i < len; i++)
			data[i] = rand();
		seq++;
		if (xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, data, len, XFER_TIMEOUT_US, 2)) {
			res.failed++;
			res.fail_errno = errno;
			continue;
		}
		if (x.status != N_RS485_OK) {
			res.failed++;
			res.fail_errno = 0;
			res.fail_status = x.status;
			continue;
		}
		if (x.resp.addr != SLAVE_ADDR || x.resp.instr != I_ECHO ||
		    x.resp.flags != N_RS485_RESP_ACK)
			res.wrong++;
		else if (x.resp.len == len && !memcmp(x.resp.data, data, len))
			res.ok++;
		else if (x.resp.len >= 5 && x.resp.len < 55 && x.resp.data[0] < NPROC)
			res.late++;	/* the echo of another request of this test */
		else
			res.wrong++;
	}
	if (write(out, &res, sizeof(res)) != sizeof(res))
		_exit(2);
	_exit(0);
}

int main(void)
{
	struct result res[NPROC], sum = { 0 };
	struct n_rs485_stats st;
	struct event_reader rd;
	struct slave s;
	int fd, pipes[NPROC][2], i, status, exits_ok = 1;
	unsigned int min_ok = ~0u, max_ok = 0;

	duration_from_env();
	tap_plan(6);
	if (sim_load())
		tap_bail("cannot load ts_uart + ts7800_sim");
	fd = bus_open(PORT);
	if (fd < 0)
		tap_bail("attach n_rs485");
	if (slave_start_events(&s, PORT, EVENT_PERIOD_US))
		tap_bail("slave");
	if (event_reader_start(&rd, fd, UINT32_MAX, 1))
		tap_bail("reader thread");

	for (i = 0; i < NPROC; i++) {
		if (pipe(pipes[i]))
			tap_bail("pipe");
		if (!fork())
			child(fd, i, pipes[i][1]);
	}
	for (i = 0; i < NPROC; i++) {
		memset(&res[i], 0, sizeof(res[i]));
		if (read(pipes[i][0], &res[i], sizeof(res[i])) != sizeof(res[i]))
			exits_ok = 0;
	}
	while (wait(&status) > 0)
		if (!WIFEXITED(status) || WEXITSTATUS(status))
			exits_ok = 0;
	s.stop = 1;
	usleep(1000000);	/* the last event arrives (also on a slow debug kernel) */
	event_reader_stop(&rd);
	slave_stop(&s);

	for (i = 0; i < NPROC; i++) {
		sum.ok += res[i].ok;
		sum.late += res[i].late;
		sum.wrong += res[i].wrong;
		sum.failed += res[i].failed;
		min_ok = res[i].ok < min_ok ? res[i].ok : min_ok;
		max_ok = res[i].ok > max_ok ? res[i].ok : max_ok;
		tap_diag("process %d: %u ok, %u late, %u wrong, %u failed", i, res[i].ok,
			 res[i].late, res[i].wrong, res[i].failed);
		if (res[i].failed)
			tap_diag("process %d: last failure: %s %d", i,
				 res[i].fail_errno ? "errno" : "status",
				 res[i].fail_errno ? res[i].fail_errno : (int)res[i].fail_status);
	}
	get_stats(fd, &st);
	tap_diag("stats: xfers %llu ok %llu failed %llu retries %llu timeouts %llu crc %llu truncated %llu noise %llu overruns %llu framing %llu events %llu dropped %llu",
		 (unsigned long long)st.xfers, (unsigned long long)st.xfers_ok,
		 (unsigned long long)st.xfers_failed, (unsigned long long)st.retries,
		 (unsigned long long)st.timeouts, (unsigned long long)st.rx_crc_errors,
		 (unsigned long long)st.rx_truncated, (unsigned long long)st.rx_noise,
		 (unsigned long long)st.rx_overruns, (unsigned long long)st.rx_framing,
		 (unsigned long long)st.events, (unsigned long long)st.events_dropped);
	tap_ok(exits_ok && sum.ok > 0 && sum.wrong == 0 && sum.failed == 0 &&
	       (sum.late == 0 || st.timeouts > 0),
	       "%d processes, %u transactions in %u s: every one answered correctly (%u wrong, %u failed; %u late answers after %llu timeouts)",
	       NPROC, sum.ok + sum.late, duration_s, sum.wrong, sum.failed, sum.late,
	       (unsigned long long)st.timeouts);
	tap_ok(st.xfers == st.xfers_ok + st.xfers_failed && st.xfers_ok == sum.ok + sum.late,
	       "counters add up: xfers %llu = ok %llu + failed %llu",
	       (unsigned long long)st.xfers, (unsigned long long)st.xfers_ok,
	       (unsigned long long)st.xfers_failed);
	tap_ok(min_ok * 2 >= max_ok, "fair turns: fewest %u, most %u transactions per process",
	       min_ok, max_ok);
	tap_ok(rd.non_event <= st.timeouts + st.xfers_failed,
	       "no response went to read() but one per timeout or failed transaction at most (%u, %llu timeouts, %llu failed, %u late)",
	       rd.non_event, (unsigned long long)st.timeouts,
	       (unsigned long long)st.xfers_failed, sum.late);
	tap_ok(rd.other == 0, "events arrive in order and byte-exact (%u wrong)", rd.other);
	/*
	 * An overrun (the emulated CPU did not serve the 16-deep FIFO in time)
	 * loses characters: the frame they belonged to, and the next one if its
	 * address character was among them. Nothing else may lose an event.
	 */
	tap_ok(rd.got <= s.events_sent && s.events_sent - rd.got <= 2 * st.rx_overruns,
	       "every event reached read() but those hit by overruns: %u of %u (%llu overruns)",
	       rd.got, s.events_sent, (unsigned long long)st.rx_overruns);
	close(fd);
	sim_unload();
	return tap_finish();
}
