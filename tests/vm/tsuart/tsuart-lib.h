/* SPDX-License-Identifier: GPL-2.0 */
/*
 * tsuart-lib.h - helpers of the tsuart VM tests: load the simulated FPGA and
 * the TS-UART driver, configure a port with termios, read its wire
 * (/dev/ts7800-sim/uartN; opening and writing it: ts7800-wire.h) and decode
 * what N_TTY delivers with PARMRK. Included by exactly one .c per program.
 */
#ifndef TSUART_LIB_H
#define TSUART_LIB_H

#include <dirent.h>
#include <fcntl.h>
#include <pthread.h>
#include <poll.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>
#include <linux/serial.h>
#include <linux/ts7800_sim.h>

#include "tap.h"
#include "vmtest.h"
#include "ts7800-wire.h"

#define NPORTS 10

struct rate {
	unsigned int baud;
	speed_t speed;
};

static const struct rate rates[] = {
	{ 115200, B115200 }, { 57600, B57600 }, { 38400, B38400 }, { 19200, B19200 },
	{ 9600, B9600 }, { 4800, B4800 }, { 2400, B2400 },
};

static inline int wait_ports(int nports)
{
	char path[64];
	int i;

	for (i = 0; i < nports; i++) {
		snprintf(path, sizeof(path), "/dev/ttyTSU%d", i);
		if (wait_for_path(path))
			return -1;
		snprintf(path, sizeof(path), "/dev/ts7800-sim/uart%d", i);
		if (wait_for_path(path))
			return -1;
	}
	return 0;
}

/* Load driver + simulator with the given module parameters; 0 on success. */
static inline int sim_load(const char *params)
{
	if (sh("modprobe ts_uart") || sh("modprobe ts7800_sim %s", params ? params : ""))
		return -1;
	return wait_ports(NPORTS);
}

static inline int sim_unload(void)
{
	return sh("modprobe -r ts7800_sim") || sh("modprobe -r ts_uart ts7800_fpga");
}

/* Raw port: no echo, no translation; PARMRK makes flagged characters visible. */
static inline int tty_open(int port, speed_t speed, tcflag_t cflag_extra, int flags)
{
	struct termios t;
	char path[32];
	int fd;

	snprintf(path, sizeof(path), "/dev/ttyTSU%d", port);
	fd = open(path, O_RDWR | O_NOCTTY | flags);
	if (fd < 0)
		return -1;
	memset(&t, 0, sizeof(t));
	cfmakeraw(&t);
	t.c_cflag = CS8 | CREAD | CLOCAL | cflag_extra;
	t.c_iflag = INPCK | PARMRK;
	t.c_cc[VMIN] = 0;
	t.c_cc[VTIME] = 0;
	cfsetispeed(&t, speed);
	cfsetospeed(&t, speed);
	if (tcsetattr(fd, TCSANOW, &t)) {
		close(fd);
		return -1;
	}
	return fd;
}

/*
 * The kernel thread "irq/N-..." serving the tty's interrupt line when its
 * handler is threaded (PREEMPT_RT, threadirqs): its pid, else 0.
 */
static inline int tty_irq_thread(int fd)
{
	char path[300], comm[32], want[32];
	struct serial_struct ser;
	struct dirent *d;
	DIR *dir;
	int pid = 0;
	FILE *f;

	memset(&ser, 0, sizeof(ser));
	if (ioctl(fd, TIOCGSERIAL, &ser) < 0 || ser.irq <= 0)
		return 0;
	snprintf(want, sizeof(want), "irq/%d-", ser.irq);
	dir = opendir("/proc");
	if (!dir)
		return 0;
	while (!pid && (d = readdir(dir))) {
		if (d->d_name[0] < '1' || d->d_name[0] > '9')
			continue;
		snprintf(path, sizeof(path), "/proc/%s/comm", d->d_name);
		f = fopen(path, "r");
		if (!f)
			continue;
		if (fgets(comm, sizeof(comm), f) && !strncmp(comm, want, strlen(want)))
			pid = atoi(d->d_name);
		fclose(f);
	}
	closedir(dir);
	return pid;
}

/*
 * Read n words, giving up after timeout_s without progress; returns the
 * number read, *t_last the time the last ones arrived.
 */
static inline size_t wire_read_n(int wfd, uint16_t *w, size_t n, double timeout_s, double *t_last)
{
	double end = now_s() + timeout_s;
	struct pollfd p = { .fd = wfd, .events = POLLIN };
	size_t done = 0;
	ssize_t r;

	while (done < n && now_s() < end) {
		if (poll(&p, 1, 100) <= 0)
			continue;
		r = read(wfd, w + done, (n - done) * 2);
		if (r > 0) {
			done += r / 2;
			end = now_s() + timeout_s;
			if (t_last)
				*t_last = now_s();
		}
	}
	return done;
}

/* Read n raw bytes from a tty within timeout_s; returns the number read. */
static inline size_t tty_read_n(int fd, uint8_t *buf, size_t n, double timeout_s)
{
	double end = now_s() + timeout_s;
	struct pollfd p = { .fd = fd, .events = POLLIN };
	size_t done = 0;
	ssize_t r;

	while (done < n && now_s() < end) {
		if (poll(&p, 1, 100) <= 0)
			continue;
		r = read(fd, buf + done, n - done);
		if (r > 0)
			done += r;
	}
	return done;
}

static inline int tty_write_all(int fd, const uint8_t *buf, size_t n)
{
	size_t done = 0;
	ssize_t r;

	while (done < n) {
		r = write(fd, buf + done, n - done);
		if (r < 0) {
			if (errno == EINTR)
				continue;
			if (errno == EAGAIN) {
				struct pollfd p = { .fd = fd, .events = POLLOUT };

				poll(&p, 1, 100);
				continue;
			}
			return -1;
		}
		done += r;
	}
	return 0;
}

/*
 * Decode N_TTY's PARMRK stream (INPCK, !IGNPAR, !ISTRIP): "\377\0c" is c with
 * a parity error, "\377\377" a data byte 0xFF, "\377\0\0" could also be a
 * break (tests that send breaks know where). Output: words with bit 8 set for
 * flagged characters. Returns the number of words; *used = bytes consumed.
 */
static inline size_t parmrk_decode(const uint8_t *in, size_t len, uint16_t *out, size_t max,
				   size_t *used)
{
	size_t i = 0, n = 0;

	while (i < len && n < max) {
		if (in[i] != 0377) {
			out[n++] = in[i++];
			continue;
		}
		if (i + 1 >= len)
			break;
		if (in[i + 1] == 0377) {
			out[n++] = 0377;
			i += 2;
			continue;
		}
		if (i + 2 >= len)
			break;
		out[n++] = 0x100 | in[i + 2];
		i += 3;
	}
	*used = i;
	return n;
}

/* Receive n characters from a PARMRK tty as words (bit 8 = flagged), see above. */
static inline size_t tty_read_words(int fd, uint16_t *w, size_t n, double timeout_s,
				    double *t_last)
{
	const size_t bufsize = 65536;
	uint8_t *buf = malloc(bufsize);	/* one per thread: collectors run in parallel */
	double end = now_s() + timeout_s;
	struct pollfd p = { .fd = fd, .events = POLLIN };
	size_t have = 0, done = 0, used;
	ssize_t r;

	if (!buf)
		return 0;
	while (done < n && now_s() < end) {
		if (poll(&p, 1, 100) <= 0)
			continue;
		r = read(fd, buf + have, bufsize - have);
		if (r <= 0)
			continue;
		have += r;
		done += parmrk_decode(buf, have, w + done, n - done, &used);
		end = now_s() + timeout_s;
		if (t_last)
			*t_last = now_s();
		memmove(buf, buf + used, have - used);
		have -= used;
	}
	free(buf);
	return done;
}

/* A reader running in its own thread while the main thread writes. */
struct collector {
	int fd;
	int from_wire;		/* 1: read words from a wire, 0: PARMRK words from a tty */
	uint16_t *w;
	size_t n;
	double timeout_s;
	size_t got;
	double t_last;
	pthread_t thread;
};

static inline void *collector_main(void *arg)
{
	struct collector *c = arg;

	c->got = c->from_wire ? wire_read_n(c->fd, c->w, c->n, c->timeout_s, &c->t_last) :
				tty_read_words(c->fd, c->w, c->n, c->timeout_s, &c->t_last);
	return NULL;
}

static inline int collector_start(struct collector *c, int fd, int from_wire, uint16_t *w,
				  size_t n, double timeout_s)
{
	memset(c, 0, sizeof(*c));
	c->fd = fd;
	c->from_wire = from_wire;
	c->w = w;
	c->n = n;
	c->timeout_s = timeout_s;
	return pthread_create(&c->thread, NULL, collector_main, c);
}

static inline size_t collector_join(struct collector *c)
{
	pthread_join(c->thread, NULL);
	return c->got;
}

/* Index of the first difference, or -1 if equal. */
static inline long first_diff(const uint16_t *a, const uint16_t *b, size_t n)
{
	size_t i;

	for (i = 0; i < n; i++)
		if (a[i] != b[i])
			return (long)i;
	return -1;
}

/* Is got[0..ng) what sent[0..ns) becomes after dropping some characters? */
static inline int is_subsequence(const uint16_t *got, size_t ng, const uint16_t *sent, size_t ns)
{
	size_t i = 0, j;

	for (j = 0; j < ns && i < ng; j++)
		if (got[i] == sent[j])
			i++;
	return i == ng;
}

#endif /* TSUART_LIB_H */
