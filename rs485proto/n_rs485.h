/* SPDX-License-Identifier: GPL-2.0 */
/*
 * n_rs485.h - internal interfaces of the n_rs485 line discipline.
 *
 * One struct rs485_bus per attached tty. Who touches what:
 *   rx      receive_buf (one call at a time per tty, kworker context)
 *   queue, cur, resp_*, events, stats, nodes: under lock (a spinlock, because
 *           receive_buf must not sleep)
 *   the bus itself (TX, termios switching, waiting for a response) belongs
 *           to one work item on the bus's ordered workqueue, so requests of
 *           all callers run one after the other in FIFO order.
 */
#ifndef N_RS485_INTERNAL_H
#define N_RS485_INTERNAL_H

#include <linux/kref.h>
#include <linux/ktime.h>
#include <linux/list.h>
#include <linux/mutex.h>
#include <linux/serial.h>
#include <linux/spinlock.h>
#include <linux/tty.h>
#include <linux/wait.h>
#include <linux/workqueue.h>
#include <uapi/linux/n_rs485.h>

/* ADDR INSTR FLAGS LEN DATA CRC */
#define RS485_WIRE_MAX		(N_RS485_MAX_FRAME + 1)
#define RS485_EVENT_QUEUE_MAX	64
#define RS485_REQ_QUEUE_MAX	64
#define RS485_ERR_FAIL		8	/* CAN-like counter: +8 per failure */
#define RS485_ERR_PASSIVE	128
#define RS485_ERR_OFF		256

enum rs485_rx_state {
	RS485_RX_IDLE,		/* waiting for an address character */
	RS485_RX_HEADER,	/* INSTR FLAGS LEN */
	RS485_RX_DATA,
	RS485_RX_CRC,
};

struct rs485_rx {
	enum rs485_rx_state state;
	/*
	 * While the address character is sent in mark parity the UART flags
	 * received characters against mark: the 9th bits of whatever arrives
	 * then (full duplex) read inverted. The worker sets this from before the
	 * switch to mark until everything received up to the switch back has
	 * passed receive_buf; meanwhile a frame in progress takes every
	 * character as data, and any character starts a frame (see rs485-rx.c).
	 */
	bool lenient;			/* under bus->lock */
	unsigned int pos;		/* bytes of frame.buf filled */
	unsigned int left;		/* characters that may still come (rs485-rx.c) */
	u32 attempt;			/* bus->attempt when the frame in progress began */
	u8 buf[N_RS485_MAX_FRAME];	/* ADDR INSTR FLAGS LEN DATA */
	/*
	 * The characters of the frame in progress as received (with their
	 * parity flag) and whether leniency decided anything in it: if such a
	 * frame fails its CRC, its characters after the first are parsed again
	 * by their flags, so that a wrong guess costs no valid frame.
	 */
	bool guessed;
	unsigned int nraw;
	u8 raw[RS485_WIRE_MAX];
	bool raw_parity[RS485_WIRE_MAX];
	u8 replay[RS485_WIRE_MAX];
	bool replay_parity[RS485_WIRE_MAX];
};

/* What the worker waits for after sending a request that expects a response. */
enum rs485_resp_state {
	RS485_RESP_NONE,	/* no response expected */
	RS485_RESP_WAIT,	/* nothing yet */
	RS485_RESP_STARTED,	/* address character of the awaited node seen */
	RS485_RESP_GOOD,	/* valid response in the request's resp */
	RS485_RESP_CORRUPT,	/* a frame from that node failed its CRC */
};

struct rs485_req {
	struct list_head node;		/* bus->queue */
	struct kref ref;		/* caller + bus */
	struct n_rs485_frame frame;	/* request */
	struct n_rs485_frame resp;
	u32 timeout_us;
	u32 retries;
	u32 status;
	u32 attempts;
	bool expect_resp;
	bool is_xfer;			/* N_RS485_IOC_XFER (else write()) */
	bool done;
	bool abandoned;			/* the caller gave up (signal, close) */
};

struct rs485_event {
	struct list_head node;
	unsigned int len;
	u8 buf[N_RS485_MAX_FRAME];
};

struct rs485_bus {
	struct tty_struct *tty;
	spinlock_t lock;		/* everything below that rx hands over */
	struct rs485_rx rx;

	struct workqueue_struct *wq;
	struct work_struct work;
	struct list_head queue;		/* struct rs485_req, FIFO */
	unsigned int queued;
	struct rs485_req *cur;		/* on the bus now */
	enum rs485_resp_state resp_state;
	/*
	 * Number of the attempt that resp_state is about: a frame that began
	 * during an earlier attempt and is cut short or fails its CRC later
	 * says nothing about the current one.
	 */
	u32 attempt;
	wait_queue_head_t resp_wait;	/* the worker: response or dead */
	wait_queue_head_t done_wait;	/* callers: their request done */
	bool dead;			/* detaching or hung up: no new work */
	bool rx_flush;			/* TCIFLUSH: rx resets at its next call */
	/*
	 * The line is idle for gap_chars before every request, retries
	 * included: line_free is the end of the last request sent plus the gap
	 * (worker only), rx_last when the last character was received (under
	 * lock; receive_buf runs after the character ended, so the gap counted
	 * from it is never short), rx_busy_until when the characters that may
	 * still come of a frame in progress or a broken one could have passed
	 * at the earliest (under lock, see rs485-rx.c).
	 */
	ktime_t line_free;
	ktime_t rx_last;
	ktime_t rx_busy_until;

	/*
	 * N_RS485_CFG_ECHO: the frame being sent, which the first characters
	 * received must repeat. echo_len 0: no echo expected. Set by the
	 * worker, consumed by receive_buf (rs485_rx_echo()).
	 */
	u8 echo_buf[RS485_WIRE_MAX];
	unsigned int echo_len;
	unsigned int echo_pos;		/* characters of the echo seen */
	bool echo_collided;		/* one of them differed or had an error */

	struct list_head events;	/* struct rs485_event, FIFO */
	unsigned int nevents;

	struct n_rs485_config cfg;	/* written under line_mutex and lock */
	struct n_rs485_stats stats;
	u16 node_err[256];

	struct ktermios saved_termios;
	/*
	 * N_RS485_PATH_ADDRB: the port's RS-485 setting before attach (put
	 * back at detach) and the one the bus uses (rs485-tx.c).
	 */
	bool addrb;
	struct serial_rs485 saved_rs485;
	struct serial_rs485 rs485;
	struct mutex line_mutex;	/* termios and cfg: worker vs SET_CONFIG */
};

/*
 * N_RS485_IOC_GET_STATS of a program built before issue 20 extended
 * struct n_rs485_stats: the same request for its first 18 fields.
 */
#define N_RS485_IOC_GET_STATS_V1 \
	_IOC(_IOC_READ, N_RS485_IOC_MAGIC, 4, offsetof(struct n_rs485_stats, tx_path))

/* rs485-crc.c */
void rs485_crc_init(void);
u8 rs485_crc(const u8 *buf, size_t len);

/* rs485-rx.c */
void rs485_rx_reset(struct rs485_bus *bus);
void rs485_rx_chars(struct rs485_bus *bus, const u8 *cp, const u8 *fp, int count);

/* rs485-tx.c */
int rs485_line_setup(struct rs485_bus *bus);
void rs485_line_restore(struct rs485_bus *bus);
int rs485_line_set_config(struct rs485_bus *bus, const struct n_rs485_config *cfg);
u64 rs485_char_ns(const struct rs485_bus *bus);
void rs485_line_wait(struct rs485_bus *bus);
int rs485_tx_frame(struct rs485_bus *bus, const u8 *buf, size_t len);

/* rs485-xact.c */
void rs485_count(struct rs485_bus *bus, u64 *counter);
struct rs485_req *rs485_req_alloc(void);
void rs485_req_put(struct rs485_req *req);
int rs485_req_submit(struct rs485_bus *bus, struct rs485_req *req);
int rs485_req_wait(struct rs485_bus *bus, struct rs485_req *req);
void rs485_xact_work(struct work_struct *work);
void rs485_xact_kill(struct rs485_bus *bus);
bool rs485_rx_frame_for_xact(struct rs485_bus *bus, const u8 *frame, unsigned int len,
			     u32 attempt);
void rs485_rx_corrupt_from(struct rs485_bus *bus, u8 addr, u32 attempt);
u32 rs485_rx_addr_seen(struct rs485_bus *bus, u8 addr);

/* rs485-user.c */
void rs485_event_queue(struct rs485_bus *bus, const u8 *frame, unsigned int len);
void rs485_events_flush(struct rs485_bus *bus);
ssize_t rs485_read(struct tty_struct *tty, struct file *file, u8 *kbuf, size_t nr,
		   void **cookie, unsigned long offset);
ssize_t rs485_write(struct tty_struct *tty, struct file *file, const u8 *buf, size_t nr);
__poll_t rs485_poll(struct tty_struct *tty, struct file *file, struct poll_table_struct *wait);
int rs485_ioctl(struct tty_struct *tty, unsigned int cmd, unsigned long arg);
int rs485_compat_ioctl(struct tty_struct *tty, unsigned int cmd, unsigned long arg);
int rs485_config_check(const struct n_rs485_config *cfg);

#endif /* N_RS485_INTERNAL_H */
