/* SPDX-License-Identifier: GPL-2.0 */
/*
 * ts7800-wire.h - the far end of a simulated TS-UART's line for the VM
 * tests: the wire /dev/ts7800-sim/uartN (protocol in <linux/ts7800_sim.h>:
 * 16-bit words, one per character) and the simulator's debugfs knobs.
 * Shared by the tsuart and rs485proto suites. Header-only, like tap.h.
 */
#ifndef VMTEST_TS7800_WIRE_H
#define VMTEST_TS7800_WIRE_H

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdint.h>
#include <stdio.h>
#include <sys/ioctl.h>
#include <unistd.h>
#include <linux/ts7800_sim.h>

#define DEBUGFS "/sys/kernel/debug/ts7800-sim"

/* Open the wire of port @port; @flags e.g. O_NONBLOCK. */
static inline int wire_open(int port, int flags)
{
	char path[48];

	snprintf(path, sizeof(path), "/dev/ts7800-sim/uart%d", port);
	return open(path, O_RDWR | flags);
}

/*
 * Write all @n words, waiting for room as needed (blocking or O_NONBLOCK
 * wire); returns 0 or -1 (errno set).
 */
static inline int wire_write_all(int wfd, const uint16_t *w, size_t n)
{
	size_t done = 0;
	ssize_t r;

	while (done < n) {
		r = write(wfd, w + done, (n - done) * 2);
		if (r < 0) {
			if (errno == EINTR)
				continue;
			if (errno == EAGAIN) {
				struct pollfd p = { .fd = wfd, .events = POLLOUT };

				poll(&p, 1, 100);
				continue;
			}
			return -1;
		}
		done += r / 2;
	}
	return 0;
}

static inline int wire_stats(int wfd, struct ts7800_sim_wire_stats *st)
{
	return ioctl(wfd, TS7800_SIM_GET_STATS, st);
}

/* 1: the UART also receives what it transmits (a 2-wire bus), 0: not. */
static inline int wire_reset_stats(int wfd)
{
	return ioctl(wfd, TS7800_SIM_RESET_STATS);
}

static inline int wire_gaps(int wfd, struct ts7800_sim_line_gaps *g)
{
	return ioctl(wfd, TS7800_SIM_GET_GAPS, g);
}

static inline int wire_set_echo(int wfd, int on)
{
	uint32_t v = on;

	return ioctl(wfd, TS7800_SIM_SET_ECHO, &v);
}

/* Line log (TS7800_SIM_SET_LOG): 1 starts it empty, 0 stops it. */
static inline int wire_set_log(int wfd, int on)
{
	uint32_t v = on;

	return ioctl(wfd, TS7800_SIM_SET_LOG, &v);
}

/* Take up to @max logged characters; returns how many, or -1. */
static inline int wire_read_log(int wfd, struct ts7800_sim_line_event *ev, unsigned int max,
				unsigned int *dropped)
{
	struct ts7800_sim_log_read rd = {
		.events = (uintptr_t)ev,
		.max = max,
	};

	if (ioctl(wfd, TS7800_SIM_READ_LOG, &rd))
		return -1;
	if (dropped)
		*dropped += rd.dropped;
	return rd.count;
}

/* Write @val to the simulator's debugfs file @file of port @port (-1: top). */
static inline int debugfs_write(int port, const char *file, long val)
{
	char path[128];
	FILE *f;
	int ret;

	if (port >= 0)
		snprintf(path, sizeof(path), DEBUGFS "/uart%d/%s", port, file);
	else
		snprintf(path, sizeof(path), DEBUGFS "/%s", file);
	f = fopen(path, "w");
	if (!f)
		return -1;
	ret = fprintf(f, "%ld\n", val) < 0;
	return fclose(f) || ret ? -1 : 0;
}

#endif /* VMTEST_TS7800_WIRE_H */
