// SPDX-License-Identifier: GPL-2.0
/*
 * unbind-poll: unbinding the DIO gpiochip while its edge poll is at work
 * (issue 18 item 13). The poll work must be stopped before the gpiochip and
 * its interrupt domain go away; it used to be cancelled only afterwards, so
 * a poll still running looked up the line's interrupt in the freed domain
 * (KASAN: use-after-free; the stock kernel: NULL dereference in
 * handle_nested_irq).
 *
 * A poll runs every few milliseconds and the window is a few microseconds,
 * so the test makes it deterministic with the simulator: it holds the
 * poll's read of the input register (debugfs dio/in_hold), changes the
 * level the held read will return, and unbinds. The unbind must wait for
 * the held poll in ts7800_dio_stop_poll() while the gpiochip is still
 * registered. The monitor's line is released while the unbind waits,
 * before the poll is let go: 6.1's gpiolib frees the interrupt descriptors of a
 * removed chip under a still requested interrupt (leaking its irqaction and
 * warning about its /proc entry, fixed upstream in 6.10), which is not the
 * driver's defect. On the old code the held poll then still finds the edge
 * enabled (the chip's removal does not mask it) and dispatches it through
 * the freed domain; on the fixed code polling has stopped for good and the
 * poll ends quietly. The harness fails the program on the kernel report.
 */
#define _GNU_SOURCE
#include <dirent.h>
#include <fcntl.h>
#include <linux/gpio.h>
#include <poll.h>
#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <unistd.h>

#include "tap.h"
#include "vmtest.h"

#define DRV_DIR		"/sys/bus/platform/drivers/ts7800-dio"
#define DEV_NAME	"ts7800-dio"
#define DEV_DIR		"/sys/bus/platform/devices/" DEV_NAME
#define DIO_FS		"/sys/kernel/debug/ts7800-sim/dio"
#define TIMER_MIGRATION	"/proc/sys/kernel/timer_migration"
/* Longest hold of the poll's read (ms): the simulator busy-waits that long. */
#define HOLD_MS		5000
/* Deadline for the unbind to reach the poll's cancel (s), inside HOLD_MS. */
#define UNBIND_WAIT_S	3.5

enum { HOLD_OFF, HOLD_ARMED, HOLD_HOLDING, HOLD_EXPIRED };	/* sim_dio_hold */

static int write_str(const char *path, const char *val)
{
	int fd = open(path, O_WRONLY);
	ssize_t n;

	if (fd < 0)
		return -1;
	n = write(fd, val, strlen(val));
	close(fd);
	return n == (ssize_t)strlen(val) ? 0 : -1;
}

static long read_long(const char *path)
{
	char buf[32] = "";
	int fd = open(path, O_RDONLY);
	ssize_t n;

	if (fd < 0)
		return -1;
	n = read(fd, buf, sizeof(buf) - 1);
	close(fd);
	return n > 0 ? strtol(buf, NULL, 0) : -1;
}

/* The gpiochipN device of the bound DIO header, or -1. */
static int dio_chip(void)
{
	struct dirent *e;
	int chip = -1;
	DIR *d = opendir(DEV_DIR);

	if (!d)
		return -1;
	while ((e = readdir(d)))
		if (!strncmp(e->d_name, "gpiochip", 8))
			chip = atoi(e->d_name + 8);
	closedir(d);
	return chip;
}

static int wait_chip(void)
{
	double end = now_s() + 5;
	char path[64];
	int chip;

	do {
		chip = dio_chip();
		snprintf(path, sizeof(path), "/dev/gpiochip%d", chip);
		if (chip >= 0 && !access(path, R_OK))
			return chip;
		usleep(10000);
	} while (now_s() < end);
	return -1;
}

/* A line request with both edges on @offset; returns the line fd or -1. */
static int request_edges(int chip, unsigned int offset)
{
	struct gpio_v2_line_request req;
	char path[64];
	int fd, ret;

	snprintf(path, sizeof(path), "/dev/gpiochip%d", chip);
	fd = open(path, O_RDONLY);
	if (fd < 0)
		return -1;
	memset(&req, 0, sizeof(req));
	req.offsets[0] = offset;
	req.num_lines = 1;
	req.config.flags = GPIO_V2_LINE_FLAG_INPUT | GPIO_V2_LINE_FLAG_EDGE_RISING |
			   GPIO_V2_LINE_FLAG_EDGE_FALLING;
	/*
	 * No consumer name: on the old code the chip goes away under this
	 * request, and a named one adds gpiolib's /proc warning to the report.
	 */
	ret = ioctl(fd, GPIO_V2_GET_LINE_IOCTL, &req);
	close(fd);
	return ret ? -1 : req.fd;
}

/* The next edge event on @line within 5 s: its id (GPIO_V2_LINE_EVENT_*) or -1. */
static int next_event(int line)
{
	struct gpio_v2_line_event ev;
	struct pollfd p = { .fd = line, .events = POLLIN };

	if (poll(&p, 1, 5000) != 1 || read(line, &ev, sizeof(ev)) != sizeof(ev))
		return -1;
	return ev.id;
}

static bool wait_hold(long state, double secs)
{
	double end = now_s() + secs;

	do {
		if (read_long(DIO_FS "/in_hold") == state)
			return true;
		usleep(1000);
	} while (now_s() < end);
	return false;
}

struct unbinder {
	pthread_t thread;
	bool started;
	int go[2];		/* pipe: a byte starts the unbind */
	atomic_int tid;
	atomic_int result;	/* 1 running, 0 done, -1 failed */
};

/*
 * Started before a read is held: while a CPU spins with interrupts off,
 * creating a thread (mmap, mprotect: TLB shootdowns) can wait for it.
 */
static void *unbind_thread(void *arg)
{
	struct unbinder *u = arg;
	char c;

	u->tid = gettid();
	if (read(u->go[0], &c, 1) != 1) {
		u->result = -1;
		return NULL;
	}
	u->result = write_str(DRV_DIR "/unbind", DEV_NAME);
	return NULL;
}

/*
 * While a CPU spins with interrupts off, nothing may wait for a device
 * interrupt that may be routed to it: no TAP output to the results share
 * (virtio-9p) and no page faults on the program's files (9p too). So the
 * output goes to a tmpfs file until the read is let go, and every page is
 * faulted in and locked first.
 */
static int quiet_begin(void)
{
	char path[256];
	int saved, fd;

	snprintf(path, sizeof(path), "%s/held.out", getenv("VMTEST_SCRATCH") ?: "/tmp");
	fflush(stdout);
	saved = dup(1);
	fd = open(path, O_RDWR | O_CREAT | O_TRUNC, 0600);
	if (saved < 0 || fd < 0 || dup2(fd, 1) < 0)
		tap_bail("cannot divert the output to %s", path);
	close(fd);
	if (mlockall(MCL_CURRENT))
		tap_diag("mlockall failed: a page fault may wait for the held CPU");
	return saved;
}

static void quiet_end(int saved)
{
	char buf[4096];
	ssize_t n;

	fflush(stdout);
	lseek(1, 0, SEEK_SET);
	while ((n = read(1, buf, sizeof(buf))) > 0)
		if (write(saved, buf, n) != n)
			break;
	dup2(saved, 1);
	close(saved);
	munlockall();
}

/*
 * Threads on @cpu. The poll work runs on the CPU that started it (the
 * request's, with timer migration off), so the test requests the line on
 * CPU 1 and waits on CPU 0: a sleeper whose timer is on the held CPU would
 * not wake up before the hold ends.
 */
static bool pin(pid_t tid, int cpu)
{
	cpu_set_t set;

	CPU_ZERO(&set);
	CPU_SET(cpu, &set);
	return !sched_setaffinity(tid, sizeof(set), &set);
}

/* Whether task @tid's kernel stack holds @fn: where a blocked write waits. */
static bool stack_has(pid_t tid, const char *fn)
{
	char path[64], buf[4096];
	ssize_t n;
	int fd;

	snprintf(path, sizeof(path), "/proc/self/task/%d/stack", tid);
	fd = open(path, O_RDONLY);
	if (fd < 0)
		return false;
	n = read(fd, buf, sizeof(buf) - 1);
	close(fd);
	if (n <= 0)
		return false;
	buf[n] = '\0';
	return strstr(buf, fn);
}

/* The unbind thread's kernel stack as diagnostics (no fork: a CPU is held). */
static void show_stack(pid_t tid)
{
	char path[64], buf[4096], *line, *save;
	ssize_t n;
	int fd;

	snprintf(path, sizeof(path), "/proc/self/task/%d/stack", tid);
	fd = open(path, O_RDONLY);
	n = fd < 0 ? -1 : read(fd, buf, sizeof(buf) - 1);
	if (fd >= 0)
		close(fd);
	if (n <= 0) {
		tap_diag("no kernel stack of the unbind thread");
		return;
	}
	buf[n] = '\0';
	for (line = strtok_r(buf, "\n", &save); line; line = strtok_r(NULL, "\n", &save))
		tap_diag("unbind stack: %s", line);
}

int main(void)
{
	struct unbinder u = { .result = 1 };
	unsigned int pause_off;
	char path[64];
	bool waiting = false, ordered = false, sent = false;
	long timer_migration = -1;
	int saved_out;
	int chip, line;
	long pause_pin;
	double end;

	/*
	 * The PREEMPT_RT guests have one CPU (vm-x86.sh, vm-debug.sh): the
	 * stock 6.1 lane and the debug lane's second guest run it (settings).
	 */
	if (sysconf(_SC_NPROCESSORS_ONLN) < 2) {
		printf("TAP version 13\n1..0 # SKIP the guest has one CPU: the unbind must run beside the poll\n");
		return 4;	/* guest-run.sh: a skip */
	}
	tap_plan(9);
	sh("mountpoint -q /sys/kernel/debug || mount -t debugfs none /sys/kernel/debug");
	if (sh("modprobe ts7800_dio && modprobe ts7800_sim"))
		tap_bail("cannot load ts7800_dio and ts7800_sim");
	chip = wait_chip();
	if (!tap_ok(chip >= 0, "the simulated FPGA's DIO header is bound (gpiochip%d)", chip))
		goto out;
	pause_pin = read_long(DIO_FS "/pause_pin");
	if (pause_pin < 1)
		tap_bail("cannot read " DIO_FS "/pause_pin");
	pause_off = pause_pin - 1;

	timer_migration = read_long(TIMER_MIGRATION);
	write_str(TIMER_MIGRATION, "0");
	if (!pin(0, 1))
		tap_bail("cannot run on CPU 1 (the guest needs two CPUs)");
	line = request_edges(chip, pause_off);
	if (!tap_ok(line >= 0, "DIO_%ld (PAUSE) requested with both edges", pause_pin))
		goto out;
	write_str(DIO_FS "/pause", "1");
	tap_ok(next_event(line) == GPIO_V2_LINE_EVENT_FALLING_EDGE,
	       "PAUSE asserted: a falling edge, so the poll runs");

	if (pipe(u.go) || pthread_create(&u.thread, NULL, unbind_thread, &u))
		tap_bail("cannot start the unbind thread");
	u.started = true;
	while (!u.tid)
		usleep(1000);
	if (!pin(0, 0) || !pin(u.tid, 0))
		tap_bail("cannot pin the threads to CPU 0");

	/* Hold the next poll in its register read, with an edge for it to find. */
	saved_out = quiet_begin();
	snprintf(path, sizeof(path), "%d", HOLD_MS);
	write_str(DIO_FS "/in_hold", path);
	if (!tap_ok(wait_hold(HOLD_HOLDING, 2), "a poll is held in its read of the input register")) {
		close(line);
		goto release;
	}
	write_str(DIO_FS "/pause", "0");
	if (write(u.go[1], "u", 1) != 1)
		tap_bail("cannot start the unbind");
	sent = true;
	end = now_s() + UNBIND_WAIT_S;
	/*
	 * ts7800_dio_stop_poll() tail-calls cancel_delayed_work_sync(), so
	 * the stack shows the cancel under devres_release_all(): the only
	 * work the DIO driver's devres cancels is the poll. 6.1 shows it as
	 * __cancel_work_timer, 6.12 as cancel_delayed_work_sync (over
	 * __flush_work).
	 */
	while (!(waiting = u.tid && (stack_has(u.tid, "cancel_work") ||
				     stack_has(u.tid, "cancel_delayed_work")) &&
			   stack_has(u.tid, "devres_release_all")) &&
	       u.result == 1 && now_s() < end)
		usleep(2000);
	if (!tap_ok(waiting, "the unbind waits for the held poll (its cancel, from devres)"))
		show_stack(u.tid);
	snprintf(path, sizeof(path), "/sys/bus/gpio/devices/gpiochip%d", chip);
	ordered = tap_ok(waiting && !access(path, F_OK),
			 "the gpiochip is still registered while the unbind waits for the poll");
	/* The monitor lets go while the poll is still held (see the top). */
	close(line);

release:
	if (u.started && !sent)
		close(u.go[1]);	/* the thread ends without unbinding */
	tap_ok(read_long(DIO_FS "/in_hold") == HOLD_HOLDING,
	       "the held read is let go by the test, not by its %d ms limit", HOLD_MS);
	write_str(DIO_FS "/in_hold", "0");
	quiet_end(saved_out);
	if (!u.started)
		goto out;
	end = now_s() + 20;
	while (u.result == 1 && now_s() < end)
		usleep(10000);
	tap_ok(u.result == 0, "the unbind completes (result %d)", u.result);
	if (u.result != 1)
		pthread_join(u.thread, NULL);
	else
		pthread_detach(u.thread);
	if (!ordered) {
		/* The chip went with a requested line: 6.1 may crash a new one. */
		tap_ok(0, "bound again, the header reports edges (not tried: the chip went with a requested line)");
		goto out;
	}

	/* A new binding polls again: the old one's "stopped for good" is its own. */
	write_str(DRV_DIR "/bind", DEV_NAME);
	chip = wait_chip();
	line = chip >= 0 ? request_edges(chip, pause_off) : -1;
	write_str(DIO_FS "/pause", "1");
	tap_ok(line >= 0 && next_event(line) == GPIO_V2_LINE_EVENT_FALLING_EDGE,
	       "bound again, the header reports edges (gpiochip%d)", chip);
	write_str(DIO_FS "/pause", "0");
	if (line >= 0)
		close(line);
out:
	write_str(DIO_FS "/in_hold", "0");
	if (timer_migration >= 0) {
		snprintf(path, sizeof(path), "%ld", timer_migration);
		write_str(TIMER_MIGRATION, path);
	}
	if (u.started && atomic_load(&u.result) == 1) {
		tap_diag("the unbind is still blocked: modules left loaded");
		return tap_finish();
	}
	sh("modprobe -r ts7800_sim; modprobe -r ts7800_dio ts_uart ts7800_fpga");
	return tap_finish();
}
