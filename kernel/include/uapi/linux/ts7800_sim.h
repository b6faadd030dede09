/* SPDX-License-Identifier: GPL-2.0 WITH Linux-syscall-note */
/*
 * ts7800_sim.h - user-space side of the simulated TS-7800 FPGA (test only).
 *
 * Every simulated TS-UART n has a "wire", the character device
 * /dev/ts7800-sim/uartN. A program that opens it is the far end of the line:
 *
 *   read()  returns what the UART transmitted, one word per character, each
 *           becoming readable when its stop bit has left the line;
 *   write() queues characters for the UART to receive; the simulator clocks
 *           them in back to back at the UART's configured rate.
 *
 * Both directions carry arrays of 16-bit little-endian words (see
 * TS7800_SIM_WORD_*); byte counts must be even. Reads and writes block unless
 * O_NONBLOCK is set; poll() reports EPOLLIN when transmitted words wait and
 * EPOLLOUT when the receive queue has room. Each direction queues 4096 words.
 *
 * Wake-ups are batched to keep the simulation cheap: a blocked reader (or
 * poller) is woken when 64 words wait or when the UART's transmitter goes
 * idle (the end of every burst or frame), a blocked writer when a quarter of
 * the queue is free. A non-blocking read always returns what is there.
 * There is no flow control on the wire: words transmitted while the read
 * queue is full are dropped and counted (to_wire_dropped).
 * TS7800_SIM_SET_ECHO makes the UART hear its own characters (2-wire bus).
 */
#ifndef _UAPI_LINUX_TS7800_SIM_H
#define _UAPI_LINUX_TS7800_SIM_H

#include <linux/ioctl.h>
#include <linux/types.h>

/* Wire word layout */
#define TS7800_SIM_WORD_DATA	0x00ff	/* bits 7..0 of the character */
#define TS7800_SIM_WORD_BIT9	0x0100	/* 9th bit (meaningful in 9-bit mode) */
#define TS7800_SIM_WORD_CHAR	0x01ff	/* the whole character */
/*
 * A break condition instead of a character. Sent by the UART while it holds
 * TXBRK (one word per break); written by the far end, the UART receives a
 * break (STAT RXBRK with a NUL character).
 */
#define TS7800_SIM_WORD_BREAK	0x0200
/*
 * Written by the far end: the character has a bad stop bit. The TS-UART has
 * no framing-error status, so the model delivers the character unchanged
 * (documented choice); the flag is counted in framing_errors.
 */
#define TS7800_SIM_WORD_FRAME	0x0400
#define TS7800_SIM_WORD_FLAGS	0x0600

/* Line timing and counters of one simulated UART (times: CLOCK_MONOTONIC). */
struct ts7800_sim_wire_stats {
	__u64 to_wire;			/* characters the UART transmitted */
	__u64 to_wire_dropped;		/* ...lost because nobody read the wire */
	__u64 to_wire_first_ns;		/* start bit of the first one */
	__u64 to_wire_last_ns;		/* end of the stop bit of the last one */
	__u64 from_wire;		/* characters the UART's receiver completed */
	__u64 from_wire_first_ns;
	__u64 from_wire_last_ns;
	__u64 rx_overruns;		/* completed while the RX FIFO was full */
	__u64 framing_errors;		/* TS7800_SIM_WORD_FRAME words received */
	__u64 faults;			/* characters dropped or corrupted by debugfs */
	/*
	 * Time the line stood still because the simulator itself ran late (its
	 * timer fired more than a character time late, e.g. a stalled virtual
	 * CPU): the model then pauses the line instead of delivering a burst of
	 * characters, so such a stall never causes an overrun.
	 */
	__u64 to_wire_stall_ns;
	__u64 from_wire_stall_ns;
	__u32 char_ns;			/* current character time, 0 = line off */
	__u16 ctrl;			/* STAT control bits as last written */
	__u16 fifo_depth;		/* RX and TX FIFO depth of the model */
};

/*
 * 0xBC: not listed in Documentation/userspace-api/ioctl/ioctl-number.rst
 * (6.1 up to at least 6.18; it was 0xB4, gpio's, until issue 18).
 */
#define TS7800_SIM_IOC_MAGIC	0xbc
/* Read the counters and line state of this wire's UART. */
#define TS7800_SIM_GET_STATS	_IOR(TS7800_SIM_IOC_MAGIC, 1, struct ts7800_sim_wire_stats)
/* Zero the counters and times (the next character starts a new measurement). */
#define TS7800_SIM_RESET_STATS	_IO(TS7800_SIM_IOC_MAGIC, 2)
/* Drive the UART's CTS input: 0 = deasserted, 1 = asserted (the default). */
#define TS7800_SIM_SET_CTS	_IOW(TS7800_SIM_IOC_MAGIC, 3, __u32)
/*
 * Echo: 1 = the UART also receives every character it transmits, when its
 * stop bit ends (after tx fault injection, like everyone on the line), as
 * on a 2-wire half-duplex bus whose transceiver keeps its receiver enabled;
 * the wire still reads them. 0 = off (the default, also after reloading).
 */
#define TS7800_SIM_SET_ECHO	_IOW(TS7800_SIM_IOC_MAGIC, 4, __u32)

/*
 * Line log: every character of this wire, in both directions, with the time
 * its stop bit ended (CLOCK_MONOTONIC): what the UART transmitted (after tx
 * fault injection, as the line carried it) and what its receiver completed
 * (after rx fault injection; also a character lost to a full RX FIFO). It
 * starts at TS7800_SIM_SET_LOG 1 (which empties it) and holds the last
 * TS7800_SIM_LOG_EVENTS characters not yet read; more are dropped and
 * counted. Independent of read(), which still returns the words.
 */
#define TS7800_SIM_LOG_EVENTS	4096
#define TS7800_SIM_LOG_TX	0	/* the UART sent it */
#define TS7800_SIM_LOG_RX	1	/* the UART received it */

struct ts7800_sim_line_event {
	__u64 end_ns;			/* end of the stop bit */
	__u32 char_ns;			/* the character's time on the line */
	__u16 word;			/* TS7800_SIM_WORD_* */
	__u8 dir;			/* TS7800_SIM_LOG_TX or _RX */
	__u8 pad;
};

/* TS7800_SIM_READ_LOG argument: takes up to max events, oldest first. */
struct ts7800_sim_log_read {
	__u64 events;			/* user pointer to max struct ts7800_sim_line_event */
	__u32 max;			/* in */
	__u32 count;			/* out: events copied */
	__u32 dropped;			/* out: events lost (log full) since the last read */
	__u32 pad;
};

/* 1 = start logging (emptied), 0 = stop. Off by default. */
#define TS7800_SIM_SET_LOG	_IOW(TS7800_SIM_IOC_MAGIC, 5, __u32)
/* Non-blocking: copies what the log holds (count may be 0). */
#define TS7800_SIM_READ_LOG	_IOWR(TS7800_SIM_IOC_MAGIC, 6, struct ts7800_sim_log_read)

/*
 * Idle line time (TS7800_SIM_GET_GAPS), in the model's line time: for every
 * character on this port's line, the time the line was idle before its
 * start bit (its end less its character time) since the end of the previous
 * character in either direction, 0 if they overlap. Summed per direction
 * (index TS7800_SIM_LOG_TX or _RX) and separately for address characters
 * (9th bit 1: the first character of a 9-bit frame) and for all others
 * (the rest of a frame, 8-bit traffic, breaks). A frame's idle time is the
 * gap between frames on the line, a character's the gap inside one. A
 * pause of the line because the simulator itself ran late (see
 * to_wire_stall_ns) is not idle time. The
 * echo of TS7800_SIM_SET_ECHO is the transmitted character itself and is not
 * counted again. Zeroed by TS7800_SIM_RESET_STATS; the first character after
 * it has no predecessor and counts no idle time.
 */
struct ts7800_sim_line_gaps {
	__u64 frames[2];		/* address characters */
	__u64 frame_idle_ns[2];		/* idle line before them */
	__u64 frame_idle_max_ns[2];	/* the longest of those */
	__u64 chars[2];			/* the other characters */
	__u64 char_idle_ns[2];		/* idle line before them */
	__u64 char_idle_max_ns[2];	/* the longest of those */
};

#define TS7800_SIM_GET_GAPS	_IOR(TS7800_SIM_IOC_MAGIC, 7, struct ts7800_sim_line_gaps)

#endif /* _UAPI_LINUX_TS7800_SIM_H */
