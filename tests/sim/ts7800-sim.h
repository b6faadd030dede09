/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Simulated TS-7800 FPGA (test only): shared state of the module's files.
 *
 * One spinlock (ts7800_sim.lock) guards the whole model: register accesses
 * from the drivers, the per-port character engines (hrtimers, hard irq
 * context), the wires and debugfs. Cross-connected ports deliver into each
 * other under it, so one lock avoids any lock ordering between ports.
 * irq_lock (nested inside lock) guards the interrupt state, which the irq_chip
 * callbacks also reach from genirq without the model lock.
 */
#ifndef TS7800_SIM_H
#define TS7800_SIM_H

#include <linux/hrtimer.h>
#include <linux/irq_work.h>
#include <linux/kfifo.h>
#include <linux/miscdevice.h>
#include <linux/spinlock.h>
#include <linux/ts7800-fpga.h>
#include <linux/ts7800_sim.h>
#include <linux/wait.h>

/* Words queued on each direction of a wire. */
#define SIM_WIRE_WORDS		4096
/*
 * Wire readers are woken once this many words wait or when the transmitter
 * goes idle, writers once a quarter of the queue is free: waking a process
 * per character would cost more than the line itself under emulation.
 */
#define SIM_WIRE_WAKE_WORDS	64
#define SIM_WIRE_WAKE_ROOM	(SIM_WIRE_WORDS / 4)
/* Longest slice of line time simulated per timer expiry (ts7800-sim-uart.c). */
#define SIM_SLICE_NS		1000000
#define SIM_SLICE_MAX		16U
/* RX FIFO entry flag (model internal): the entry is a received break. */
#define SIM_RX_BREAK		BIT(15)

struct ts7800_sim;

struct sim_ring {
	u16 *buf;
	unsigned int head;
	unsigned int count;
	unsigned int depth;
};

struct sim_fault {
	u32 drop;		/* drop the next N characters */
	u32 corrupt;		/* XOR the next N characters with corrupt_xor */
	u32 corrupt_xor;
};

/* One debugfs fault file: a u32 of a port, bounded by max. */
struct sim_knob {
	struct sim_uart *u;
	u32 *val;
	u32 max;
};

#define SIM_NR_KNOBS	6

struct sim_uart {
	struct ts7800_sim *sim;
	unsigned int idx;
	u16 ctrl;		/* STAT control bits as written */
	bool cts;		/* CTS input level, driven from the wire */

	/* receiver: line_in -> shift (timed) -> rx FIFO -> DATA reads */
	DECLARE_KFIFO(line_in, u16, SIM_WIRE_WORDS);
	struct sim_ring rx;
	bool oerr;
	bool rx_busy;
	unsigned int rx_nslice;	/* characters completing at the next expiry */
	ktime_t rx_line_free;
	struct hrtimer rx_timer;

	/* transmitter: DATA writes -> tx FIFO -> shift (timed) -> line_out */
	struct sim_ring tx;
	u16 tx_shift[SIM_SLICE_MAX];	/* the slice on the line */
	unsigned int tx_nshift;
	bool tx_busy;
	bool tx_event;		/* TX FIFO ran empty since the last STAT read */
	ktime_t tx_line_free;
	struct hrtimer tx_timer;
	DECLARE_KFIFO(line_out, u16, SIM_WIRE_WORDS);

	wait_queue_head_t wait_in;	/* writers: room in line_in */
	wait_queue_head_t wait_out;	/* readers: words in line_out */

	int peer;		/* cross-connected port, or -1 */
	struct sim_fault rx_fault;
	struct sim_fault tx_fault;
	struct ts7800_sim_wire_stats stats;
	struct sim_knob knobs[SIM_NR_KNOBS];

	struct miscdevice misc;
	char name[24];
	char nodename[32];
};

struct ts7800_sim {
	struct device *dev;
	spinlock_t lock;	/* the whole model, see the top of this file */
	bool stopping;		/* teardown: engines must not restart */
	u16 divisors[TS7800_UART_NR_CODES + 1];
	u32 rowc;		/* PC/104 row C pin function register */
	unsigned int nports;
	struct sim_uart uart[TS7800_UART_MAX_PORTS];

	/* interrupts (irq_lock) */
	raw_spinlock_t irq_lock;
	u32 irq_enable;		/* FPGA enable mask, offset 0x204 */
	u32 irq_level;		/* current level of each source */
	u32 irq_cause;		/* latched, cleared by ack (the doorbell cause) */
	bool edge;		/* trigger rule, see ts7800_sim_irq_source() */
	bool irq_hold;		/* debugfs: the CPU "does not respond" */
	struct irq_work irq_work;
	struct irq_domain *domain;
	struct fwnode_handle *fwnode;

	struct dentry *debugfs;
};

/* model parameters (ts7800-sim-main.c) */
extern unsigned int sim_fifo_depth;
extern bool sim_oerr_clear_on_data;

/* ts7800-sim-main.c */
void ts7800_sim_irq_source(struct ts7800_sim *sim, unsigned int hwirq, bool level);
void ts7800_sim_irq_set_hold(struct ts7800_sim *sim, bool hold);
void ts7800_sim_irq_deliver(struct ts7800_sim *sim);
void ts7800_sim_irq_kick(struct ts7800_sim *sim);

/* ts7800-sim-uart.c */
int sim_uart_init(struct ts7800_sim *sim, struct sim_uart *u, unsigned int idx);
void sim_uart_stop(struct sim_uart *u);
int sim_reg_read(void *context, unsigned int reg, unsigned int *val);
int sim_reg_write(void *context, unsigned int reg, unsigned int val);
void sim_uart_rx_kick(struct sim_uart *u);
void sim_uart_tx_kick(struct sim_uart *u);

/* ts7800-sim-wire.c */
int sim_wire_register(struct sim_uart *u);
void sim_wire_unregister(struct sim_uart *u);

/* ts7800-sim-debugfs.c */
void sim_debugfs_init(struct ts7800_sim *sim);

#endif /* TS7800_SIM_H */
