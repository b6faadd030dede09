// SPDX-License-Identifier: GPL-2.0
/*
 * lifecycle - pending transactions against signals, hangup, detach and
 * rmmod: a signal ends the caller's wait with EINTR without corrupting the
 * bus (the late response is not taken by the next caller); hangup and
 * detach end pending calls with EIO; rmmod is refused while attached and the
 * bus keeps working; blocked read() returns on detach.
 *
 * Orders come from conditions, not from sleeps: the slave holds the answer
 * the signal must beat until the signal handler has run, and every deadline
 * here is one that only a failure reaches (a TCG guest on a loaded host
 * stalls for seconds; CI saw one of these points fail under load).
 */
#include <signal.h>
#include <sys/time.h>

#include "rs485-lib.h"

#define PORT	0

static struct slave s;

/* The answer the signal has to beat is held until the signal is handled. */
static void on_alarm(int sig)
{
	(void)sig;
	s.hold = 0;
}

struct pending {
	int fd;
	int ret, err;
	struct n_rs485_xfer x;
};

static void *pending_main(void *arg)
{
	struct pending *p = arg;

	p->ret = xfer(p->fd, &p->x, SLAVE_ADDR, I_SILENT, 0, NULL, 0, 10000000, 0);
	p->err = errno;
	return NULL;
}

/*
 * Start a transaction that waits 10 s for an answer that never comes, act
 * after 200 ms, see how it ends: with EIO well before the 10 s.
 */
static void pending_vs(int fd, const char *what, int (*act)(int fd))
{
	struct pending p = { .fd = fd };
	pthread_t t;
	double t0 = now_s();

	pthread_create(&t, NULL, pending_main, &p);
	usleep(200000);
	act(fd);
	pthread_join(t, NULL);
	tap_ok(p.ret == -1 && p.err == EIO && now_s() - t0 < 8,
	       "%s ends a pending transaction with EIO (ret %d, %s, after %.2f s)", what, p.ret,
	       strerror(p.err), now_s() - t0);
}

struct queued {
	int fd;
	int ret;
	struct n_rs485_xfer x;
};

static void *queued_main(void *arg)
{
	struct queued *q = arg;

	usleep(10000);		/* behind the slow one */
	q->ret = xfer(q->fd, &q->x, SLAVE_ADDR, I_ECHO, 0, "queued", 6, 10000000, 0);
	return NULL;
}

static void *slow_main(void *arg)
{
	struct queued *q = arg;

	q->ret = xfer(q->fd, &q->x, SLAVE_ADDR, I_SLOW, 0, "slow", 4, 10000000, 0);
	return NULL;
}

static int do_hangup(int fd)
{
	return ioctl(fd, TIOCVHANGUP);
}

static int do_detach(int fd)
{
	int ld = N_TTY;

	return ioctl(fd, TIOCSETD, &ld);
}

int main(void)
{
	struct sigaction sa;
	struct itimerval it;
	struct n_rs485_xfer x;
	sigset_t alrm;
	uint8_t d[4] = { 1, 2, 3, 4 };
	int fd, fd2, ret, err;
	double t0;

	tap_plan(10);
	if (sim_load())
		tap_bail("cannot load ts_uart + ts7800_sim");
	fd = bus_open(PORT);
	/* SIGALRM is for the caller blocked in the ioctl, not the slave thread. */
	sigemptyset(&alrm);
	sigaddset(&alrm, SIGALRM);
	pthread_sigmask(SIG_BLOCK, &alrm, NULL);
	if (fd < 0 || slave_start(&s, PORT))
		tap_bail("attach n_rs485, slave");
	pthread_sigmask(SIG_UNBLOCK, &alrm, NULL);

	/*
	 * A signal during a slow transaction: the alarm comes 30 ms after the
	 * request; the slave answers 50 ms after the handler has run, so the
	 * answer cannot win the race however late the signal is delivered
	 * (0.2 s on the armhf guest at host load 12).
	 */
	memset(&sa, 0, sizeof(sa));
	sa.sa_handler = on_alarm;
	sigaction(SIGALRM, &sa, NULL);
	memset(&it, 0, sizeof(it));
	it.it_value.tv_usec = 30000;
	s.delay_us = 50000;
	s.hold = 1;
	setitimer(ITIMER_REAL, &it, NULL);
	t0 = now_s();
	ret = xfer(fd, &x, SLAVE_ADDR, I_DELAY, 0, d, 4, 10000000, 0);
	err = errno;
	tap_ok(ret == -1 && err == EINTR,
	       "a signal ends the caller's wait with EINTR, before the answer (ret %d, %s, after %.3f s)",
	       ret, ret ? strerror(err) : "OK", now_s() - t0);
	/* The late answer comes while this request waits: not taken for it. */
	d[0] = 9;
	ret = xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, d, 4, 10000000, 0);
	tap_ok(ret == 0 && x.status == N_RS485_OK && x.resp.instr == I_ECHO && x.resp.len == 4 &&
	       !memcmp(x.resp.data, d, 4),
	       "the next caller gets its own response, not the late one");

	/* rmmod while attached */
	tap_ok(sh("rmmod n_rs485 2>/dev/null") != 0, "rmmod is refused while attached");
	ret = xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, d, 4, 10000000, 0);
	tap_ok(ret == 0 && x.status == N_RS485_OK, "...and the bus still works");

	/* another process opens the tty while a request waits in the queue */
	{
		struct queued slow = { .fd = fd }, q = { .fd = fd };
		pthread_t ts, tq;
		int fd3;

		pthread_create(&ts, NULL, slow_main, &slow);
		pthread_create(&tq, NULL, queued_main, &q);
		usleep(40000);
		fd3 = open("/dev/ttyTSU0", O_RDWR | O_NOCTTY);
		pthread_join(tq, NULL);
		pthread_join(ts, NULL);
		tap_ok(fd3 >= 0 && q.ret == 0 && q.x.status == N_RS485_OK && q.x.resp.instr == I_ECHO &&
		       q.x.resp.len == 6 && !memcmp(q.x.resp.data, "queued", 6),
		       "a queued request survives another open() of the tty (slow one: ret %d)",
		       slow.ret);
		if (fd3 >= 0)
			close(fd3);
	}

	pending_vs(fd, "detach (TIOCSETD N_TTY)", do_detach);

	/* blocked read() and detach from a second open file */
	fd2 = open("/dev/ttyTSU0", O_RDWR | O_NOCTTY);
	{
		int ld = N_RS485_DEFAULT_LDISC;
		uint8_t buf[N_RS485_MAX_FRAME];

		ioctl(fd, TIOCSETD, &ld);
		if (!fork()) {
			usleep(200000);
			ld = N_TTY;
			ioctl(fd2, TIOCSETD, &ld);
			_exit(0);
		}
		t0 = now_s();
		ret = read(fd, buf, sizeof(buf));
		err = errno;
		wait(NULL);
		tap_ok(now_s() - t0 < 8 && ld == N_RS485_DEFAULT_LDISC,
		       "a blocked read() returns when another process detaches (ret %d, %s)", ret,
		       ret < 0 ? strerror(err) : "-");
	}
	close(fd2);

	{
		int ld = N_RS485_DEFAULT_LDISC;

		ioctl(fd, TIOCSETD, &ld);
	}
	pending_vs(fd, "hangup (TIOCVHANGUP)", do_hangup);
	ret = xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, d, 4, 10000000, 0);
	tap_ok(ret == -1, "the hung-up file gives errors (%s)", strerror(errno));
	close(fd);

	/* a new open works again */
	fd = bus_open(PORT);
	ret = xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, d, 4, 10000000, 0);
	tap_ok(fd >= 0 && ret == 0 && x.status == N_RS485_OK, "reopen + attach after hangup works");
	/* close with a transaction pending in another thread is the test's exit */
	slave_stop(&s);
	close(fd);
	sim_unload();
	return tap_finish();
}
