// SPDX-License-Identifier: GPL-2.0
/*
 * bench - back-to-back transactions on the simulated bus at 115200 Bd with
 * a slave (a thread on the wire) that answers 200 us after a request ended:
 *
 *   a. through n_rs485 (N_RS485_IOC_XFER) on its addressing path (ADDRB),
 *   b. through n_rs485 on its mark/space path (module parameter addrb=0),
 *   c. through N_TTY with the seed's design: a user-space state machine that
 *      switches mark/space with tcsetattr(TCSADRAIN) and decodes PARMRK,
 *
 * each for SECONDS. Printed for each: transactions/s, the fraction of the
 * wire limit (characters x 11 / rate + turnaround per transaction), the
 * idle line per transaction from the simulator (TS7800_SIM_GET_GAPS) split
 * into what the protocol imposes (the inter-frame gap before the request and
 * the slave's turnaround), the idle line inside the request (what a design
 * adds between address and data) and the rest (the emulated CPU), termios
 * switches and drains per frame (n_rs485's counters; the seed design's own
 * tcsetattr(TCSADRAIN) calls), the guest's CPU time per transaction
 * (/proc/stat, both vCPUs, everything but idle) and latency percentiles;
 * and the ratios of the rates measured in this one run. Under TCG the
 * emulated CPU is far slower than the TS-7800's line, so the fractions say
 * more about the emulator than the design; the ratios and the idle-line
 * split are the meaningful numbers. A benchmark: make bench runs it.
 */
#include "rs485-lib.h"

#define PORT		0
#define SECONDS		8
#define BAUD		115200
#define TURNAROUND_US	200
#define REQ_DATA	4
#define MAX_SAMPLES	100000
#define GAP_CHARS	2	/* n_rs485's default inter-frame gap */

static double lat[MAX_SAMPLES];

static int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return x < y ? -1 : x > y;
}

/* A slave that answers I_ECHO exactly TURNAROUND_US after the request. */
struct fast_slave {
	int wfd;
	atomic_int stop;
	pthread_t thread;
};

static void *fast_slave_main(void *arg)
{
	struct fast_slave *s = arg;
	struct pollfd p = { .fd = s->wfd, .events = POLLIN };
	uint8_t f[N_RS485_MAX_FRAME + 1], r[N_RS485_MAX_FRAME];
	uint16_t w[512];
	size_t pos = 0;
	int in_frame = 0;

	while (!s->stop) {
		ssize_t n, i;

		if (poll(&p, 1, 20) <= 0)
			continue;
		n = read(s->wfd, w, sizeof(w));
		for (i = 0; i < n / 2; i++) {
			if (w[i] & TS7800_SIM_WORD_BIT9) {
				in_frame = 1;
				pos = 0;
			} else if (!in_frame) {
				continue;
			}
			f[pos++] = w[i];
			if (pos >= 5 && pos == (size_t)f[3] + 5) {
				double t = now_s() + TURNAROUND_US / 1e6;

				in_frame = 0;
				if (crc8_maxim(f, pos - 1) != f[pos - 1] || f[0] != SLAVE_ADDR)
					continue;
				memcpy(r, f, pos - 1);
				r[2] = N_RS485_RESP_ACK;
				while (now_s() < t)
					;
				wire_send_frame(s->wfd, r, pos - 1, 0);
			}
		}
	}
	return NULL;
}

/* The seed's design: user space switches parity and parses PARMRK. */
static int raw_open(void)
{
	struct termios t;
	int fd = open("/dev/ttyTSU0", O_RDWR | O_NOCTTY | O_NONBLOCK);

	if (fd < 0)
		return -1;
	memset(&t, 0, sizeof(t));
	cfmakeraw(&t);
	t.c_cflag = CS8 | CREAD | CLOCAL | PARENB | CMSPAR;
	t.c_iflag = INPCK | PARMRK;
	cfsetispeed(&t, B115200);
	cfsetospeed(&t, B115200);
	if (tcsetattr(fd, TCSANOW, &t)) {
		close(fd);
		return -1;
	}
	return fd;
}

static int raw_set_mark(int fd, int mark)
{
	struct termios t;

	if (tcgetattr(fd, &t))
		return -1;
	if (mark)
		t.c_cflag |= PARODD;
	else
		t.c_cflag &= ~PARODD;
	return tcsetattr(fd, TCSADRAIN, &t);
}

static int raw_xfer(int fd, const uint8_t *req, size_t n, uint8_t *resp, double timeout_s)
{
	uint8_t wire[N_RS485_MAX_FRAME + 1], in[1024];
	struct pollfd p = { .fd = fd, .events = POLLIN };
	double end = now_s() + timeout_s;
	size_t pos = 0;
	int in_frame = 0, esc = 0;

	memcpy(wire, req, n);
	wire[n] = crc8_maxim(req, n);
	if (raw_set_mark(fd, 1) || write(fd, wire, 1) != 1 || raw_set_mark(fd, 0) ||
	    write(fd, wire + 1, n) != (ssize_t)n)
		return -1;
	while (now_s() < end) {
		ssize_t r, i;

		if (poll(&p, 1, 10) <= 0)
			continue;
		r = read(fd, in, sizeof(in));
		for (i = 0; i < r; i++) {
			int addr = 0;
			uint8_t c = in[i];

			/* PARMRK: \377 \0 c = flagged c, \377 \377 = 0xff */
			if (esc == 0 && c == 0377) {
				esc = 1;
				continue;
			}
			if (esc == 1) {
				if (c == 0377) {
					esc = 0;
				} else {
					esc = 2;
					continue;
				}
			} else if (esc == 2) {
				esc = 0;
				addr = 1;
			}
			if (addr) {
				in_frame = 1;
				pos = 0;
			} else if (!in_frame) {
				continue;
			}
			resp[pos++] = c;
			if (pos >= 5 && pos == (size_t)resp[3] + 5) {
				in_frame = 0;
				if (crc8_maxim(resp, pos - 1) == resp[pos - 1])
					return 0;
			}
		}
	}
	return -1;
}

struct result {
	const char *name;
	unsigned int n, failed;
	double seconds, p50, p90, p99, max;
	double cpu_s;			/* guest CPU time during the pass */
	struct ts7800_sim_line_gaps g;	/* the line during the pass */
	double switches, drains, addr_drains;	/* per frame */
};

static void finish(struct result *r, double t0)
{
	r->seconds = now_s() - t0;
	qsort(lat, r->n, sizeof(lat[0]), cmp_double);
	if (!r->n)
		return;
	r->p50 = lat[r->n / 2];
	r->p90 = lat[r->n * 9 / 10];
	r->p99 = lat[r->n * 99 / 100];
	r->max = lat[r->n - 1];
}

/* Guest CPU time so far, all CPUs, everything but idle and iowait. */
static double guest_cpu_s(void)
{
	unsigned long long v[8] = { 0 };
	FILE *f = fopen("/proc/stat", "r");
	int n = 0;

	if (f) {
		n = fscanf(f, "cpu %llu %llu %llu %llu %llu %llu %llu %llu", &v[0], &v[1], &v[2],
			   &v[3], &v[4], &v[5], &v[6], &v[7]);
		fclose(f);
	}
	if (n < 7)
		return 0;
	return (double)(v[0] + v[1] + v[2] + v[5] + v[6] + v[7]) / sysconf(_SC_CLK_TCK);
}

static void pass_start(struct result *r, int wfd, double *t0)
{
	wire_reset_stats(wfd);
	r->cpu_s = guest_cpu_s();
	*t0 = now_s();
}

static void pass_end(struct result *r, int wfd)
{
	r->cpu_s = guest_cpu_s() - r->cpu_s;
	wire_gaps(wfd, &r->g);
}

/* n_rs485 on the path the module parameter addrb selects. */
static void run_n_rs485(struct result *r, int wfd, int addrb, unsigned int want_path)
{
	uint8_t data[REQ_DATA] = { 1, 2, 3, 4 };
	struct n_rs485_stats st;
	struct n_rs485_xfer x;
	double t0, t;
	int fd, ret;

	if (sh("echo %d > /sys/module/n_rs485/parameters/addrb", addrb))
		tap_bail("n_rs485 parameter addrb");
	fd = bus_open(PORT);
	memset(&st, 0, sizeof(st));
	if (fd < 0 || get_stats(fd, &st) || st.tx_path != want_path)
		tap_bail("attach n_rs485 on path %u (got %llu)", want_path,
			 (unsigned long long)st.tx_path);
	pass_start(r, wfd, &t0);
	while (now_s() - t0 < SECONDS && r->n < MAX_SAMPLES) {
		t = now_s();
		ret = xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, data, REQ_DATA, 100000, 0);
		if (ret || x.status != N_RS485_OK || memcmp(x.resp.data, data, REQ_DATA)) {
			if (!r->failed++)
				tap_diag("%s: transaction %u failed after %.1f ms: ioctl %d, status %u, attempts %u",
					 r->name, r->n, (now_s() - t) * 1e3, ret, x.status,
					 x.attempts);
			continue;
		}
		lat[r->n++] = now_s() - t;
	}
	pass_end(r, wfd);
	finish(r, t0);
	if (!get_stats(fd, &st) && st.tx_frames) {
		r->switches = (double)st.termios_switches / st.tx_frames;
		r->drains = (double)st.drains / st.tx_frames;
		r->addr_drains = (double)st.addr_drains / st.tx_frames;
	}
	close(fd);
}

static void run_seed_design(struct result *r, int wfd)
{
	uint8_t data[REQ_DATA] = { 1, 2, 3, 4 }, req[8], resp[N_RS485_MAX_FRAME + 1];
	double t0, t;
	int fd = raw_open();

	if (fd < 0)
		tap_bail("open raw tty");
	memcpy(req, (uint8_t[]){ SLAVE_ADDR, I_ECHO, 0, REQ_DATA }, 4);
	memcpy(req + 4, data, REQ_DATA);
	pass_start(r, wfd, &t0);
	while (now_s() - t0 < SECONDS && r->n < MAX_SAMPLES) {
		t = now_s();
		if (raw_xfer(fd, req, 4 + REQ_DATA, resp, 0.1) || memcmp(resp + 4, data, REQ_DATA)) {
			r->failed++;
			continue;
		}
		lat[r->n++] = now_s() - t;
	}
	pass_end(r, wfd);
	finish(r, t0);
	/* raw_xfer(): two tcsetattr(TCSADRAIN) per request, one between address and data */
	r->switches = 2;
	r->drains = 2;
	r->addr_drains = 1;
	close(fd);
}

static void report(const struct result *r, double wire_s, double char_s)
{
	const struct ts7800_sim_line_gaps *g = &r->g;
	double n = r->n ? r->n : 1, per = r->n ? r->seconds / r->n : 0;
	double idle = (g->frame_idle_ns[0] + g->char_idle_ns[0] + g->frame_idle_ns[1] +
		       g->char_idle_ns[1]) / 1e9 / n;
	double protocol = GAP_CHARS * char_s + TURNAROUND_US / 1e6;
	double in_req = g->char_idle_ns[TS7800_SIM_LOG_TX] / 1e9 / n;

	tap_diag("| %s | %.1f | %.3f | %.0f | %.0f | %.0f | %.0f | %.2f | %.2f | %.2f | %.0f | %.0f / %.0f / %.0f | %u |",
		 r->name, r->n / r->seconds, per ? wire_s / per : 0, idle * 1e6, protocol * 1e6,
		 in_req * 1e6, (idle - protocol - in_req) * 1e6, r->switches, r->addr_drains,
		 r->drains, r->cpu_s / n * 1e6, r->p50 * 1e6, r->p90 * 1e6, r->p99 * 1e6,
		 r->failed);
}

static double load_avg(void)
{
	double l = 0;
	FILE *f = fopen("/proc/loadavg", "r");

	if (f) {
		if (fscanf(f, "%lf", &l) != 1)
			l = 0;
		fclose(f);
	}
	return l;
}

int main(void)
{
	struct result res[3] = { { .name = "a. n_rs485, addressing path (ADDRB)" },
				 { .name = "b. n_rs485, mark/space path" },
				 { .name = "c. seed design: user space over N_TTY" } };
	struct fast_slave s = { 0 };
	/* request and response: ADDR INSTR FLAGS LEN DATA CRC */
	double char_s = 11.0 / BAUD;
	double wire_s = 2.0 * (REQ_DATA + 5) * char_s + TURNAROUND_US / 1e6;
	int fd;

	tap_plan(4);
	if (sim_load())
		tap_bail("cannot load ts_uart + ts7800_sim");
	s.wfd = wire_open(PORT, O_NONBLOCK);
	if (s.wfd < 0 || pthread_create(&s.thread, NULL, fast_slave_main, &s))
		tap_bail("slave");
	/* load n_rs485 (TIOCSETD autoloads it) so that its parameter exists */
	fd = bus_open(PORT);
	if (fd < 0)
		tap_bail("attach n_rs485");
	close(fd);

	run_n_rs485(&res[0], s.wfd, 1, N_RS485_PATH_ADDRB);
	run_n_rs485(&res[1], s.wfd, 0, N_RS485_PATH_PARITY);
	sh("echo 1 > /sys/module/n_rs485/parameters/addrb");
	run_seed_design(&res[2], s.wfd);
	s.stop = 1;
	pthread_join(s.thread, NULL);
	close(s.wfd);

	tap_diag("guest load average %.2f (1 min) after the run; wire limit %.0f us per transaction",
		 load_avg(), wire_s * 1e6);
	tap_diag("| path | xact/s | of wire limit | idle us/xact | protocol gaps | in request | rest (CPU) | termios switches/frame | drains addr-data/frame | drains/frame | guest CPU us/xact | latency us p50 / p90 / p99 | failed |");
	tap_diag("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
	for (fd = 0; fd < 3; fd++)
		report(&res[fd], wire_s, char_s);
	tap_diag("ratio a/c %.2f, b/c %.2f, a/b %.2f (transactions per second, same run)",
		 res[0].n * res[2].seconds / (res[2].n * res[0].seconds + 1e-9),
		 res[1].n * res[2].seconds / (res[2].n * res[1].seconds + 1e-9),
		 res[0].n * res[1].seconds / (res[1].n * res[0].seconds + 1e-9));
	tap_ok(res[0].n > 0 && res[0].failed == 0,
	       "n_rs485 addressing path: every transaction answered (%u failed)", res[0].failed);
	tap_ok(res[0].switches == 0 && res[0].addr_drains == 0,
	       "n_rs485 addressing path: no termios switch, no drain between address and data (%.2f, %.2f per frame)",
	       res[0].switches, res[0].addr_drains);
	tap_ok(res[1].n > 0 && res[1].failed == 0,
	       "n_rs485 mark/space path: every transaction answered (%u failed)", res[1].failed);
	tap_ok(res[2].n > 0, "user-space design completed transactions (%u failed)",
	       res[2].failed);
	sim_unload();
	return tap_finish();
}
