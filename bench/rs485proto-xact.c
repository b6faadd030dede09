// SPDX-License-Identifier: GPL-2.0
/*
 * bench - back-to-back transactions on the simulated bus at 115200 Bd with
 * a slave (a thread on the wire) that answers 200 us after a request ended:
 *
 *   1. through n_rs485 (N_RS485_IOC_XFER),
 *   2. through N_TTY with the seed's design: a user-space state machine that
 *      switches mark/space with tcsetattr(TCSADRAIN) and decodes PARMRK,
 *
 * each for SECONDS. Printed for each: the rate as a fraction of the wire
 * limit (characters x 11 / rate + turnaround per transaction), latency
 * percentiles, and the ratio of the two rates measured in this one run.
 * Under TCG the emulated CPU is far slower than the TS-7800's line, so the
 * fractions say more about the emulator than the design; the ratio between
 * the two designs is the meaningful number. A benchmark: make bench runs it.
 */
#include "rs485-lib.h"

#define PORT		0
#define SECONDS		8
#define BAUD		115200
#define TURNAROUND_US	200
#define REQ_DATA	4
#define MAX_SAMPLES	100000

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
	unsigned int n, failed;
	double seconds, p50, p90, p99, max;
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

static void report(const char *what, const struct result *r, double wire_s)
{
	double per = r->n ? r->seconds / r->n : 0;

	tap_diag("%s: %u transactions (%u failed) in %.2f s = %.1f/s; %.3f of the wire limit (%.0f us each); latency us p50 %.0f p90 %.0f p99 %.0f max %.0f",
		 what, r->n, r->failed, r->seconds, r->n / r->seconds, per ? wire_s / per : 0,
		 wire_s * 1e6, r->p50 * 1e6, r->p90 * 1e6, r->p99 * 1e6, r->max * 1e6);
}

int main(void)
{
	uint8_t data[REQ_DATA] = { 1, 2, 3, 4 }, req[8], resp[N_RS485_MAX_FRAME + 1];
	struct result kern = { 0 }, user = { 0 };
	struct fast_slave s = { 0 };
	struct n_rs485_xfer x;
	/* request and response: ADDR INSTR FLAGS LEN DATA CRC */
	double wire_s = 2.0 * (REQ_DATA + 5) * 11 / BAUD + TURNAROUND_US / 1e6;
	double t0, t;
	int fd;

	tap_plan(2);
	if (sim_load())
		tap_bail("cannot load ts_uart + ts7800_sim");
	s.wfd = wire_open(PORT, O_NONBLOCK);
	if (s.wfd < 0 || pthread_create(&s.thread, NULL, fast_slave_main, &s))
		tap_bail("slave");

	fd = bus_open(PORT);
	if (fd < 0)
		tap_bail("attach n_rs485");
	t0 = now_s();
	while (now_s() - t0 < SECONDS && kern.n < MAX_SAMPLES) {
		t = now_s();
		if (xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, data, REQ_DATA, 100000, 0) ||
		    x.status != N_RS485_OK || memcmp(x.resp.data, data, REQ_DATA)) {
			kern.failed++;
			continue;
		}
		lat[kern.n++] = now_s() - t;
	}
	finish(&kern, t0);
	close(fd);

	fd = raw_open();
	if (fd < 0)
		tap_bail("open raw tty");
	memcpy(req, (uint8_t[]){ SLAVE_ADDR, I_ECHO, 0, REQ_DATA }, 4);
	memcpy(req + 4, data, REQ_DATA);
	t0 = now_s();
	while (now_s() - t0 < SECONDS && user.n < MAX_SAMPLES) {
		t = now_s();
		if (raw_xfer(fd, req, 4 + REQ_DATA, resp, 0.1) || memcmp(resp + 4, data, REQ_DATA)) {
			user.failed++;
			continue;
		}
		lat[user.n++] = now_s() - t;
	}
	finish(&user, t0);
	close(fd);
	s.stop = 1;
	pthread_join(s.thread, NULL);
	close(s.wfd);

	report("n_rs485 ioctl", &kern, wire_s);
	report("user-space state machine over N_TTY (seed design)", &user, wire_s);
	tap_diag("ratio n_rs485 / user space: %.2f (transactions per second, same run)",
		 user.n ? (kern.n / kern.seconds) / (user.n / user.seconds) : 0);
	tap_ok(kern.n > 0 && kern.failed == 0, "n_rs485: every transaction answered (%u failed)",
	       kern.failed);
	tap_ok(user.n > 0, "user-space design completed transactions (%u failed)", user.failed);
	sim_unload();
	return tap_finish();
}
