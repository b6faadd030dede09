// SPDX-License-Identifier: GPL-2.0
/*
 * serialcore - what serial_core and user space are told about a TS-UART:
 * the port type (TIOCGSERIAL, sysfs), the termios really applied (CSTOPB),
 * the transmitter-empty state (TIOCSERGETLSR, which tcdrain and close rely
 * on), interrupts that find nothing to do (IRQ_NONE for the spurious-IRQ
 * detector) and RS-485 direction control on RTS (TIOCSRS485).
 */
#include <sys/ioctl.h>

#include "tsuart-lib.h"

/* Mainline's PORT_8250; the driver must not pose as one. */
#define TYPE_8250	1

static void port_type(void)
{
	struct serial_struct ser;
	char buf[32] = "";
	int fd = tty_open(0, B115200, 0, 0), ret;
	FILE *f;

	memset(&ser, 0, sizeof(ser));
	ret = ioctl(fd, TIOCGSERIAL, &ser);
	tap_ok(ret == 0 && ser.type != TYPE_8250 && ser.type != PORT_UNKNOWN,
	       "TIOCGSERIAL: type %d is neither PORT_8250 nor PORT_UNKNOWN", ser.type);
	f = fopen("/sys/class/tty/ttyTSU0/type", "r");
	if (f) {
		if (!fgets(buf, sizeof(buf), f))
			buf[0] = 0;
		fclose(f);
	}
	tap_ok(atoi(buf) == ser.type, "sysfs type %d is the same", atoi(buf));
	tap_ok(sh("grep -q '^0: uart:TS-UART ' /proc/tty/driver/ts-uart") == 0,
	       "/proc/tty/driver/ts-uart names it TS-UART");
	if (fd >= 0)
		close(fd);
}

/* 8 data bits + parity fill the 9-bit character: no room for a 2nd stop bit. */
static void cstopb(void)
{
	int fd = tty_open(1, B115200, PARENB | CSTOPB, 0);
	struct termios t;

	tap_ok(fd >= 0 && tcgetattr(fd, &t) == 0 && !(t.c_cflag & CSTOPB) &&
	       (t.c_cflag & PARENB),
	       "8E2 is reported back as 8E1 (the second stop bit cannot be sent)");
	if (fd >= 0) {
		t.c_cflag = (t.c_cflag & ~(CSIZE | PARENB)) | CS8 | CSTOPB;
		tap_ok(tcsetattr(fd, TCSANOW, &t) == 0 && tcgetattr(fd, &t) == 0 &&
		       (t.c_cflag & CSTOPB), "8N2 keeps CSTOPB (sent in the 9th bit)");
		close(fd);
	} else {
		tap_ok(0, "8N2 keeps CSTOPB (sent in the 9th bit)");
	}
}

/* Wait until the wire got no new character for quiet_s; returns the count. */
static uint64_t wire_settle(int wfd, double quiet_s, double timeout_s)
{
	struct ts7800_sim_wire_stats st;
	double end = now_s() + timeout_s, since = now_s();
	uint64_t last = ~0ULL;

	while (now_s() < end) {
		if (wire_stats(wfd, &st))
			return ~0ULL;
		if (st.to_wire != last) {
			last = st.to_wire;
			since = now_s();
		} else if (now_s() - since >= quiet_s) {
			break;
		}
		usleep(2000);
	}
	return last;
}

/*
 * With interrupts held the FIFO runs dry while the tty still has characters:
 * TIOCSERGETLSR (serial_core's tx_empty()) then moves the rest into the FIFO
 * and must not report the transmitter empty. 24 characters: the 16-deep FIFO
 * and the shift register take 17 at once, the other 7 fit into the FIFO in
 * that one call, so serial_core sees no characters left in its buffer (with
 * some left it clears TEMT itself and hides the driver's answer).
 */
static void tx_empty(void)
{
	int fd = tty_open(2, B9600, 0, 0), wfd = wire_open(2, O_NONBLOCK), ret;
	uint8_t msg[24];
	uint16_t w[24];
	unsigned int lsr = 0;
	uint64_t sent;
	size_t n;

	memset(msg, 'x', sizeof(msg));
	debugfs_write(-1, "irq_hold", 1);
	tty_write_all(fd, msg, sizeof(msg));
	/* 1.1 ms a character: quiet for 20 characters means the FIFO is empty. */
	sent = wire_settle(wfd, 0.025, 5);
	tap_diag("with interrupts held the FIFO sent %llu characters", (unsigned long long)sent);
	ret = ioctl(fd, TIOCSERGETLSR, &lsr);
	tap_ok(ret == 0 && !(lsr & TIOCSER_TEMT) && sent < sizeof(msg),
	       "TIOCSERGETLSR that queues characters does not report the transmitter empty (lsr %u)",
	       lsr);
	debugfs_write(-1, "irq_hold", 0);
	n = wire_read_n(wfd, w, sizeof(msg), 3, NULL);
	tcdrain(fd);
	lsr = 0;
	ret = ioctl(fd, TIOCSERGETLSR, &lsr);
	tap_ok(n == sizeof(msg) && ret == 0 && (lsr & TIOCSER_TEMT),
	       "after all %zu characters are out it does", n);
	close(fd);
	close(wfd);
}

/* "unhandled" of /proc/irq/N/spurious, or -1. */
static long irq_unhandled(int irq)
{
	char path[64], key[32];
	long val = -1, v;
	FILE *f;

	snprintf(path, sizeof(path), "/proc/irq/%d/spurious", irq);
	f = fopen(path, "r");
	if (!f)
		return -1;
	while (fscanf(f, "%31s %ld%*[^\n]", key, &v) == 2)
		if (!strcmp(key, "unhandled"))
			val = v;
	fclose(f);
	return val;
}

/* The line's hard interrupts so far (/proc/interrupts, every CPU), or -1. */
static long irq_hard_count(int irq)
{
	char line[512], *p, *q;
	long sum = -1, v;
	FILE *f = fopen("/proc/interrupts", "r");

	if (!f)
		return -1;
	while (sum < 0 && fgets(line, sizeof(line), f)) {
		v = strtol(line, &p, 10);
		if (p == line || *p != ':' || v != irq)
			continue;
		for (sum = 0, p++;; p = q) {
			v = strtol(p, &q, 10);
			if (q == p)
				break;
			sum += v;
		}
	}
	fclose(f);
	return sum;
}

/* voluntary_ctxt_switches of a task: it went to sleep that often. */
static long task_sleeps(int pid)
{
	char path[64], line[128];
	long v = -1;
	FILE *f;

	snprintf(path, sizeof(path), "/proc/%d/status", pid);
	f = fopen(path, "r");
	if (!f)
		return -1;
	while (fgets(line, sizeof(line), f))
		if (sscanf(line, "voluntary_ctxt_switches: %ld", &v) == 1)
			break;
	fclose(f);
	return v;
}

static void irq_none(void)
{
	int fd = tty_open(3, B115200, 0, 0);
	long before, after = -1, hard, sleeps;
	struct serial_struct ser;
	int i, thread, want, raised = 0;
	double end;

	memset(&ser, 0, sizeof(ser));
	ioctl(fd, TIOCGSERIAL, &ser);
	/*
	 * A threaded handler's result is accounted at the line's next hard
	 * interrupt (note_interrupt(), SPURIOUS_DEFERRED): the last of the 20
	 * stays pending. IRQ_HANDLED for all of them counts none either way.
	 * One at a time, each handled before the next is raised: raised while
	 * the thread runs (IRQF_ONESHOT keeps the line masked), they would
	 * merge into fewer hard interrupts.
	 */
	thread = tty_irq_thread(fd);
	want = thread ? 19 : 20;
	before = irq_unhandled(ser.irq);
	for (i = 0; i < 20; i++) {
		hard = irq_hard_count(ser.irq);
		sleeps = thread ? task_sleeps(thread) : 0;
		debugfs_write(-1, "irq_raise", 16 + 3);	/* TS-UART 3's source */
		/* Delivered through irq_work, then the thread: up to 2 s. */
		for (end = now_s() + 2; now_s() < end; usleep(1000))
			if (irq_hard_count(ser.irq) > hard &&
			    (!thread || task_sleeps(thread) > sleeps))
				break;
		raised += now_s() < end;
	}
	for (end = now_s() + 2; now_s() < end; usleep(10000)) {
		after = irq_unhandled(ser.irq);
		if (after >= before + want)
			break;
	}
	tap_ok(before >= 0 && raised == 20 && after >= before + want,
	       "20 interrupts with nothing pending are reported unhandled (IRQ_NONE): %ld -> %ld (%s handler: %d or more; %d of 20 seen handled)",
	       before, after, thread ? "threaded" : "hard irq", want, raised);
	close(fd);
}

static int rts_of(int wfd)
{
	struct ts7800_sim_wire_stats st;

	if (wire_stats(wfd, &st))
		return -1;
	return !!(st.ctrl & 0x0010);	/* STAT RTS */
}

/*
 * RS-485 on RTS: while characters go out RTS is at its "send" level, after
 * the last stop bit at its "after send" level. Sampled from the simulator's
 * view of STAT while 40 characters take 183 ms at 2400 Bd.
 */
static void rs485_dir(unsigned int flags, int on_level, const char *what)
{
	int fd = tty_open(4, B2400, 0, 0), wfd = wire_open(4, O_NONBLOCK);
	struct serial_rs485 r = { .flags = SER_RS485_ENABLED | flags };
	int idle_before, during = -1, after = -1, mixed = 0, rts, ret;
	uint8_t msg[40];
	uint16_t w[40];
	double end;
	size_t n;

	memset(msg, 'r', sizeof(msg));
	ret = ioctl(fd, TIOCSRS485, &r);
	tap_ok(fd >= 0 && ret == 0 && (r.flags & SER_RS485_ENABLED),
	       "%s: TIOCSRS485 accepted (flags 0x%x)", what, r.flags);
	idle_before = rts_of(wfd);
	tty_write_all(fd, msg, sizeof(msg));
	n = 0;
	for (end = now_s() + 5; now_s() < end && n < sizeof(msg);) {
		ssize_t got = read(wfd, w, sizeof(w));

		if (got > 0)
			n += got / 2;
		rts = rts_of(wfd);
		if (n > 0 && n < sizeof(msg) - 1) {
			if (during < 0)
				during = rts;
			else if (rts != during)
				mixed = 1;
		}
		usleep(1000);
	}
	/* After the last stop bit: RTS must return within 50 ms (12 characters). */
	for (end = now_s() + 0.05; now_s() < end; usleep(1000)) {
		after = rts_of(wfd);
		if (after == !on_level)
			break;
	}
	tap_ok(idle_before == !on_level, "%s: RTS idle level before sending (%d)", what, idle_before);
	tap_ok(n == sizeof(msg) && during == on_level && !mixed,
	       "%s: RTS %d during the whole transmission (got %d%s, %zu chars)", what, on_level,
	       during, mixed ? ", changing" : "", n);
	tap_ok(after == !on_level, "%s: RTS back to %d after the last character (%d)", what,
	       !on_level, after);
	r.flags = 0;
	ioctl(fd, TIOCSRS485, &r);
	close(fd);
	close(wfd);
}

static void rs485_flags(void)
{
	int fd = tty_open(5, B115200, 0, 0), wfd = wire_open(5, O_NONBLOCK);
	struct serial_rs485 r = { .flags = SER_RS485_ENABLED | SER_RS485_RTS_ON_SEND };
	struct serial_rs485 g = { 0 };
	int mctrl = TIOCM_RTS, ret;

	ret = ioctl(fd, TIOCSRS485, &r) || ioctl(fd, TIOCGRS485, &g);
	tap_ok(!ret && (g.flags & SER_RS485_RX_DURING_TX),
	       "TIOCGRS485 reports RX_DURING_TX: the receiver is never switched off (0x%x)", g.flags);
	r.flags = 0;
	ioctl(fd, TIOCSRS485, &r);
	ioctl(fd, TIOCMBIS, &mctrl);
	tap_ok(rts_of(wfd) == 1, "RS-485 off again: TIOCMBIS RTS drives RTS");
	ioctl(fd, TIOCMBIC, &mctrl);
	tap_ok(rts_of(wfd) == 0, "and TIOCMBIC clears it");
	close(fd);
	close(wfd);
}

int main(void)
{
	tap_plan(21);
	if (!tap_ok(sim_load("") == 0, "load ts_uart and ts7800_sim"))
		tap_bail("cannot continue without the simulator");
	port_type();
	cstopb();
	tx_empty();
	irq_none();
	rs485_dir(SER_RS485_RTS_ON_SEND, 1, "RTS_ON_SEND");
	rs485_dir(SER_RS485_RTS_AFTER_SEND, 0, "RTS_AFTER_SEND");
	rs485_flags();
	tap_ok(sim_unload() == 0, "unload");
	return tap_finish();
}
