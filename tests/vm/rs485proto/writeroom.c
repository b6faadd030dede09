// SPDX-License-Identifier: GPL-2.0
/*
 * writeroom - a frame that found the tty's buffer full goes out as soon as
 * the tty has room again (issue 18, item 5).
 *
 * The tty core wakes a writer waiting for room with tty_wakeup() (a UART
 * driver that sent characters, start_tty() after a flow-control stop), and
 * that is wake_up_interruptible(): a discipline sleeping uninterruptibly on
 * write_wait is never woken and waits out its whole 500 ms timeout each time
 * the driver's buffer fills. The test tty /dev/ttyVT0 (tests/kmod/
 * vmtest_tty.c) takes only the characters debugfs vmtest_tty/room allows and
 * calls tty_wakeup() when it is given room.
 *
 * Each round: room 0, one broadcast frame written, the tty seen refusing
 * its first character (vmtest_tty/starved: the worker now waits for room),
 * room given; the time until the frame has gone out is measured. Limits:
 * the median round under 250 ms, half of what a missed wakeup costs (the
 * rest of the 500 ms wait less the time the test took to see the refusal,
 * reported per round); each frame reaches the tty whole and in order.
 */
#include <stdbool.h>

#include "rs485-lib.h"

#define ROUNDS		10
#define DATA_LEN	16
#define FRAME_LEN	(N_RS485_HEADER_LEN + DATA_LEN)
#define LIMIT_S		0.25
#define DEADLINE_S	20.0
#define ROOM		"/sys/kernel/debug/vmtest_tty/room"
#define SENT		"/sys/kernel/debug/vmtest_tty/sent"
#define STARVED		"/sys/kernel/debug/vmtest_tty/starved"

static int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return (x > y) - (x < y);
}

static uint64_t tx_frames(int fd)
{
	struct n_rs485_stats st;

	if (get_stats(fd, &st))
		tap_bail("N_RS485_IOC_GET_STATS: %s", strerror(errno));
	return st.tx_frames;
}

static void set_room(unsigned int room)
{
	char buf[16];
	int fd = open(ROOM, O_WRONLY), len;

	len = snprintf(buf, sizeof(buf), "%u", room);
	if (fd < 0 || write(fd, buf, len) != len)
		tap_bail("cannot set the room of /dev/ttyVT0 (%s): %s", ROOM, strerror(errno));
	close(fd);
}

/* How many writes found the tty without room. */
static unsigned long starved(void)
{
	FILE *f = fopen(STARVED, "r");
	unsigned long n = 0;

	if (!f || fscanf(f, "%lu", &n) != 1)
		tap_bail("cannot read %s", STARVED);
	fclose(f);
	return n;
}

/* Read exactly @len bytes the tty was sent, within DEADLINE_S. */
static bool read_sent(uint8_t *buf, size_t len)
{
	double end = now_s() + DEADLINE_S;
	size_t got = 0;
	int fd = open(SENT, O_RDONLY);

	while (fd >= 0 && got < len && now_s() < end) {
		ssize_t n = read(fd, buf + got, len - got);

		if (n < 0)
			break;
		got += n;
		if (!n)
			usleep(1000);
	}
	if (fd >= 0)
		close(fd);
	return got == len;
}

int main(void)
{
	int ld = N_RS485_DEFAULT_LDISC, fd;
	double lat[ROUNDS], worst_seen = 0;
	unsigned int round, intact = 0, seen = 0;
	uint8_t frame[FRAME_LEN], got[FRAME_LEN + 1];

	tap_plan(3);
	sh("mountpoint -q /sys/kernel/debug || mount -t debugfs none /sys/kernel/debug");
	if (sh("modprobe n_rs485") || sh("modprobe vmtest_tty") || wait_for_path("/dev/ttyVT0"))
		tap_bail("modprobe n_rs485 vmtest_tty");
	fd = open("/dev/ttyVT0", O_RDWR | O_NOCTTY);
	if (fd < 0)
		tap_bail("/dev/ttyVT0: %s", strerror(errno));
	if (ioctl(fd, TIOCSETD, &ld))
		tap_bail("attach n_rs485 to /dev/ttyVT0: %s", strerror(errno));

	for (round = 0; round < ROUNDS; round++) {
		uint64_t before = tx_frames(fd);
		unsigned long refused = starved();
		bool waiting;
		double t0, end, seen_s;

		frame[0] = N_RS485_ADDR_BROADCAST;
		frame[1] = 0x40 + round;
		frame[2] = 0;
		frame[3] = DATA_LEN;
		memset(frame + N_RS485_HEADER_LEN, round, DATA_LEN);
		set_room(0);
		if (write(fd, frame, FRAME_LEN) != FRAME_LEN)
			tap_bail("write of a frame: %s", strerror(errno));
		t0 = now_s();
		end = t0 + DEADLINE_S;
		while (!(waiting = starved() != refused) && now_s() < end)
			usleep(1000);
		seen_s = now_s() - t0;
		if (waiting) {
			seen++;
			if (seen_s > worst_seen)
				worst_seen = seen_s;
		}
		set_room(4 * FRAME_LEN);
		t0 = now_s();
		end = t0 + DEADLINE_S;
		while (tx_frames(fd) == before && now_s() < end)
			usleep(1000);
		lat[round] = now_s() - t0;
		if (read_sent(got, FRAME_LEN + 1) &&
		    !memcmp(got, frame, FRAME_LEN) && got[FRAME_LEN] == crc8_maxim(frame, FRAME_LEN))
			intact++;
		else
			tap_diag("round %u: the tty was not sent the frame whole", round);
		tap_diag("round %u: the tty refused a character after %.1f ms%s; frame out %.1f ms "
			 "after the room", round, seen_s * 1e3, waiting ? "" : " (never)",
			 lat[round] * 1e3);
	}
	tap_ok(seen == ROUNDS, "the bus worker found no room in %u of %u rounds (seen within %.1f ms)",
	       seen, ROUNDS, worst_seen * 1e3);
	tap_ok(intact == ROUNDS, "%u of %u frames reached the tty whole and in order",
	       intact, ROUNDS);
	qsort(lat, ROUNDS, sizeof(lat[0]), cmp_double);
	tap_ok(lat[ROUNDS / 2] < LIMIT_S,
	       "a frame goes out once the tty has room: median %.1f ms after it (limit %.0f ms; "
	       "min %.1f, max %.1f)", lat[ROUNDS / 2] * 1e3, LIMIT_S * 1e3, lat[0] * 1e3,
	       lat[ROUNDS - 1] * 1e3);
	close(fd);
	sh("modprobe -r n_rs485 vmtest_tty");
	return tap_finish();
}
