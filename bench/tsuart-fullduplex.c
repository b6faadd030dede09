// SPDX-License-Identifier: GPL-2.0
/*
 * tsuart-fullduplex - full-duplex throughput of one TS-UART on the simulated
 * FPGA (run inside the VM through bench/tsuart.sh).
 *
 * The tty and the far end (the port's wire) both send as fast as they can
 * for the whole run; both receivers check the data against the sender's
 * sequence. Printed, all measured in this one run:
 *   - characters per second each way as a fraction of the line limit
 *     (rate / bits per character; target >= 0.99),
 *   - guest CPU time per 1000 characters carried (both directions summed),
 *   - the simulator's stall time (periods the emulated CPU did not run),
 *   - the data check: nothing altered either way, and every character lost
 *     on receive accounted for by an overrun (exit status 1 otherwise).
 * usage: tsuart-fullduplex [-d SECONDS] [-p PORT] [-8]
 */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>
#include <linux/ts7800_sim.h>

#define CHUNK 512

#define RESYNC_WINDOW 256	/* longest run of lost characters the checker skips */

static volatile int stop_writers, stop_readers;
static int nine = 1;
static unsigned long long rx_bad, tx_bad, rx_n, tx_n, rx_lost;

static double now_s(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + ts.tv_nsec / 1e9;
}

/* The i-th character of a direction's sequence (9th bit on every 64th). */
static uint16_t seq_word(unsigned long long i, unsigned int salt)
{
	uint32_t x = (uint32_t)(i * 2654435761u) ^ salt;
	uint16_t w = (x >> 13) & 0xff;

	if (nine && (i % 64) == 0)
		w |= TS7800_SIM_WORD_BIT9;
	return w;
}

struct cpu_sample {
	unsigned long long busy, total, sys;
};

static int cpu_read(struct cpu_sample *s)
{
	unsigned long long v[8] = { 0 };
	FILE *f = fopen("/proc/stat", "r");
	int n;

	if (!f)
		return -1;
	n = fscanf(f, "cpu %llu %llu %llu %llu %llu %llu %llu %llu", &v[0], &v[1], &v[2],
		   &v[3], &v[4], &v[5], &v[6], &v[7]);
	fclose(f);
	if (n < 8)
		return -1;
	s->total = v[0] + v[1] + v[2] + v[3] + v[4] + v[5] + v[6] + v[7];
	s->busy = s->total - v[3] - v[4];
	s->sys = v[2] + v[5] + v[6];
	return 0;
}

static int tty_fd, wire_fd;

static void *tty_writer(void *arg)
{
	unsigned long long i = 0;
	uint8_t buf[CHUNK];
	ssize_t r;
	int k;

	(void)arg;
	while (!stop_writers) {
		for (k = 0; k < CHUNK; k++)
			buf[k] = seq_word(i + k, 0x5a5a) & 0xff;
		r = write(tty_fd, buf, CHUNK);
		if (r > 0)
			i += r;	/* a short write leaves the rest for the next round */
		else if (r < 0 && errno != EINTR)
			break;
	}
	return NULL;
}

static void *wire_reader(void *arg)
{
	uint16_t w[CHUNK];
	ssize_t r;
	int k;

	(void)arg;
	while (!stop_readers) {
		struct pollfd p = { .fd = wire_fd, .events = POLLIN };

		if (poll(&p, 1, 100) <= 0)
			continue;
		r = read(wire_fd, w, sizeof(w));
		if (r <= 0)
			continue;
		for (k = 0; k < r / 2; k++, tx_n++) {
			uint16_t want = seq_word(tx_n, 0x5a5a) & 0xff;

			if (w[k] != want)
				tx_bad++;
		}
	}
	return NULL;
}

static void *wire_writer(void *arg)
{
	unsigned long long i = 0;
	uint16_t w[CHUNK];
	ssize_t r;
	int k;

	(void)arg;
	while (!stop_writers) {
		for (k = 0; k < CHUNK; k++)
			w[k] = seq_word(i + k, 0xa5a5);
		r = write(wire_fd, w, sizeof(w));
		if (r > 0)
			i += r / 2;
		else if (r < 0 && errno != EINTR && errno != EAGAIN)
			break;
	}
	return NULL;
}

/*
 * Received character number rx_n + rx_lost should be got. Characters the
 * UART lost in an overrun are skipped: the next match within the window
 * resynchronises and the gap counts as lost (compared with the simulator's
 * overrun count at the end); anything else is wrong.
 */
static void rx_check(uint16_t got)
{
	unsigned long long k;

	for (k = 0; k < RESYNC_WINDOW; k++) {
		if (got == seq_word(rx_n + rx_lost + k, 0xa5a5)) {
			rx_lost += k;
			rx_n++;
			return;
		}
	}
	rx_bad++;
	rx_n++;
}

/* PARMRK stream: "\377\0c" = c with the 9th bit differing from space. */
static void *tty_reader(void *arg)
{
	uint8_t buf[4096 + 2];
	size_t have = 0, i;
	ssize_t r;

	(void)arg;
	while (!stop_readers) {
		struct pollfd p = { .fd = tty_fd, .events = POLLIN };

		if (poll(&p, 1, 100) <= 0)
			continue;
		r = read(tty_fd, buf + have, sizeof(buf) - 2 - have);
		if (r <= 0)
			continue;
		have += r;
		for (i = 0; i < have;) {
			uint16_t got;

			if (buf[i] != 0377) {
				got = buf[i++];
			} else if (i + 1 < have && buf[i + 1] == 0377) {
				got = 0377;
				i += 2;
			} else if (i + 2 < have) {
				got = TS7800_SIM_WORD_BIT9 | buf[i + 2];
				i += 3;
			} else {
				break;
			}
			rx_check(got);
		}
		memmove(buf, buf + i, have - i);
		have -= i;
	}
	return NULL;
}

/* Wait until the wire's queued characters have all been received. */
static void wait_line_idle(void)
{
	struct ts7800_sim_wire_stats st;
	unsigned long long last = ~0ULL;
	int i;

	for (i = 0; i < 600; i++) {
		if (ioctl(wire_fd, TS7800_SIM_GET_STATS, &st))
			return;
		if (st.from_wire + st.rx_overruns == last)
			return;
		last = st.from_wire + st.rx_overruns;
		usleep(200000);
	}
}

int main(int argc, char **argv)
{
	double seconds = 60, t0, t1, cpu_s, sys_s, line_cps, exact_cps;
	struct ts7800_sim_wire_stats s0, s1, s_end;
	struct cpu_sample c0, c1;
	pthread_t th[4];
	unsigned long long tx, rx;
	unsigned int bits;
	struct termios t;
	char path[64];
	int port = 0, opt;

	while ((opt = getopt(argc, argv, "d:p:8")) != -1) {
		switch (opt) {
		case 'd': seconds = atof(optarg); break;
		case 'p': port = atoi(optarg); break;
		case '8': nine = 0; break;
		default:
			fprintf(stderr, "usage: %s [-d SECONDS] [-p PORT] [-8]\n", argv[0]);
			return 2;
		}
	}
	bits = nine ? 11 : 10;

	snprintf(path, sizeof(path), "/dev/ttyTSU%d", port);
	tty_fd = open(path, O_RDWR | O_NOCTTY);
	snprintf(path, sizeof(path), "/dev/ts7800-sim/uart%d", port);
	wire_fd = open(path, O_RDWR);
	if (tty_fd < 0 || wire_fd < 0) {
		perror("open tty or wire");
		return 1;
	}
	memset(&t, 0, sizeof(t));
	cfmakeraw(&t);
	t.c_cflag = CS8 | CREAD | CLOCAL | (nine ? PARENB | CMSPAR : 0);
	t.c_iflag = INPCK | PARMRK;	/* flagged and 0xFF bytes stay unambiguous */
	cfsetispeed(&t, B115200);
	cfsetospeed(&t, B115200);
	if (tcsetattr(tty_fd, TCSANOW, &t)) {
		perror("tcsetattr");
		return 1;
	}

	pthread_create(&th[0], NULL, tty_reader, NULL);
	pthread_create(&th[1], NULL, wire_reader, NULL);
	pthread_create(&th[2], NULL, tty_writer, NULL);
	pthread_create(&th[3], NULL, wire_writer, NULL);

	sleep(1);	/* warm-up: both lines busy */
	ioctl(wire_fd, TS7800_SIM_GET_STATS, &s0);
	cpu_read(&c0);
	t0 = now_s();
	usleep((useconds_t)(seconds * 1e6));
	ioctl(wire_fd, TS7800_SIM_GET_STATS, &s1);
	cpu_read(&c1);
	t1 = now_s();

	/* End cleanly: writers finish their chunk, everything sent arrives. */
	stop_writers = 1;
	pthread_join(th[2], NULL);
	pthread_join(th[3], NULL);
	tcdrain(tty_fd);
	wait_line_idle();
	sleep(1);
	stop_readers = 1;
	pthread_join(th[0], NULL);
	pthread_join(th[1], NULL);
	ioctl(wire_fd, TS7800_SIM_GET_STATS, &s_end);

	tx = s1.to_wire - s0.to_wire;
	rx = s1.from_wire - s0.from_wire;
	line_cps = 115200.0 / bits;
	/* 115200 Bd really is 12.5 MHz / 108 = 115741 bit/s on this board. */
	exact_cps = 12500000.0 / 108 / bits;
	cpu_s = (double)(c1.busy - c0.busy) / sysconf(_SC_CLK_TCK);
	sys_s = (double)(c1.sys - c0.sys) / sysconf(_SC_CLK_TCK);

	printf("tsuart full duplex, port %d, 115200 Bd, %s (%u bits/char), %.1f s\n", port,
	       nine ? "9-bit (PARENB|CMSPAR)" : "8-bit", bits, t1 - t0);
	printf("  TX (tty -> wire): %llu chars, %.1f chars/s = %.4f of the line limit (%.1f/s; %.4f of the divisor-exact %.1f/s)\n",
	       tx, tx / (t1 - t0), tx / (t1 - t0) / line_cps, line_cps,
	       tx / (t1 - t0) / exact_cps, exact_cps);
	printf("  RX (wire -> tty): %llu chars, %.1f chars/s = %.4f of the line limit (%.4f of divisor-exact)\n",
	       rx, rx / (t1 - t0), rx / (t1 - t0) / line_cps, rx / (t1 - t0) / exact_cps);
	printf("  guest CPU: %.2f CPU-s busy (%.2f s kernel+irq), %.3f ms per 1000 chars carried\n",
	       cpu_s, sys_s, cpu_s * 1e6 / (double)(tx + rx));
	printf("  simulator stalls (emulated CPU not running): TX %.3f s, RX %.3f s; overruns %llu; wire drops %llu\n",
	       (s1.to_wire_stall_ns - s0.to_wire_stall_ns) / 1e9,
	       (s1.from_wire_stall_ns - s0.from_wire_stall_ns) / 1e9,
	       (unsigned long long)(s1.rx_overruns - s0.rx_overruns),
	       (unsigned long long)(s1.to_wire_dropped - s0.to_wire_dropped));
	printf("  data check: TX %llu chars verified, %llu wrong; RX %llu verified, %llu wrong, %llu lost (simulator overruns in the whole run: %llu)\n",
	       tx_n, tx_bad, rx_n, rx_bad, rx_lost, (unsigned long long)s_end.rx_overruns);
	close(tty_fd);
	close(wire_fd);
	/* Correct: nothing altered, and every lost character was an overrun. */
	return tx_bad || rx_bad || rx_lost != s_end.rx_overruns ? 1 : 0;
}
