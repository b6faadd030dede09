/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Simulated TS-7800 FPGA (test only): shared state of the module's files.
 *
 * One spinlock (ts7800_sim.lock) guards the whole model: register accesses
 * from the drivers, the per-port character engines (hrtimers, hard irq
 * context), the wires and debugfs. Cross-connected ports deliver into each
 * other under it, so one lock avoids any lock ordering between ports.
 * The DIO pins, the I2C slave and the MAX6615 model live under the same lock.
 * irq_lock (nested inside lock) guards the interrupt state, which the irq_chip
 * callbacks also reach from genirq without the model lock.
 */
#ifndef TS7800_SIM_H
#define TS7800_SIM_H

#include <linux/atomic.h>
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
	bool echo;		/* receives what it transmits (TS7800_SIM_SET_ECHO) */
	/* TS7800_SIM_SET_LOG: line log, buffer allocated on first use (devm) */
	bool log_on;
	u32 log_dropped;
	DECLARE_KFIFO_PTR(log, struct ts7800_sim_line_event);
	struct sim_fault rx_fault;
	struct sim_fault tx_fault;
	struct ts7800_sim_wire_stats stats;
	/*
	 * TS7800_SIM_GET_GAPS; line_end: end of the last character, 0 = none;
	 * line_stall_ns: the line paused for a stalled simulator since then
	 */
	struct ts7800_sim_line_gaps gaps;
	ktime_t line_end;
	u64 line_stall_ns;
	struct sim_knob knobs[SIM_NR_KNOBS];

	struct miscdevice misc;
	char name[24];
	char nodename[32];
};

/*
 * DIO header (ts7800-sim-dio.c): every pin is a wired-AND of the output
 * latch, outside devices pulled low through debugfs and the simulated
 * MAX6615 (SDA of its bus, its FAN_FAIL output).
 */
struct sim_dio {
	u16 out;		/* output latch, offset 0x08 */
	u16 ext_low;		/* pins held low by the outside (debugfs) */
	u16 chip_low;		/* pins held low by the simulated MAX6615 */
	unsigned int scl, sda;	/* header pins of the I2C bus */
	unsigned int fan_fail;	/* header pin of the FAN_FAIL output */
	unsigned int pause;	/* header pin of the robot's PAUSE signal */
	atomic_t hold;		/* enum sim_dio_hold: debugfs "in_hold" */
	unsigned int hold_ms;	/* longest hold of an armed read */
};

/* A held read of the DIO input register (debugfs "in_hold"). */
enum sim_dio_hold {
	SIM_DIO_HOLD_OFF,	/* reads return at once */
	SIM_DIO_HOLD_ARMED,	/* the next read will be held */
	SIM_DIO_HOLD_HOLDING,	/* a read is being held */
	SIM_DIO_HOLD_EXPIRED,	/* the last held read ended by its time limit */
};

/* Bit-level I2C slave (ts7800-sim-i2c.c). */
enum sim_i2c_state {
	SIM_I2C_IDLE,		/* waiting for a START */
	SIM_I2C_ADDR,		/* receiving the address byte */
	SIM_I2C_ADDR_ACK,	/* driving the ACK of the address */
	SIM_I2C_WDATA,		/* receiving a data byte */
	SIM_I2C_WDATA_ACK,	/* driving the ACK of a data byte */
	SIM_I2C_RDATA,		/* sending a data byte */
	SIM_I2C_RDATA_ACK,	/* sampling the master's ACK/NACK */
};

struct sim_i2c {
	enum sim_i2c_state state;
	bool scl, sda;		/* bus levels seen last */
	bool drive_low;		/* the slave pulls SDA low */
	bool read;		/* R/W bit of the current transfer */
	bool first;		/* next written byte is the register pointer */
	bool acked;		/* master's ACK of the last byte sent */
	unsigned int bits;
	u8 shift;
	/* what the bus saw, for tests */
	u32 starts, stops, addr_acks, addr_nacks;
};

/* One debugfs file of the MAX6615 model: a channel (temperature or fan). */
struct sim_chip_knob {
	struct ts7800_sim *sim;
	unsigned int idx;
};

/* Register model of a MAX6615 (ts7800-sim-max6615.c). */
struct sim_max6615 {
	u8 addr;		/* 7-bit bus address */
	u8 reg[256];
	u8 ptr;			/* register pointer */
	int temp_mc[2];		/* temperatures, millidegrees C (debugfs) */
	unsigned int rpm[2];	/* fan speeds (debugfs) */
	bool fan_on[2][2];	/* auto mode hysteresis state per fan, channel */
	ktime_t ramp_t[2];	/* when the instantaneous duty last stepped */
	struct sim_chip_knob knobs[2];
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

	struct sim_dio dio;
	struct sim_i2c i2c;
	struct sim_max6615 fan;

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
void ts7800_sim_irq_raise(struct ts7800_sim *sim, unsigned int hwirq);

/* ts7800-sim-uart.c */
int sim_uart_init(struct ts7800_sim *sim, struct sim_uart *u, unsigned int idx);
void sim_uart_stop(struct sim_uart *u);
int sim_reg_read(void *context, unsigned int reg, unsigned int *val);
int sim_reg_write(void *context, unsigned int reg, unsigned int val);
void sim_uart_rx_kick(struct sim_uart *u);
void sim_uart_tx_kick(struct sim_uart *u);
void sim_uart_log(struct sim_uart *u, u16 w, ktime_t t, u8 dir);

/* ts7800-sim-wire.c */
int sim_wire_register(struct sim_uart *u);
void sim_wire_unregister(struct sim_uart *u);

/* ts7800-sim-dio.c (all with sim->lock held, except the debugfs setup) */
int sim_dio_init(struct ts7800_sim *sim);
u16 sim_dio_read_in(struct ts7800_sim *sim);
void sim_dio_hold_read(struct ts7800_sim *sim);
void sim_dio_write_out(struct ts7800_sim *sim, u16 val);
void sim_dio_update(struct ts7800_sim *sim);
void sim_dio_debugfs_init(struct ts7800_sim *sim);

/* ts7800-sim-i2c.c (sim->lock held) */
void sim_i2c_bus(struct ts7800_sim *sim, bool scl, bool sda);

/* ts7800-sim-max6615.c (sim->lock held, except init and debugfs setup) */
int sim_max6615_param_addr(void);
void sim_max6615_init(struct sim_max6615 *chip, u8 addr);
void sim_max6615_update(struct sim_max6615 *chip);
bool sim_max6615_fan_fail(struct sim_max6615 *chip);
u8 sim_max6615_read(struct sim_max6615 *chip);
void sim_max6615_write(struct sim_max6615 *chip, u8 val, bool pointer);
void sim_max6615_debugfs_init(struct ts7800_sim *sim);

/* ts7800-sim-debugfs.c */
void sim_debugfs_init(struct ts7800_sim *sim);

#endif /* TS7800_SIM_H */
