/* SPDX-License-Identifier: GPL-2.0 */
/*
 * rs485-lib.h - helpers of the rs485proto VM tests: the simulated FPGA with
 * its wires, attaching n_rs485 to /dev/ttyTSUn, the protocol's CRC, and a
 * slave that answers on the wire (a thread of the test program). Included
 * by exactly one .c per program.
 */
#ifndef RS485_LIB_H
#define RS485_LIB_H

#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>
#include <linux/n_rs485.h>
#include <linux/ts7800_sim.h>

#include "tap.h"
#include "vmtest.h"
#include "ts7800-wire.h"

/* termios 9-bit addressing (6.0+); glibc's <termios.h> does not have it */
#ifndef ADDRB
#define ADDRB		0x20000000	/* include/uapi/asm-generic/termbits-common.h */
#endif

#define SLAVE_ADDR	0x10
#define OTHER_ADDR	0x11

/* Instructions of the test slave (what it does with a request). */
enum {
	I_ECHO = 0x01,		/* ACK, data = request data */
	I_SILENT = 0x02,	/* never answers */
	I_UNKNOWN = 0x03,	/* UNKINSTR */
	I_DEVERR = 0x04,	/* DEVERR, data 0xde 0xad */
	I_CORRUPT_ONCE = 0x05,	/* first answer has a bad CRC, RESEND gets a good one */
	I_EVENT_FIRST = 0x06,	/* an EVENT frame (same addr/instr) before the answer */
	I_WRONG_ADDR = 0x07,	/* answers from OTHER_ADDR */
	I_CORRUPT = 0x08,	/* every answer has a bad CRC */
	I_COUNT = 0x09,		/* ACK, data = u32 count of executions of this instr */
	I_SLOW = 0x0a,		/* ACK after 100 ms, data = request data */
	/*
	 * The first answer (the execution) is cut short after ADDR INSTR FLAGS
	 * LEN and 2 of its 4 data bytes; RESEND gets the whole answer:
	 */
	I_CUT_SILENT = 0x0b,	/* ...and the slave stops sending */
	I_CUT_ADDR = 0x0c,	/* ...by an address character (OTHER_ADDR), then silence */
	I_CUT_BREAK = 0x0d,	/* ...by a break */
	/*
	 * The first answer has OVERRUN_DATA data bytes and is sent while the
	 * simulated CPU does not serve interrupts, so the UART's RX FIFO
	 * overruns; the slave serves interrupts again once the overrun has
	 * happened, so most of the answer is still on the line when the
	 * discipline learns of it.
	 */
	I_CUT_OVERRUN = 0x0e,
	I_DELAY = 0x0f,		/* ACK after slave.hold, then slave.delay_us; data = request data */
	/*
	 * Every other execution (the 1st, 3rd...) sends an EVENT frame of its
	 * own and no answer; the others answer ACK.
	 */
	I_EVENT_SILENT = 0x10,
	/*
	 * ACK without data, sent while the simulated CPU does not serve
	 * interrupts between an EVENT frame of the node and a second one:
	 * the RX FIFO (16 characters) holds the first event, the whole answer
	 * and the second event's first 2 characters, the rest overruns, and
	 * the UART reports the overrun with the first event's address
	 * character (the oldest in the FIFO). The slave answers
	 * EVENT_OVERRUN_DELAY_US after the request: the master's drain after
	 * its request serves the port (tx_empty() reads the RX FIFO), which
	 * must be over before the burst, else it takes characters of it.
	 */
	I_EVENT_OVERRUN = 0x11,
};

#define EVENT_OVERRUN_DELAY_US	50000

#define CUT_DATA	4	/* data bytes of the whole answer of I_CUT_* */
#define CUT_SENT	6	/* characters of it sent before the cut */
#define OVERRUN_DATA	200

static inline int sim_load(void)
{
	if (sh("modprobe ts_uart") || sh("modprobe ts7800_sim"))
		return -1;
	return wait_for_path("/dev/ttyTSU0") || wait_for_path("/dev/ts7800-sim/uart0") ||
	       wait_for_path("/dev/ttyTSU1") || wait_for_path("/dev/ts7800-sim/uart1");
}

static inline void sim_unload(void)
{
	sh("modprobe -r n_rs485");
	sh("modprobe -r ts7800_sim");
	sh("modprobe -r ts_uart ts7800_fpga");
}

/* NAME=N on the kernel command line (VMTEST_APPEND=NAME=N), else @def. */
static inline unsigned long cmdline_ulong(const char *name, unsigned long def)
{
	char buf[4096], key[64];
	FILE *f = fopen("/proc/cmdline", "r");
	char *p = NULL;

	snprintf(key, sizeof(key), " %s=", name);
	buf[0] = ' ';
	if (f && fgets(buf + 1, sizeof(buf) - 1, f))
		p = strstr(buf, key);
	if (f)
		fclose(f);
	return p ? strtoul(p + strlen(key), NULL, 10) : def;
}

/* Open /dev/ttyTSU<port> and attach the discipline; returns the fd or -1. */
static inline int bus_open(int port)
{
	int ld = N_RS485_DEFAULT_LDISC;
	char path[32];
	int fd;

	snprintf(path, sizeof(path), "/dev/ttyTSU%d", port);
	fd = open(path, O_RDWR | O_NOCTTY);
	if (fd < 0)
		return -1;
	if (ioctl(fd, TIOCSETD, &ld)) {
		close(fd);
		return -1;
	}
	return fd;
}

/* CRC-8/MAXIM, bit by bit: independent of the kernel's table. */
static inline uint8_t crc8_maxim(const uint8_t *p, size_t n)
{
	uint8_t crc = 0;
	int b;

	while (n--) {
		crc ^= *p++;
		for (b = 0; b < 8; b++)
			crc = crc & 1 ? (crc >> 1) ^ 0x8c : crc >> 1;
	}
	return crc;
}

/* Frame (ADDR..DATA, n bytes) to wire words with CRC; returns the word count. */
static inline size_t frame_words(const uint8_t *f, size_t n, uint8_t crc_xor, uint16_t *w)
{
	size_t i;

	for (i = 0; i < n; i++)
		w[i] = f[i];
	w[0] |= TS7800_SIM_WORD_BIT9;
	w[n] = crc8_maxim(f, n) ^ crc_xor;
	return n + 1;
}

static inline int wire_send_frame(int wfd, const uint8_t *f, size_t n, uint8_t crc_xor)
{
	uint16_t w[N_RS485_MAX_FRAME + 1] = { 0 };

	return wire_write_all(wfd, w, frame_words(f, n, crc_xor, w));
}

/* The slave thread: parses what the master sends and answers. */
struct slave {
	int wfd;
	atomic_int stop;
	pthread_t thread;
	/* what it saw (written by the slave thread only) */
	atomic_uint requests;		/* valid request frames to any address */
	atomic_uint resends;		/* ...with the RESEND flag */
	atomic_uint executions[256];	/* per instruction, RESEND not counted */
	atomic_uint bad_frames;		/* CRC errors, bad 9th bits, truncation */
	atomic_uint broadcasts;
	uint8_t last[N_RS485_MAX_FRAME];	/* last request (guarded by last_lock) */
	size_t last_len;
	pthread_mutex_t last_lock;
	uint8_t last_resp[N_RS485_MAX_FRAME];	/* for RESEND */
	size_t last_resp_len;
	pthread_mutex_t send_lock;	/* one frame at a time on the wire */
	atomic_uint mute_resends;	/* leave this many RESENDs unanswered */
	atomic_uint delay_us;		/* I_DELAY */
	atomic_int hold;		/* I_DELAY: wait while set (10 s at most) */
	atomic_uint overrun_missed;	/* I_CUT_OVERRUN: no overrun within 2 s */
	/* unsolicited events (event_period_us > 0): a second thread */
	unsigned int event_period_us;
	atomic_uint events_sent;
	pthread_t event_thread;
};

static inline void slave_send(struct slave *s, const uint8_t *f, size_t n, uint8_t crc_xor)
{
	pthread_mutex_lock(&s->send_lock);
	wire_send_frame(s->wfd, f, n, crc_xor);
	pthread_mutex_unlock(&s->send_lock);
}

/* Event frame number seq: addr SLAVE_ADDR, instr 0x41, EVENT, 4 bytes of seq. */
static inline size_t event_frame(uint32_t seq, uint8_t *f)
{
	f[0] = SLAVE_ADDR;
	f[1] = 0x41;
	f[2] = N_RS485_RESP_EVENT;
	f[3] = 4;
	memcpy(f + 4, &seq, 4);
	return 8;
}

static inline void *slave_events_main(void *arg)
{
	struct slave *s = arg;
	uint8_t f[8];

	while (!s->stop) {
		usleep(s->event_period_us);
		slave_send(s, f, event_frame(s->events_sent, f), 0);
		s->events_sent++;
	}
	return NULL;
}

/* The first CUT_SENT characters of frame @f, then @end (a word, or none if 0). */
static inline void slave_send_cut(struct slave *s, const uint8_t *f, uint16_t end)
{
	uint16_t w[CUT_SENT + 1];

	frame_words(f, CUT_SENT, 0, w);	/* w[CUT_SENT] (a CRC) is replaced: */
	w[CUT_SENT] = end;
	pthread_mutex_lock(&s->send_lock);
	wire_write_all(s->wfd, w, end ? CUT_SENT + 1 : CUT_SENT);
	pthread_mutex_unlock(&s->send_lock);
}

/* Send @n words while the CPU ignores interrupts, until the RX FIFO overruns. */
static inline void slave_send_words_overrun(struct slave *s, const uint16_t *w, size_t n)
{
	struct ts7800_sim_wire_stats st;
	uint64_t before;
	double end;

	wire_stats(s->wfd, &st);
	before = st.rx_overruns;
	debugfs_write(-1, "irq_hold", 1);
	pthread_mutex_lock(&s->send_lock);
	wire_write_all(s->wfd, w, n);
	pthread_mutex_unlock(&s->send_lock);
	end = now_s() + 2;
	do {
		usleep(1000);
		wire_stats(s->wfd, &st);
	} while (st.rx_overruns == before && now_s() < end);
	debugfs_write(-1, "irq_hold", 0);
	if (st.rx_overruns == before)
		s->overrun_missed++;
}

/* Send @f (n bytes) while the CPU ignores interrupts, until the RX FIFO overruns. */
static inline void slave_send_overrun(struct slave *s, const uint8_t *f, size_t n)
{
	uint16_t w[N_RS485_MAX_FRAME + 1];

	slave_send_words_overrun(s, w, frame_words(f, n, 0, w));
}

/* I_EVENT_OVERRUN: event, the answer @f (n bytes), event, while the FIFO overruns. */
static inline void slave_send_event_overrun(struct slave *s, const uint8_t *f, size_t n)
{
	uint16_t w[2 * 9 + N_RS485_MAX_FRAME + 1];
	uint8_t ev[8];
	size_t k;

	k = frame_words(ev, event_frame(s->events_sent++, ev), 0, w);
	k += frame_words(f, n, 0, w + k);
	k += frame_words(ev, event_frame(s->events_sent++, ev), 0, w + k);
	slave_send_words_overrun(s, w, k);
}

static inline void slave_answer(struct slave *s, const uint8_t *req)
{
	uint8_t r[N_RS485_MAX_FRAME];
	uint8_t ev[8];
	uint8_t instr = req[1], xor = 0;
	size_t len = 0;
	uint32_t cnt;

	if (req[0] == N_RS485_ADDR_BROADCAST) {
		s->broadcasts++;
		return;
	}
	if (req[0] != SLAVE_ADDR)
		return;
	if (req[2] & N_RS485_REQ_RESEND) {
		s->resends++;
		if (s->mute_resends) {
			s->mute_resends--;
			return;
		}
		if (s->last_resp_len)
			slave_send(s, s->last_resp, s->last_resp_len,
				   instr == I_CORRUPT ? 0x55 : 0);
		return;
	}
	s->executions[instr]++;
	if (req[2] & N_RS485_REQ_NOACK)
		return;
	r[0] = SLAVE_ADDR;
	r[1] = instr;
	r[2] = N_RS485_RESP_ACK;
	switch (instr) {
	case I_SLOW:
		usleep(100000);
		/* fall through */
	case I_DELAY:
		if (instr == I_DELAY) {
			double until = now_s() + 10;

			while (s->hold && now_s() < until)
				usleep(1000);
			usleep(s->delay_us);
		}
		/* fall through */
	case I_ECHO:
	case I_EVENT_FIRST:
		len = req[3];
		memcpy(r + 4, req + 4, len);
		break;
	case I_SILENT:
		return;
	case I_UNKNOWN:
		r[2] = N_RS485_RESP_UNKINSTR;
		break;
	case I_DEVERR:
		r[2] = N_RS485_RESP_DEVERR;
		r[4] = 0xde;
		r[5] = 0xad;
		len = 2;
		break;
	case I_CORRUPT_ONCE:
		len = 1;
		r[4] = 0x5a;
		xor = 0x55;
		break;
	case I_WRONG_ADDR:
		r[0] = OTHER_ADDR;
		break;
	case I_CORRUPT:
		xor = 0x55;
		break;
	case I_COUNT:
		cnt = s->executions[I_COUNT];
		memcpy(r + 4, &cnt, 4);
		len = 4;
		break;
	case I_CUT_SILENT:
	case I_CUT_ADDR:
	case I_CUT_BREAK:
		len = CUT_DATA;
		memset(r + 4, instr, len);
		break;
	case I_CUT_OVERRUN:
		len = OVERRUN_DATA;
		memset(r + 4, instr, len);
		break;
	case I_EVENT_OVERRUN:
		break;		/* ACK, no data */
	case I_EVENT_SILENT:
		if (s->executions[instr] % 2) {
			slave_send(s, ev, event_frame(s->executions[instr], ev), 0);
			return;
		}
		break;
	default:
		r[2] = N_RS485_RESP_UNKINSTR;
		break;
	}
	r[3] = len;
	if (instr == I_EVENT_FIRST) {
		ev[0] = SLAVE_ADDR;
		ev[1] = instr;
		ev[2] = N_RS485_RESP_EVENT;
		ev[3] = 2;
		ev[4] = req[3];
		ev[5] = 0xee;
		slave_send(s, ev, 6, 0);
	}
	memcpy(s->last_resp, r, 4 + len);
	s->last_resp_len = 4 + len;
	switch (instr) {
	case I_CUT_SILENT:
		slave_send_cut(s, r, 0);
		break;
	case I_CUT_ADDR:
		slave_send_cut(s, r, OTHER_ADDR | TS7800_SIM_WORD_BIT9);
		break;
	case I_CUT_BREAK:
		slave_send_cut(s, r, TS7800_SIM_WORD_BREAK);
		break;
	case I_CUT_OVERRUN:
		slave_send_overrun(s, r, 4 + len);
		break;
	case I_EVENT_OVERRUN:
		usleep(EVENT_OVERRUN_DELAY_US);
		slave_send_event_overrun(s, r, 4 + len);
		break;
	default:
		slave_send(s, r, 4 + len, xor);
		break;
	}
}

static inline void *slave_main(void *arg)
{
	struct slave *s = arg;
	struct pollfd p = { .fd = s->wfd, .events = POLLIN };
	uint8_t f[N_RS485_MAX_FRAME + 1];
	uint16_t w[512];
	size_t pos = 0;
	int in_frame = 0;

	while (!s->stop) {
		ssize_t r, i;

		if (poll(&p, 1, 20) <= 0)
			continue;
		r = read(s->wfd, w, sizeof(w));
		if (r <= 0)
			continue;
		for (i = 0; i < r / 2; i++) {
			if (w[i] & TS7800_SIM_WORD_BIT9) {
				if (in_frame)
					s->bad_frames++;
				in_frame = 1;
				pos = 0;
			} else if (!in_frame) {
				s->bad_frames++;
				continue;
			}
			f[pos++] = w[i] & 0xff;
			if (pos >= 5 && pos == (size_t)f[3] + 5) {
				in_frame = 0;
				if (crc8_maxim(f, pos - 1) != f[pos - 1]) {
					s->bad_frames++;
					continue;
				}
				pthread_mutex_lock(&s->last_lock);
				memcpy(s->last, f, pos - 1);
				s->last_len = pos - 1;
				pthread_mutex_unlock(&s->last_lock);
				s->requests++;
				slave_answer(s, f);
			}
		}
	}
	return NULL;
}

/* Start the slave; with event_period_us it also sends an event that often. */
static inline int slave_start_events(struct slave *s, int port, unsigned int event_period_us)
{
	memset(s, 0, sizeof(*s));
	pthread_mutex_init(&s->last_lock, NULL);
	pthread_mutex_init(&s->send_lock, NULL);
	s->event_period_us = event_period_us;
	s->wfd = wire_open(port, O_NONBLOCK);
	if (s->wfd < 0)
		return -1;
	if (pthread_create(&s->thread, NULL, slave_main, s))
		return -1;
	if (event_period_us && pthread_create(&s->event_thread, NULL, slave_events_main, s))
		return -1;
	return 0;
}

static inline int slave_start(struct slave *s, int port)
{
	return slave_start_events(s, port, 0);
}

static inline void slave_stop(struct slave *s)
{
	s->stop = 1;
	pthread_join(s->thread, NULL);
	if (s->event_period_us)
		pthread_join(s->event_thread, NULL);
	close(s->wfd);
}

/*
 * A thread that read()s event frames from the bus and checks that the
 * slave's events (event_frame(seq)) arrive in order and byte-exact.
 */
struct event_reader {
	int fd;
	uint32_t max_seq;	/* larger sequence numbers are not the slave's */
	int verbose;		/* tap_diag every gap and stranger */
	atomic_int stop;
	pthread_t thread;
	/* written by the thread, read after event_reader_stop() */
	uint32_t next;		/* next expected sequence number */
	unsigned int got;	/* events in order, byte-exact */
	unsigned int missed;	/* sequence numbers skipped */
	unsigned int non_event;	/* frames without the EVENT flag (responses) */
	unsigned int other;	/* other frames: wrong size or contents */
};

static inline void *event_reader_main(void *arg)
{
	struct event_reader *r = arg;
	struct pollfd p = { .fd = r->fd, .events = POLLIN };
	uint8_t buf[N_RS485_MAX_FRAME], want[8];
	uint32_t seq;
	ssize_t n;

	while (!r->stop) {
		if (poll(&p, 1, 100) <= 0)
			continue;
		n = read(r->fd, buf, sizeof(buf));
		if (n <= 0)
			continue;
		if (!(buf[2] & N_RS485_RESP_EVENT)) {
			r->non_event++;
			continue;
		}
		if (n == 8 && buf[0] == SLAVE_ADDR && buf[1] == 0x41) {
			memcpy(&seq, buf + 4, 4);
			if (seq > r->next && seq < r->max_seq) {
				if (r->verbose)
					tap_diag("events %u..%u missing", r->next, seq - 1);
				r->missed += seq - r->next;
				r->next = seq;
			}
		}
		event_frame(r->next, want);
		if (n == 8 && !memcmp(buf, want, 8)) {
			r->got++;
			r->next++;
			continue;
		}
		if (r->verbose)
			tap_diag("event frame of %zd bytes is not event %u", n, r->next);
		r->other++;
	}
	return NULL;
}

static inline int event_reader_start(struct event_reader *r, int fd, uint32_t max_seq,
				     int verbose)
{
	memset(r, 0, sizeof(*r));
	r->fd = fd;
	r->max_seq = max_seq;
	r->verbose = verbose;
	return pthread_create(&r->thread, NULL, event_reader_main, r);
}

static inline void event_reader_stop(struct event_reader *r)
{
	r->stop = 1;
	pthread_join(r->thread, NULL);
}

/*
 * Take every frame that waits for read() now; returns how many, *responses
 * of them without the EVENT flag (responses, which must never go there).
 */
static inline unsigned int read_queue_drain(int fd, unsigned int *responses)
{
	struct pollfd p = { .fd = fd, .events = POLLIN };
	uint8_t buf[N_RS485_MAX_FRAME];
	unsigned int n = 0;

	*responses = 0;
	while (poll(&p, 1, 0) > 0 && (p.revents & POLLIN) &&
	       read(fd, buf, sizeof(buf)) >= N_RS485_HEADER_LEN) {
		n++;
		if (!(buf[2] & N_RS485_RESP_EVENT))
			(*responses)++;
	}
	return n;
}

/*
 * Idle line before every request, from the wire's line log: a request starts
 * with the start bit of its address character (a transmitted character with
 * the 9th bit); the line was idle since the end of the last character that
 * began before it, in either direction. The log holds each direction in the
 * order its characters ended, the two interleaved as the simulator processed
 * them, so each batch is ordered by start time first and the scan keeps the
 * latest end seen: a request that starts while a received character is still
 * on the line gives a negative idle time.
 * Requests with no received character since the previous request are repeats
 * after a silence (a timeout, or no response expected): their idle time runs
 * from the end of that request. Characters that start while the other
 * direction's last one is still on the line are counted as overlaps (a
 * collision on a half-duplex bus).
 *
 * The slave writes each frame to the wire at once, so its characters follow
 * each other without idle line, unless the simulator's line engine stalled
 * (its timer late under TCG). A request that starts less than the gap after
 * a response is judged, unless that response paused inside itself for longer
 * than the rest of it plus the gap took: then even a receiver that knew
 * exactly how many characters were still to come saw the line idle for the
 * gap after they could have ended (rs485-rx.c). Such a request is set apart
 * (excused_ns; the overlaps it made are not counted), reported and not
 * judged; the pause must come before the request and the rest counts every
 * character of the response, also those that overlapped the request.
 */
#define LINE_SAMPLES	4096

struct line_scan {
	int wfd;		/* a wire fd of the bus's UART, log on */
	/* state between reads */
	int64_t prev_end;	/* latest end of a character so far, either direction */
	int rx_since_req;	/* a character was received since the last request */
	int64_t dir_end[2];	/* latest end of a character, per TS7800_SIM_LOG_* */
	/* results */
	unsigned int requests, dropped, overlaps;
	unsigned int ngaps, nsilent;
	int64_t gap_ns[LINE_SAMPLES];		/* idle before a request, after a response */
	int64_t silent_ns[LINE_SAMPLES];	/* idle before a request, after a request */
	unsigned int nresp;
	int64_t resp_ns[LINE_SAMPLES];		/* end of a request to its response's start */
	unsigned int nexcused;
	int64_t excused_ns[LINE_SAMPLES];	/* early requests after a stalled response */
	/* the response since the last request: characters, inner pauses */
	unsigned int resp_chars;
	int64_t resp_pause_key;		/* max of pause + (characters before it) * char_ns */
	int64_t resp_pause_max;
	/* a request that started less than the gap after a response, until judged */
	int early;
	unsigned int early_chars, early_tail, early_overlaps;
	int64_t early_ns, early_key, early_pause;
	uint32_t char_ns;
	struct ts7800_sim_line_event batch[TS7800_SIM_LOG_EVENTS];
};

static inline void line_scan_init(struct line_scan *ls, int wfd)
{
	memset(ls, 0, sizeof(*ls));
	ls->wfd = wfd;
	ls->prev_end = -1;
	ls->dir_end[0] = -1;
	ls->dir_end[1] = -1;
	ls->resp_pause_key = INT64_MIN;
}

static inline int line_scan_start(struct line_scan *ls, int wfd)
{
	line_scan_init(ls, wfd);
	return wire_set_log(wfd, 1);
}

static inline int64_t line_event_start(const struct ts7800_sim_line_event *ev)
{
	return (int64_t)ev->end_ns - ev->char_ns;
}

/* By start time; a transmitted character before a received one that starts with it. */
static inline int cmp_line_event(const void *a, const void *b)
{
	const struct ts7800_sim_line_event *x = a, *y = b;
	int64_t sx = line_event_start(x), sy = line_event_start(y);

	if (sx != sy)
		return (sx > sy) - (sx < sy);
	return (x->dir > y->dir) - (x->dir < y->dir);
}

/*
 * Judge the early request: excused when its response paused inside itself
 * for longer than the rest of it (characters after the pause, the tail that
 * overlapped the request included) plus the gap; else it counts as a gap.
 */
static inline void line_scan_judge(struct line_scan *ls)
{
	int64_t rest = (int64_t)(ls->early_chars + ls->early_tail + 2) * ls->char_ns;

	if (!ls->early)
		return;
	ls->early = 0;
	if (ls->early_key > rest && ls->nexcused < LINE_SAMPLES) {
		ls->excused_ns[ls->nexcused++] = ls->early_ns;
		tap_diag("a request %.0f us after a response that paused %.0f us inside itself "
			 "(%u characters, %u after the request started): excused, not judged",
			 ls->early_ns / 1e3, ls->early_pause / 1e3, ls->early_chars,
			 ls->early_tail);
		return;
	}
	ls->overlaps += ls->early_overlaps;
	if (ls->ngaps < LINE_SAMPLES)
		ls->gap_ns[ls->ngaps++] = ls->early_ns;
	tap_diag("a request %.0f us after a response of %u characters (%u after the request "
		 "started), whose longest inner pause was %.0f us", ls->early_ns / 1e3,
		 ls->early_chars, ls->early_tail, ls->early_pause / 1e3);
}

/* A received character that starts at @start: the response's inner pauses. */
static inline void line_scan_rx(struct line_scan *ls, int64_t start, int64_t char_ns)
{
	if (ls->rx_since_req && ls->resp_chars) {
		int64_t pause = start - ls->dir_end[1];

		if (pause > char_ns / 2) {
			if (pause + (int64_t)ls->resp_chars * char_ns > ls->resp_pause_key)
				ls->resp_pause_key = pause + (int64_t)ls->resp_chars * char_ns;
			if (pause > ls->resp_pause_max)
				ls->resp_pause_max = pause;
		}
	}
	ls->resp_chars++;
}

/*
 * Scan @n line events (any order): everything the line showed until now, or
 * the rest of it since the last call. rs485proto/scan feeds it made-up lines.
 */
static inline void line_scan_feed(struct line_scan *ls, struct ts7800_sim_line_event *ev,
				  unsigned int n)
{
	unsigned int i;

	qsort(ev, n, sizeof(ev[0]), cmp_line_event);
	for (i = 0; i < n; i++) {
		int64_t start = line_event_start(&ev[i]);
		unsigned int dir = ev[i].dir == TS7800_SIM_LOG_RX;
		int overlap = start < ls->dir_end[!dir];
		int request = ev[i].dir == TS7800_SIM_LOG_TX && (ev[i].word & TS7800_SIM_WORD_BIT9);

		/* the early request's tail: its response's characters that overlap it */
		if (ls->early && dir && overlap)
			ls->early_tail++;
		/*
		 * A request's address character that overlaps is counted below, once
		 * it is known whether it starts an early request: its overlap is then
		 * that request's (excused with it after a stalled response).
		 */
		if (overlap && !request) {
			if (ls->early)
				ls->early_overlaps++;
			else
				ls->overlaps++;
		}
		if (ev[i].dir == TS7800_SIM_LOG_RX)
			line_scan_rx(ls, start, ev[i].char_ns);
		if ((int64_t)ev[i].end_ns > ls->dir_end[dir])
			ls->dir_end[dir] = ev[i].end_ns;
		if (request) {
			line_scan_judge(ls);
			ls->requests++;
			ls->char_ns = ev[i].char_ns;
			if (ls->prev_end >= 0 && ls->rx_since_req &&
			    start - ls->prev_end < 2 * (int64_t)ls->char_ns) {
				ls->early = 1;
				ls->early_ns = start - ls->prev_end;
				ls->early_chars = ls->resp_chars;
				ls->early_key = ls->resp_pause_key;
				ls->early_pause = ls->resp_pause_max;
				ls->early_tail = 0;
				ls->early_overlaps = 0;
			} else if (ls->prev_end >= 0 && ls->rx_since_req && ls->ngaps < LINE_SAMPLES) {
				ls->gap_ns[ls->ngaps++] = start - ls->prev_end;
			} else if (ls->prev_end >= 0 && ls->nsilent < LINE_SAMPLES) {
				ls->silent_ns[ls->nsilent++] = start - ls->prev_end;
			}
			if (overlap) {
				if (ls->early)
					ls->early_overlaps++;
				else
					ls->overlaps++;
			}
			ls->rx_since_req = 0;
			ls->resp_chars = 0;
			ls->resp_pause_key = INT64_MIN;
			ls->resp_pause_max = 0;
		} else if (ev[i].dir == TS7800_SIM_LOG_RX) {
			if (!ls->rx_since_req && ls->requests && ls->nresp < LINE_SAMPLES)
				ls->resp_ns[ls->nresp++] = start - ls->prev_end;
			ls->rx_since_req = 1;
		}
		if ((int64_t)ev[i].end_ns > ls->prev_end)
			ls->prev_end = ev[i].end_ns;
	}
	/* read after a transaction ended: the early request's tail is all in */
	line_scan_judge(ls);
}

/* Consume what the log holds now. */
static inline void line_scan_read(struct line_scan *ls)
{
	unsigned int n = 0;
	int got;

	while (n < TS7800_SIM_LOG_EVENTS &&
	       (got = wire_read_log(ls->wfd, ls->batch + n, TS7800_SIM_LOG_EVENTS - n,
				    &ls->dropped)) > 0)
		n += got;
	line_scan_feed(ls, ls->batch, n);
}

static inline int cmp_i64(const void *a, const void *b)
{
	int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;

	return (x > y) - (x < y);
}

/* Sort @v and report min/median/max in us; returns the minimum (or INT64_MAX). */
static inline int64_t line_report(const char *what, int64_t *v, unsigned int n)
{
	if (!n) {
		tap_diag("%s: none", what);
		return INT64_MAX;
	}
	qsort(v, n, sizeof(v[0]), cmp_i64);
	tap_diag("%s: %u, min %.0f us, median %.0f us, max %.0f us", what, n, v[0] / 1e3,
		 v[n / 2] / 1e3, v[n - 1] / 1e3);
	return v[0];
}

/*
 * The usual set-up of a timing test: the simulator, the bus on /dev/ttyTSU<port>
 * (returned), the slave, and a wire fd (*wfd) with the line log on.
 */
static inline int bus_logged_setup(int port, struct slave *s, int *wfd)
{
	int fd;

	if (sim_load())
		tap_bail("cannot load ts_uart + ts7800_sim");
	fd = bus_open(port);
	if (fd < 0)
		tap_bail("attach n_rs485 to /dev/ttyTSU%d", port);
	if (slave_start(s, port))
		tap_bail("slave on the wire");
	*wfd = wire_open(port, O_NONBLOCK);
	if (*wfd < 0 || wire_set_log(*wfd, 1))
		tap_bail("line log of the wire");
	return fd;
}

static inline void bus_logged_teardown(int fd, int wfd, struct slave *s)
{
	wire_set_log(wfd, 0);
	close(wfd);
	slave_stop(s);
	close(fd);
	sim_unload();
}

/* One transaction; returns the ioctl result, the outcome in x. */
static inline int xfer(int fd, struct n_rs485_xfer *x, uint8_t addr, uint8_t instr, uint8_t flags,
		       const void *data, uint8_t len, uint32_t timeout_us, uint32_t retries)
{
	memset(x, 0, sizeof(*x));
	x->req.addr = addr;
	x->req.instr = instr;
	x->req.flags = flags;
	x->req.len = len;
	if (len)
		memcpy(x->req.data, data, len);
	x->timeout_us = timeout_us;
	x->retries = retries;
	return ioctl(fd, N_RS485_IOC_XFER, x);
}

static inline int get_stats(int fd, struct n_rs485_stats *st)
{
	memset(st, 0, sizeof(*st));
	return ioctl(fd, N_RS485_IOC_GET_STATS, st);
}

#endif /* RS485_LIB_H */
