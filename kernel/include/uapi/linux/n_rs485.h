/* SPDX-License-Identifier: GPL-2.0 WITH Linux-syscall-note */
/*
 * n_rs485.h - user API of the n_rs485 line discipline: a 9-bit multidrop
 * RS-485/EIA-422 bus master on any UART with mark/space parity.
 *
 * Attach with TIOCSETD (N_RS485_DEFAULT_LDISC) or "ldattach 29 /dev/ttyX".
 * Then, on that tty file descriptor:
 *
 *   ioctl(N_RS485_IOC_XFER)   one request/response transaction (struct n_rs485_xfer)
 *   read()                  one event frame per call: ADDR INSTR FLAGS LEN DATA
 *                           (4 + LEN bytes, no CRC); EOVERFLOW if the buffer is
 *                           shorter than the frame (the frame is then dropped)
 *   write()                 one request frame ADDR INSTR FLAGS LEN DATA, sent
 *                           as is (the CRC is appended), no response awaited
 *   poll()                  EPOLLIN: an event frame waits
 *
 * Every structure is made of fixed-size fields with explicit padding, so a
 * 32-bit program uses the same layout on a 64-bit kernel. Wire format and
 * outcomes: docs/rs485proto.md.
 */
#ifndef _UAPI_LINUX_N_RS485_H
#define _UAPI_LINUX_N_RS485_H

#include <linux/ioctl.h>
#include <linux/types.h>

/* N_DEVELOPMENT: the line discipline number reserved for out-of-tree use. */
#define N_RS485_DEFAULT_LDISC	29

#define N_RS485_ADDR_BROADCAST	0xff
#define N_RS485_MAX_DATA	255
/* ADDR INSTR FLAGS LEN */
#define N_RS485_HEADER_LEN	4
/* Largest frame read() returns or write() takes (no CRC). */
#define N_RS485_MAX_FRAME	(N_RS485_HEADER_LEN + N_RS485_MAX_DATA)

/* Request flags (master to slave) */
#define N_RS485_REQ_RESEND	0x01	/* send the last response again, do not execute */
#define N_RS485_REQ_NOACK	0x02	/* execute, send no response */

/* Response flags (slave to master) */
#define N_RS485_RESP_ACK	0x01
#define N_RS485_RESP_UNKINSTR	0x02
#define N_RS485_RESP_DEVERR	0x04
#define N_RS485_RESP_EVENT	0x08

/* One frame without its CRC (the discipline computes and checks it). */
struct n_rs485_frame {
	__u8 addr;
	__u8 instr;
	__u8 flags;
	__u8 len;
	__u8 data[N_RS485_MAX_DATA];
	__u8 pad;			/* 0 */
};

/* Outcome of a transaction (n_rs485_xfer.status) */
enum n_rs485_status {
	N_RS485_OK = 0,			/* response with ACK (or sent, if none expected) */
	N_RS485_TIMEOUT = 1,		/* no valid response after all retries */
	N_RS485_BADCRC = 2,		/* last attempt's response corrupt: bad CRC, cut short */
	N_RS485_UNKINSTR = 3,		/* the device does not know the instruction */
	N_RS485_DEVERR = 4,		/* the device failed executing it */
	N_RS485_ERROR = 5,		/* local failure (UART stuck), interrupted, bad response */
	/*
	 * N_RS485_CFG_ECHO only: the bus did not carry the request as sent (its
	 * echo differed or did not come back) on the last attempt.
	 */
	N_RS485_COLLISION = 6,
};

/* Use the bus default (n_rs485_config) for timeout_us or retries. */
#define N_RS485_DEFAULT		0xffffffffU

/* N_RS485_IOC_XFER argument */
struct n_rs485_xfer {
	struct n_rs485_frame req;	/* in: flags may hold NOACK only */
	struct n_rs485_frame resp;	/* out: the response (if any) */
	__u32 timeout_us;		/* in: response timeout, or N_RS485_DEFAULT */
	__u32 retries;			/* in: retries after a failure, or N_RS485_DEFAULT */
	__u32 status;			/* out: enum n_rs485_status */
	__u32 attempts;			/* out: requests sent (1 + retries used) */
};

/* Bus configuration (N_RS485_IOC_GET_CONFIG / N_RS485_IOC_SET_CONFIG) */
struct n_rs485_config {
	__u32 baud;			/* line rate, e.g. 115200 */
	__u32 timeout_us;		/* default response timeout, 100..10000000 */
	__u32 retries;			/* default retries, 0..16 */
	__u32 gap_chars;		/* idle characters between frames, 2..255 */
	__u32 flags;			/* RS485_CFG_*, 0 by default (was reserved) */
	__u32 reserved[3];		/* 0 */
};

/*
 * n_rs485_config.flags: the transceiver echoes every character the master
 * sends (a 2-wire half-duplex bus whose receiver stays enabled while it
 * transmits). The discipline then takes the first characters received after
 * each request as its echo and compares them with what it sent; a
 * difference (or a missing echo) is a collision: counted in
 * n_rs485_stats.collisions and retried, N_RS485_COLLISION if the last attempt
 * collided. Without it, such an echo would be taken for the response.
 */
#define N_RS485_CFG_ECHO	0x00000001U

/* Statistics since attach (N_RS485_IOC_GET_STATS) */
struct n_rs485_stats {
	__u64 tx_frames;		/* frames sent (each attempt counts) */
	__u64 tx_bytes;			/* characters sent, CRC included */
	__u64 rx_frames;		/* valid frames received */
	__u64 rx_bytes;			/* characters received (all) */
	__u64 rx_crc_errors;		/* frames with a bad CRC */
	__u64 rx_truncated;		/* frames cut short by a new address character */
	__u64 rx_noise;			/* characters outside any frame */
	__u64 rx_overruns;		/* TTY_OVERRUN reports */
	__u64 rx_framing;		/* TTY_FRAME / TTY_BREAK characters */
	__u64 xfers;			/* transactions started (N_RS485_IOC_XFER) */
	__u64 xfers_ok;			/* ...with outcome N_RS485_OK */
	__u64 xfers_failed;		/* ...with any other outcome */
	__u64 timeouts;			/* attempts without a response */
	__u64 retries;			/* attempts after the first */
	__u64 events;			/* frames queued for read() */
	__u64 events_dropped;		/* frames dropped: event queue full */
	__u64 unexpected;		/* non-event frames no transaction waited for */
	__u64 collisions;		/* N_RS485_CFG_ECHO: attempts whose echo differed */
	/*
	 * Since issue 20. A program built with the fields above only (144
	 * bytes) still gets them: the ioctl number carries the size it asks for.
	 */
	__u64 tx_path;			/* enum n_rs485_tx_path, chosen at attach */
	__u64 termios_switches;		/* tty_set_termios() calls for sending frames */
	__u64 drains;			/* waits for the transmitter to empty after a write */
	__u64 addr_drains;		/* ...of them between an address and its data */
};

/*
 * n_rs485_stats.tx_path: how the 9th bit is sent. The discipline takes
 * N_RS485_PATH_ADDRB at attach on a serial_core port that offers
 * SER_RS485_ADDRB (mainline's 9-bit addressing, e.g. the TS-UART), unless
 * the module parameter addrb=0 says not to, and N_RS485_PATH_PARITY on every
 * other UART with mark/space parity (CMSPAR).
 */
enum n_rs485_tx_path {
	/*
	 * Address in mark parity, data in space parity: per frame two
	 * termios switches and two drains, one between address and data.
	 */
	N_RS485_PATH_PARITY = 0,
	/*
	 * SER_RS485_ADDR_DEST puts the address before the data in the UART's
	 * queue: no termios switch, one drain per frame (after it, to start the
	 * response timeout when the request has left the line).
	 */
	N_RS485_PATH_ADDRB = 1,
};

/* Per-node error counter (N_RS485_IOC_GET_NODE / N_RS485_IOC_RESET_NODE) */
enum n_rs485_node_state {
	N_RS485_NODE_ACTIVE = 0,	/* counter < 128 */
	N_RS485_NODE_PASSIVE = 1,	/* 128 <= counter < 256 */
	N_RS485_NODE_OFF = 2,		/* counter >= 256: do not poll it (still served) */
};

struct n_rs485_node {
	__u8 addr;			/* in */
	__u8 state;			/* out: enum n_rs485_node_state */
	__u16 pad;			/* 0 */
	__u32 errors;			/* out: the error counter */
};

/*
 * 0xBB: a code Documentation/userspace-api/ioctl/ioctl-number.rst does not
 * list (6.1 up to at least 6.18; it was 0xB5, rpmsg's, until issue 18).
 */
#define N_RS485_IOC_MAGIC	0xbb
#define N_RS485_IOC_XFER	_IOWR(N_RS485_IOC_MAGIC, 1, struct n_rs485_xfer)
#define N_RS485_IOC_GET_CONFIG	_IOR(N_RS485_IOC_MAGIC, 2, struct n_rs485_config)
#define N_RS485_IOC_SET_CONFIG	_IOW(N_RS485_IOC_MAGIC, 3, struct n_rs485_config)
#define N_RS485_IOC_GET_STATS	_IOR(N_RS485_IOC_MAGIC, 4, struct n_rs485_stats)
#define N_RS485_IOC_GET_NODE	_IOWR(N_RS485_IOC_MAGIC, 5, struct n_rs485_node)
/* Reset one node's counter to 0 (active); argument: struct n_rs485_node (addr). */
#define N_RS485_IOC_RESET_NODE	_IOW(N_RS485_IOC_MAGIC, 6, struct n_rs485_node)

#endif /* _UAPI_LINUX_N_RS485_H */
