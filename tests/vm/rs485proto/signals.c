// SPDX-License-Identifier: GPL-2.0
/*
 * signals - a signal never makes the kernel send a request twice (issue 18,
 * item 1). A child process runs transactions of I_COUNT (the slave counts
 * every execution; retries 0, so the kernel has no reason of its own to send
 * a request twice) while the parent disturbs it at random times:
 *
 *   restart    SIGUSR1 with an SA_RESTART handler (what glibc's signal() sets)
 *   norestart  SIGUSR1 with a handler without SA_RESTART
 *   stopcont   SIGSTOP, a random pause, SIGCONT
 *   ptrace     PTRACE_ATTACH, wait for the stop, PTRACE_DETACH (strace -p)
 *
 * A thread of the parent keeps the bus busy meanwhile, so the child's
 * requests are sometimes still queued (withdrawable) and sometimes on the
 * bus when the disturbance comes. The contract: the slave executed exactly
 * one request per transaction that returned 0 or EINTR (a call restarted by
 * the kernel was withdrawn before it went out, so it counts once); with
 * norestart, EINTR may also come from a withdrawn request, so there
 * executions are at least the successes and at most successes + EINTR.
 *
 * The number of transactions over all four modes is RS485_SIGNAL_XFERS
 * (environment) or rs485_signal_xfers=N on the kernel command line
 * (VMTEST_APPEND); by default 2000 on the debug kernel and 1000 elsewhere
 * (2000 take about 110 s under KASAN/lockdep, a fifth of the CI budget of the
 * debug lane; the 10000-transaction acceptance run is
 * `make check TEST=rs485proto/signals VMTEST_LANES=debug
 * VMTEST_APPEND=rs485_signal_xfers=10000`). The time is reported.
 */
#include <signal.h>
#include <sys/ptrace.h>
#include <sys/utsname.h>

#include "rs485-lib.h"

#define PORT		0
#define XFER_TIMEOUT_US	2000000
#define HOG_INSTR	I_ECHO

enum mode { M_RESTART, M_NORESTART, M_STOPCONT, M_PTRACE, M_NR };

static const char *const mode_name[M_NR] = { "restart", "norestart", "stopcont", "ptrace" };

struct tally {
	unsigned int ok, timeout, eintr, other, signals;
	int last_errno;
	double seconds;
};

static volatile sig_atomic_t handled;

static void on_usr1(int sig)
{
	(void)sig;
	handled++;
}

/* rs485_signal_xfers=N on the kernel command line (VMTEST_APPEND), or "". */
static const char *xfers_from_cmdline(char *buf, size_t size)
{
	FILE *f = fopen("/proc/cmdline", "r");
	char *p = NULL;

	buf[0] = 0;
	if (f && fgets(buf, size, f))
		p = strstr(buf, "rs485_signal_xfers=");
	if (f)
		fclose(f);
	if (!p)
		return "";
	p += strlen("rs485_signal_xfers=");
	p[strcspn(p, " \n")] = 0;
	return p;
}

static unsigned int xfers_from_env(void)
{
	const char *s = getenv("RS485_SIGNAL_XFERS");
	struct utsname u;
	unsigned long v;
	char cmdline[4096];
	char *end;

	if (!s || !*s)
		s = xfers_from_cmdline(cmdline, sizeof(cmdline));
	if (*s) {
		v = strtoul(s, &end, 10);
		if (*end || v < M_NR || v > 10000000)
			tap_bail("transaction count %s: want 4..10000000", s);
		return v;
	}
	if (!uname(&u) && strstr(u.release, "advee-debug"))
		return 2000;
	return 1000;
}

/* The child: n transactions, the tally to @out. */
static void child_run(int fd, unsigned int n, int out)
{
	struct tally t = { 0 };
	struct n_rs485_xfer x;
	unsigned int i;
	double t0 = now_s();
	int ret;

	for (i = 0; i < n; i++) {
		ret = xfer(fd, &x, SLAVE_ADDR, I_COUNT, 0, NULL, 0, XFER_TIMEOUT_US, 0);
		if (ret == 0 && x.status == N_RS485_OK)
			t.ok++;
		else if (ret == 0 && x.status == N_RS485_TIMEOUT)
			t.timeout++;
		else if (ret == -1 && errno == EINTR)
			t.eintr++;
		else {
			t.other++;
			t.last_errno = ret ? errno : -(int)x.status;
		}
	}
	t.signals = handled;
	t.seconds = now_s() - t0;
	if (write(out, &t, sizeof(t)) != sizeof(t))
		_exit(2);
	_exit(0);
}

/* A random pause of 0..max_us. */
static void pause_random(unsigned int max_us)
{
	usleep(max_us ? (unsigned int)rand() % (max_us + 1) : 0);
}

struct hog {
	int fd;
	unsigned int max_us;		/* pause between two transactions */
	atomic_int stop;
	unsigned int done, bad;
	pthread_t thread;
};

static void *hog_main(void *arg)
{
	struct hog *h = arg;
	struct n_rs485_xfer x;

	while (!h->stop) {
		/* Often enough that the child's request is sometimes queued. */
		pause_random(h->max_us);
		if (xfer(h->fd, &x, SLAVE_ADDR, HOG_INSTR, 0, "hog", 3, XFER_TIMEOUT_US, 0) ||
		    x.status != N_RS485_OK)
			h->bad++;
		h->done++;
	}
	return NULL;
}

/*
 * One disturbance of the child; returns 1 if it was delivered, 0 if not,
 * -1 if the child ended meanwhile and this reaped it (its status in @st).
 */
static int disturb(pid_t pid, enum mode m, unsigned int max_us, int *st)
{
	switch (m) {
	case M_RESTART:
	case M_NORESTART:
		return kill(pid, SIGUSR1) == 0;
	case M_STOPCONT:
		if (kill(pid, SIGSTOP))
			return 0;
		pause_random(max_us / 4);
		kill(pid, SIGCONT);
		return 1;
	case M_PTRACE:
		if (ptrace(PTRACE_ATTACH, pid, NULL, NULL))
			return 0;
		if (waitpid(pid, st, __WALL) != pid)
			return 0;
		if (!WIFSTOPPED(*st))
			return -1;
		ptrace(PTRACE_DETACH, pid, NULL, NULL);
		return 1;
	default:
		return 0;
	}
}

/* Mean time of one undisturbed transaction while the hog runs, in us. */
static unsigned int calibrate(int fd)
{
	struct n_rs485_xfer x;
	double t0 = now_s();
	int i;

	for (i = 0; i < 50; i++)
		xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, NULL, 0, XFER_TIMEOUT_US, 0);
	return (now_s() - t0) / 50 * 1e6;
}

static void run_mode(int fd, struct slave *s, enum mode m, unsigned int n, unsigned int max_us)
{
	unsigned int e0 = s->executions[I_COUNT], executed, sent = 0, delivered = 0;
	struct n_rs485_xfer x;
	struct sigaction sa = { .sa_handler = on_usr1 };
	struct tally t = { 0 };
	int pfd[2], st;
	pid_t pid;
	ssize_t r;

	if (pipe(pfd))
		tap_bail("pipe");
	/*
	 * The child inherits the handler: installed by the child itself, a
	 * SIGUSR1 sent before it got that far would kill it (the default
	 * action), which a slow fork under load made happen on CI.
	 */
	sigemptyset(&sa.sa_mask);
	sa.sa_flags = m == M_NORESTART ? 0 : SA_RESTART;
	if (sigaction(SIGUSR1, &sa, NULL))
		tap_bail("sigaction");
	handled = 0;
	pid = fork();
	if (pid < 0)
		tap_bail("fork");
	if (!pid) {
		close(pfd[0]);
		child_run(fd, n, pfd[1]);
	}
	close(pfd[1]);
	for (;;) {
		int ret;

		pause_random(max_us);
		if (waitpid(pid, &st, WNOHANG) == pid)
			break;
		sent++;
		ret = disturb(pid, m, max_us, &st);
		if (ret < 0)
			break;	/* reaped by the ptrace wait: polling again would never end */
		delivered += ret;
	}
	r = read(pfd[0], &t, sizeof(t));
	close(pfd[0]);
	/* FIFO bus: once this is answered, every request of the child was. */
	xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, NULL, 0, XFER_TIMEOUT_US, 0);
	executed = s->executions[I_COUNT] - e0;

	tap_diag("%s: %u transactions in %.1f s: %u ok, %u timeout, %u EINTR, %u other (errno/status %d); "
		 "%u disturbances (%u delivered, %u handled); slave executed %u",
		 mode_name[m], n, t.seconds, t.ok, t.timeout, t.eintr, t.other, t.last_errno, sent,
		 delivered, t.signals, executed);
	if (r != sizeof(t) || !WIFEXITED(st) || WEXITSTATUS(st)) {
		tap_ok(0, "%s: the child finished its %u transactions (%s %d)", mode_name[m], n,
		       WIFSIGNALED(st) ? "killed by signal" : "exit status",
		       WIFSIGNALED(st) ? WTERMSIG(st) : WEXITSTATUS(st));
		return;
	}
	tap_ok(t.other == 0 && t.ok + t.timeout + t.eintr == n,
	       "%s: every call ends in OK, TIMEOUT or EINTR (%u other)", mode_name[m], t.other);
	if (m == M_NORESTART)
		tap_ok(executed >= t.ok && executed <= t.ok + t.timeout + t.eintr,
		       "%s: at most one execution per call (%u executions, %u ok, %u EINTR)",
		       mode_name[m], executed, t.ok, t.eintr);
	else
		tap_ok(executed == t.ok + t.timeout + t.eintr,
		       "%s: exactly one execution per call (%u executions for %u ok + %u timeout + %u EINTR)",
		       mode_name[m], executed, t.ok, t.timeout, t.eintr);
}

int main(void)
{
	unsigned int n = xfers_from_env(), max_us;
	struct n_rs485_stats st;
	struct slave s;
	struct hog h = { 0 };
	double t0;
	int m;

	tap_plan(2 * M_NR + 3);
	if (sim_load())
		tap_bail("cannot load ts_uart + ts7800_sim");
	h.fd = bus_open(PORT);
	if (h.fd < 0)
		tap_bail("attach n_rs485 to /dev/ttyTSU%d", PORT);
	if (slave_start(&s, PORT))
		tap_bail("slave on the wire");
	srand(1);
	if (pthread_create(&h.thread, NULL, hog_main, &h))
		tap_bail("hog thread");
	/* Disturb at random times within about two transactions. */
	max_us = 2 * calibrate(h.fd);
	h.max_us = max_us / 2;
	tap_diag("%u transactions, one disturbance every 0..%u us", n, max_us);

	t0 = now_s();
	for (m = 0; m < M_NR; m++)
		run_mode(h.fd, &s, m, n / M_NR, max_us);
	tap_diag("all modes: %.1f s", now_s() - t0);
	h.stop = 1;
	pthread_join(h.thread, NULL);

	tap_ok(h.bad == 0, "the other caller's %u transactions all OK (%u not)", h.done, h.bad);
	if (get_stats(h.fd, &st))
		tap_bail("N_RS485_IOC_GET_STATS");
	tap_ok(st.xfers == st.xfers_ok + st.xfers_failed,
	       "statistics add up: xfers %llu = ok %llu + failed %llu",
	       (unsigned long long)st.xfers, (unsigned long long)st.xfers_ok,
	       (unsigned long long)st.xfers_failed);
	tap_ok(s.bad_frames == 0, "no malformed frame on the wire (%u)", s.bad_frames);
	slave_stop(&s);
	close(h.fd);
	sim_unload();
	return tap_finish();
}
