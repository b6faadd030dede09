// SPDX-License-Identifier: GPL-2.0
/*
 * lifecycle - the port ends cleanly in every way a user can end it:
 * close with output still pending (waits and sends all of it), flush then
 * close (returns at once, the line goes quiet), hangup while transmitting,
 * removal of the simulator while a port is open and a reader is blocked, and
 * an attempt to unload the driver of an open port. The harness checks the
 * kernel log for warnings after the program.
 */
#include <sys/ioctl.h>

#include "tsuart-lib.h"

static uint8_t buf[4096];
static uint16_t words[4096];

static void close_pending(void)
{
	struct ts7800_sim_wire_stats st;
	int fd = tty_open(3, B9600, 0, 0), wfd = wire_open(3, 0);
	double t0, dt;
	size_t n, i;

	for (i = 0; i < 300; i++) {
		buf[i] = (uint8_t)(i * 13);
		words[i] = 0;
	}
	ioctl(wfd, TS7800_SIM_RESET_STATS);
	tty_write_all(fd, buf, 300);
	t0 = now_s();
	close(fd);
	dt = now_s() - t0;
	n = wire_read_n(wfd, words, 300, 2, NULL);
	for (i = 0; i < n && words[i] == buf[i]; i++)
		;
	wire_stats(wfd, &st);
	tap_ok(n == 300 && i == 300 && dt > 0.2,
	       "close with 300 characters pending at 9600 Bd waits %.2f s and sends all of them (%zu)",
	       dt, n);
	close(wfd);
}

static void flush_close(void)
{
	struct ts7800_sim_wire_stats st1, st2;
	int fd = tty_open(4, B2400, 0, 0), wfd = wire_open(4, 0);
	double t0, dt;

	memset(buf, 'x', 1000);
	ioctl(wfd, TS7800_SIM_RESET_STATS);
	tty_write_all(fd, buf, 1000);
	usleep(100000);
	tcflush(fd, TCOFLUSH);
	t0 = now_s();
	close(fd);
	dt = now_s() - t0;
	usleep(300000);		/* the FIFO (16) drains in 67 ms at 2400 Bd */
	wire_stats(wfd, &st1);
	usleep(500000);
	wire_stats(wfd, &st2);
	tap_ok(dt < 1.0 && st1.to_wire < 100 && st2.to_wire == st1.to_wire,
	       "flush + close returns in %.2f s, the line stops after %llu characters",
	       dt, (unsigned long long)st2.to_wire);
	close(wfd);
}

static void hangup(void)
{
	int fd = tty_open(5, B2400, 0, 0), fd2;
	double t0;
	ssize_t r;
	int ok;

	memset(buf, 'h', 500);
	tty_write_all(fd, buf, 500);
	t0 = now_s();
	ok = ioctl(fd, TIOCVHANGUP) == 0;
	r = write(fd, buf, 1);
	ok = ok && r < 0 && errno == EIO && read(fd, buf, 1) == 0;
	close(fd);
	tap_ok(ok && now_s() - t0 < 1.0,
	       "TIOCVHANGUP while sending: write gives EIO, read EOF, close at once");

	fd2 = tty_open(5, B115200, 0, 0);
	ok = fd2 >= 0;
	if (ok) {
		int wfd = wire_open(5, 0);
		uint16_t w[10], got[10];
		int i;

		for (i = 0; i < 10; i++)
			w[i] = (uint16_t)('0' + i);
		ok = wfd >= 0 && wire_write_all(wfd, w, 10) == 0 &&
		     tty_read_words(fd2, got, 10, 3, NULL) == 10 && first_diff(w, got, 10) < 0;
		close(wfd);
		close(fd2);
	}
	tap_ok(ok, "after the hangup the port opens again and receives");
}

struct blocked_reader {
	int fd;
	ssize_t r;
	int err;
	int done;
};

static void *reader_main(void *arg)
{
	struct blocked_reader *b = arg;

	b->r = read(b->fd, buf, 1);
	b->err = errno;
	__atomic_store_n(&b->done, 1, __ATOMIC_SEQ_CST);
	return NULL;
}

static void rmmod_while_open(void)
{
	struct termios t;
	struct blocked_reader b = { 0 };
	pthread_t th;
	int fd, i;
	ssize_t r;

	fd = tty_open(6, B2400, 0, 0);
	tcgetattr(fd, &t);
	t.c_cc[VMIN] = 1;	/* block in read() */
	tcsetattr(fd, TCSANOW, &t);
	b.fd = fd;
	pthread_create(&th, NULL, reader_main, &b);
	memset(buf, 'r', 200);
	tty_write_all(fd, buf, 200);

	tap_ok(sh("modprobe -r ts_uart 2>/dev/null") != 0,
	       "unloading the TS-UART driver of an open port is refused");
	tap_ok(sh("modprobe -r ts7800_sim") == 0,
	       "the simulator unloads while port 6 is open, transmitting and read-blocked");
	for (i = 0; i < 200 && !__atomic_load_n(&b.done, __ATOMIC_SEQ_CST); i++)
		usleep(10000);
	tap_ok(__atomic_load_n(&b.done, __ATOMIC_SEQ_CST) && b.r <= 0,
	       "the blocked read returns (%zd, %s)", b.r, b.r < 0 ? strerror(b.err) : "EOF");
	if (!b.done)
		pthread_cancel(th);
	pthread_join(th, NULL);
	r = write(fd, buf, 1);
	tap_ok(r < 0 && errno == EIO, "write to the removed port gives EIO");
	tap_ok(close(fd) == 0, "close of the removed port succeeds");
	tap_ok(sh("modprobe ts7800_sim") == 0 && wait_ports(NPORTS) == 0,
	       "the simulator loads again and the ports come back");
}

int main(void)
{
	tap_plan(12);
	if (!tap_ok(sim_load("") == 0, "load ts_uart and ts7800_sim"))
		tap_bail("cannot continue without the simulator");
	close_pending();
	flush_close();
	hangup();
	rmmod_while_open();
	tap_ok(sim_unload() == 0, "unload");
	return tap_finish();
}
