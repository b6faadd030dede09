// SPDX-License-Identifier: GPL-2.0
/*
 * config - configuration and flushing (issue 18, items 4 and 6):
 *
 *  - N_RS485_IOC_GET_CONFIG answers while a long transaction (3 x 1 s of
 *    timeouts) runs: it does not wait for the worker;
 *  - the bus rate at attach: the protocol's default (115200) on a port at its
 *    driver's initial speed, the port's speed when one was set: by
 *    tcsetattr() before TIOCSETD and by "ldattach -s 57600 29 /dev/ttyTSU0";
 *  - TCIFLUSH drops the frame being received: characters after the flush
 *    cannot complete a frame that began before it;
 *  - loading the module on a line discipline number of another discipline
 *    (ldisc=21, N_GSM0710) fails instead of taking the slot over.
 */
#include <signal.h>

#include "rs485-lib.h"

#define PORT		0
#define LONG_US		300000

struct pending {
	int fd;
	double end;		/* when the transaction returned */
	struct n_rs485_xfer x;
};

static void *pending_main(void *arg)
{
	struct pending *p = arg;

	xfer(p->fd, &p->x, SLAVE_ADDR, I_SILENT, 0, NULL, 0, 1000000, 2);
	p->end = now_s();
	return NULL;
}

/*
 * The transaction takes 3 x 1 s; GET_CONFIG is asked 0.2 s into it. Had it
 * waited for the worker, it would return when the transaction ends: it must
 * return more than one attempt (1 s) before that.
 */
static void get_config_during_xfer(int fd)
{
	struct pending p = { .fd = fd };
	struct n_rs485_config c;
	pthread_t t;
	double t0, t1;
	int ret;

	pthread_create(&t, NULL, pending_main, &p);
	usleep(200000);
	t0 = now_s();
	ret = ioctl(fd, N_RS485_IOC_GET_CONFIG, &c);
	t1 = now_s();
	pthread_join(t, NULL);
	tap_ok(ret == 0 && c.baud == 115200 && p.end - t1 > 1.0,
	       "GET_CONFIG answers while a 3 s transaction runs (in %.3f s, %.3f s before the "
	       "transaction ended)", t1 - t0, p.end - t1);
}

static uint32_t bus_baud(int fd)
{
	struct n_rs485_config c;

	return ioctl(fd, N_RS485_IOC_GET_CONFIG, &c) ? 0 : c.baud;
}

static int port_speed(int fd, speed_t sp)
{
	struct termios t;

	if (tcgetattr(fd, &t))
		return -1;
	cfsetispeed(&t, sp);
	cfsetospeed(&t, sp);
	return tcsetattr(fd, TCSANOW, &t);
}

static void attach_speed(void)
{
	struct termios t;
	struct n_rs485_xfer x;
	int fd, ld = N_TTY, ok;
	pid_t pid;

	fd = bus_open(PORT);
	tap_ok(fd >= 0 && bus_baud(fd) == 115200 && !tcgetattr(fd, &t) &&
	       cfgetospeed(&t) == B115200,
	       "attach to a port at its initial speed: the default 115200 Bd (%u)", bus_baud(fd));
	get_config_during_xfer(fd);

	/* detach, set the port to 57600, attach again */
	ioctl(fd, TIOCSETD, &ld);
	ld = N_RS485_DEFAULT_LDISC;
	ok = !port_speed(fd, B57600) && !ioctl(fd, TIOCSETD, &ld);
	tap_ok(ok && bus_baud(fd) == 57600 && !tcgetattr(fd, &t) && cfgetospeed(&t) == B57600,
	       "attach keeps a speed set before it: 57600 Bd (%u)", bus_baud(fd));
	ok = !xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, "57k6", 4, LONG_US, 0) && x.status == N_RS485_OK;
	tap_ok(ok, "a transaction at 57600 Bd works");
	ld = N_TTY;
	ioctl(fd, TIOCSETD, &ld);
	port_speed(fd, B9600);
	close(fd);

	/* ldattach holds the port open with the discipline attached */
	pid = fork();
	if (!pid) {
		/* its messages are not TAP */
		if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr))
			_exit(126);
		execlp("ldattach", "ldattach", "-d", "-s", "57600", "29", "/dev/ttyTSU0", NULL);
		_exit(127);
	}
	fd = -1;
	for (int i = 0; i < 100 && pid > 0; i++) {
		usleep(50000);
		fd = open("/dev/ttyTSU0", O_RDWR | O_NOCTTY);
		if (fd >= 0 && !ioctl(fd, TIOCGETD, &ld) && ld == N_RS485_DEFAULT_LDISC)
			break;
		if (fd >= 0)
			close(fd);
		fd = -1;
	}
	tap_ok(fd >= 0 && bus_baud(fd) == 57600,
	       "ldattach -s 57600 29 /dev/ttyTSU0: the bus runs at 57600 Bd (%u)",
	       fd >= 0 ? bus_baud(fd) : 0);
	if (fd >= 0)
		close(fd);
	if (pid > 0) {
		kill(pid, SIGTERM);
		waitpid(pid, NULL, 0);
	}
}

/* Wait until the discipline has received @n more characters than @base. */
static int wait_rx_bytes(int fd, uint64_t base, uint64_t n)
{
	struct n_rs485_stats st;
	double end = now_s() + 5;

	do {
		if (get_stats(fd, &st))
			return -1;
		if (st.rx_bytes >= base + n)
			return 0;
		usleep(2000);
	} while (now_s() < end);
	return -1;
}

static void tciflush_resets_rx(struct slave *s)
{
	uint8_t ev[8], buf[N_RS485_MAX_FRAME];
	uint16_t w[9];
	struct n_rs485_stats st;
	struct pollfd p;
	int fd, ok;
	ssize_t n;

	fd = bus_open(PORT);
	if (fd < 0 || get_stats(fd, &st))
		tap_bail("attach for TCIFLUSH");
	/* the first 6 characters of event 1, the flush, then its last 3 */
	frame_words(ev, event_frame(1, ev), 0, w);
	wire_write_all(s->wfd, w, 6);
	ok = !wait_rx_bytes(fd, st.rx_bytes, 6);
	ok = ok && !tcflush(fd, TCIFLUSH);
	wire_write_all(s->wfd, w + 6, 3);
	ok = ok && !wait_rx_bytes(fd, st.rx_bytes, 9);
	/* event 2 whole: the first frame read() returns must be it */
	frame_words(ev, event_frame(2, ev), 0, w);
	wire_write_all(s->wfd, w, 9);
	p = (struct pollfd){ .fd = fd, .events = POLLIN };
	n = poll(&p, 1, 5000) == 1 ? read(fd, buf, sizeof(buf)) : -1;
	tap_ok(ok && n == 8 && !memcmp(buf, ev, 8),
	       "TCIFLUSH drops the frame being received: the next frame read() returns is the "
	       "one sent after the flush (%zd bytes, event %u)", n, n == 8 ? buf[4] : 0);
	close(fd);
}

static void ldisc_slot_taken(void)
{
	FILE *f;
	char line[128];
	int taken = 0, ret;

	sh("modprobe -r n_rs485");
	ret = sh("modprobe n_rs485 ldisc=21 2>/dev/null");
	f = fopen("/proc/tty/ldiscs", "r");
	while (f && fgets(line, sizeof(line), f))
		taken |= !strncmp(line, "n_rs485", 7);
	if (f)
		fclose(f);
	tap_ok(ret != 0 && !taken,
	       "modprobe n_rs485 ldisc=21 (N_GSM0710's number) fails (status %d, registered: %s)",
	       ret, taken ? "yes" : "no");
	sh("modprobe -r n_rs485");
}

int main(void)
{
	struct slave s;

	tap_plan(7);
	if (sim_load())
		tap_bail("cannot load ts_uart + ts7800_sim");
	if (slave_start(&s, PORT))
		tap_bail("slave on the wire");
	attach_speed();
	tciflush_resets_rx(&s);
	slave_stop(&s);
	ldisc_slot_taken();
	sim_unload();
	return tap_finish();
}
