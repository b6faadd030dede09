// SPDX-License-Identifier: GPL-2.0
/*
 * Simulated TS-7800 FPGA: TS-UART register and line model.
 *
 * Each port has an RX and a TX FIFO of sim_fifo_depth characters and a shift
 * register per direction. A character occupies the line for
 * bits x divisor x 80 ns (12.5 MHz bit clock; 10 bits, 11 in MODE9); the
 * engines are absolute-time hrtimers, so back-to-back characters do not drift
 * when a timer fires a little late. A timer that fires more than a character
 * time late means the simulator itself was not running (a stalled virtual
 * CPU); the line then pauses for that time (counted as stall) rather than
 * delivering a burst that no real line could carry.
 *
 * Choices for what the notes leave unknown are collected in
 * ts7800_sim_irq_source() (ts7800-sim-main.c) and here, marked "MODEL:".
 */
#include <linux/bitfield.h>
#include <linux/hrtimer.h>
#include <linux/ktime.h>
#include <linux/math64.h>
#include <linux/preempt.h>
#include <linux/slab.h>

#include "ts7800-sim.h"

/*
 * The engines' timers take the model's lock, a spinlock_t: they expire in
 * hard irq context, except on PREEMPT_RT, where that lock sleeps and timers
 * not marked _HARD expire in the softirq thread (a _HARD one there got
 * "BUG: scheduling while atomic" in sim_tx_timer when the lock was taken).
 */
#define SIM_ENGINE_MODE	HRTIMER_MODE_ABS

/* After an engine's step: raise what is pending from the context it ran in. */
static void sim_engine_irq(struct ts7800_sim *sim)
{
	if (in_hardirq())
		ts7800_sim_irq_deliver(sim);
	else
		ts7800_sim_irq_kick(sim);	/* PREEMPT_RT: the hard irq_work */
}

static struct sim_uart *sim_port_of(struct ts7800_sim *sim, unsigned int reg)
{
	unsigned int n = (reg - TS7800_UART_BASE(0)) / TS7800_UART_REGS_SIZE;

	return n < sim->nports ? &sim->uart[n] : NULL;
}

static u16 sim_ring_peek(const struct sim_ring *r)
{
	return r->buf[r->head];
}

static u16 sim_ring_pop(struct sim_ring *r)
{
	u16 w = r->buf[r->head];

	r->head = (r->head + 1) % r->depth;
	r->count--;
	return w;
}

static bool sim_ring_push(struct sim_ring *r, u16 w)
{
	if (r->count == r->depth)
		return false;
	r->buf[(r->head + r->count) % r->depth] = w;
	r->count++;
	return true;
}

/* Character time from the port's baud code, DIV8 and MODE9; 0 = line off. */
static u64 sim_char_ns(struct sim_uart *u)
{
	unsigned int code = FIELD_GET(TS7800_STAT_BAUD, u->ctrl);
	u64 div = u->sim->divisors[code];
	u64 bits = (u->ctrl & TS7800_STAT_MODE9) ? 11 : 10;

	/* MODEL: code 7 has no divisor slot on the board; it stops the line. */
	if (code >= TS7800_UART_NR_CODES || !div)
		return 0;
	if (u->ctrl & TS7800_STAT_DIV8)
		div *= 8;
	return bits * div * TS7800_UART_BITCLK_NS;
}

static u16 sim_char_mask(struct sim_uart *u)
{
	return (u->ctrl & TS7800_STAT_MODE9) ? TS7800_DATA_MASK9 : TS7800_DATA_MASK8;
}

static void sim_uart_update_irq(struct sim_uart *u)
{
	bool level = u->rx.count || u->tx_event;

	ts7800_sim_irq_source(u->sim, TS7800_FPGA_HWIRQ_UART(u->idx), level);
}

static bool sim_apply_fault(struct sim_uart *u, struct sim_fault *f, u16 *w)
{
	if (f->drop) {
		f->drop--;
		u->stats.faults++;
		return false;
	}
	if (f->corrupt) {
		f->corrupt--;
		*w ^= f->corrupt_xor;
		u->stats.faults++;
	}
	return true;
}

/* TS7800_SIM_SET_LOG: note a character that ended at @t (sim->lock held). */
void sim_uart_log(struct sim_uart *u, u16 w, ktime_t t, u8 dir)
{
	struct ts7800_sim_line_event ev = {
		.end_ns = ktime_to_ns(t),
		.char_ns = u->stats.char_ns,
		.word = w,
		.dir = dir,
	};

	if (u->log_on && !kfifo_put(&u->log, ev))
		u->log_dropped++;
}

/*
 * TS7800_SIM_GET_GAPS: a character of direction @dir ended on u's line at
 * @t; the idle line before it (sim->lock held). A pause of the line for a
 * stalled simulator (sim_next_slot()) since the last character is not idle
 * line: the character was due when the pause began.
 */
static void sim_line_gap(struct sim_uart *u, u16 w, ktime_t t, u8 dir)
{
	struct ts7800_sim_line_gaps *g = &u->gaps;
	ktime_t start = ktime_sub_ns(t, u->stats.char_ns);
	u64 idle = 0;

	if (u->line_end && ktime_after(start, u->line_end))
		idle = ktime_to_ns(ktime_sub(start, u->line_end));
	idle = idle > u->line_stall_ns ? idle - u->line_stall_ns : 0;
	u->line_stall_ns = 0;
	if (ktime_after(t, u->line_end))
		u->line_end = t;
	if (w & TS7800_SIM_WORD_BIT9) {
		g->frames[dir]++;
		g->frame_idle_ns[dir] += idle;
		g->frame_idle_max_ns[dir] = max(g->frame_idle_max_ns[dir], idle);
	} else {
		g->chars[dir]++;
		g->char_idle_ns[dir] += idle;
		g->char_idle_max_ns[dir] = max(g->char_idle_max_ns[dir], idle);
	}
}

/*
 * A character (or break) arrived completely at u's receiver at time t;
 * @echo: it is u's own, heard back (already counted on the line).
 */
static void sim_rx_complete(struct sim_uart *u, u16 w, ktime_t t, bool echo)
{
	u16 entry;

	if (!echo)
		sim_line_gap(u, w, t, TS7800_SIM_LOG_RX);
	if (!sim_apply_fault(u, &u->rx_fault, &w))
		return;
	sim_uart_log(u, w, t, TS7800_SIM_LOG_RX);
	if (w & TS7800_SIM_WORD_FRAME)
		u->stats.framing_errors++;
	entry = (w & TS7800_SIM_WORD_BREAK) ? SIM_RX_BREAK : (w & TS7800_SIM_WORD_CHAR);

	/* MODEL: like a 16550, the character that finds the FIFO full is lost. */
	if (!sim_ring_push(&u->rx, entry)) {
		u->oerr = true;
		u->stats.rx_overruns++;
		return;
	}
	if (!u->stats.from_wire)
		u->stats.from_wire_first_ns = ktime_to_ns(t) - u->stats.char_ns;
	u->stats.from_wire++;
	u->stats.from_wire_last_ns = ktime_to_ns(t);
	sim_uart_update_irq(u);
}

/* u's transmitter finished a character (or sends a break) at time t. */
static void sim_tx_deliver(struct sim_uart *u, u16 w, ktime_t t)
{
	struct sim_uart *peer;

	if (!sim_apply_fault(u, &u->tx_fault, &w))
		return;
	sim_line_gap(u, w, t, TS7800_SIM_LOG_TX);
	sim_uart_log(u, w, t, TS7800_SIM_LOG_TX);
	u->stats.to_wire++;
	u->stats.to_wire_last_ns = ktime_to_ns(t);
	if (!kfifo_put(&u->line_out, w))
		u->stats.to_wire_dropped++;
	if (kfifo_len(&u->line_out) >= SIM_WIRE_WAKE_WORDS)
		wake_up_interruptible(&u->wait_out);

	/* MODEL: a cross-connected peer gets the character as sent, at any rate. */
	if (u->peer >= 0) {
		peer = &u->sim->uart[u->peer];
		sim_rx_complete(peer, w, t, false);
	}
	/* MODEL: a 2-wire transceiver with its receiver on hears the line. */
	if (u->echo)
		sim_rx_complete(u, w, t, true);
}

static ktime_t sim_start_time(ktime_t line_free)
{
	ktime_t now = ktime_get();

	return ktime_after(line_free, now) ? line_free : now;
}

/*
 * Characters simulated per timer expiry (a slice): as many as take 1 ms, at
 * most half a FIFO, at least one. Every character keeps its exact time; the
 * characters of a slice just enter the RX FIFO, and leave the TX FIFO,
 * together. This bounds the timer wake-ups of an emulated CPU at high rates
 * (at 115200 Bd one per 8 characters with FIFO depth 16) without changing
 * the line rate, and half a FIFO per slice cannot overrun a FIFO that the
 * driver serves after each slice. The delay this adds is at most 1 ms.
 */
static unsigned int sim_slice_chars(struct sim_uart *u, u64 ns)
{
	unsigned int n = min_t(u64, div64_u64(SIM_SLICE_NS, ns), SIM_SLICE_MAX);

	return clamp(min(n, u->rx.depth / 2), 1U, SIM_SLICE_MAX);
}

/*
 * End of the next slice after one that ended at @done: back to back, unless
 * the simulator ran more than a slice late (see the top of this file).
 */
static ktime_t sim_next_slot(struct sim_uart *u, ktime_t done, ktime_t now, u64 slice_ns,
			     __u64 *stall_ns)
{
	ktime_t next = ktime_add_ns(done, slice_ns);
	u64 stall;

	if (ktime_after(next, now))
		return next;
	stall = ktime_to_ns(ktime_sub(now, done));
	*stall_ns += stall;
	u->line_stall_ns += stall;	/* not idle line (sim_line_gap()) */
	return ktime_add_ns(now, slice_ns);
}

/* Size the next receive slice; returns its length in ns (0: line stops). */
static u64 sim_rx_slice(struct sim_uart *u)
{
	u64 ns = sim_char_ns(u);

	if (!ns || u->sim->stopping || kfifo_is_empty(&u->line_in))
		return 0;
	u->stats.char_ns = ns;
	u->rx_nslice = min(sim_slice_chars(u, ns), kfifo_len(&u->line_in));
	return u->rx_nslice * ns;
}

void sim_uart_rx_kick(struct sim_uart *u)
{
	u64 slice_ns;

	if (u->rx_busy)
		return;
	slice_ns = sim_rx_slice(u);
	if (!slice_ns)
		return;
	u->rx_busy = true;
	hrtimer_start(&u->rx_timer, ktime_add_ns(sim_start_time(u->rx_line_free), slice_ns),
		      SIM_ENGINE_MODE);
}

static enum hrtimer_restart sim_rx_timer(struct hrtimer *t)
{
	struct sim_uart *u = container_of(t, struct sim_uart, rx_timer);
	enum hrtimer_restart ret = HRTIMER_NORESTART;
	ktime_t done = hrtimer_get_expires(t);
	unsigned long flags;
	unsigned int i;
	u64 ns, slice_ns;
	u16 w;

	spin_lock_irqsave(&u->sim->lock, flags);
	ns = u->stats.char_ns;
	for (i = u->rx_nslice; i > 0 && kfifo_get(&u->line_in, &w); i--)
		sim_rx_complete(u, w, ktime_sub_ns(done, (i - 1) * ns), false);
	u->rx_line_free = done;
	if (kfifo_avail(&u->line_in) >= SIM_WIRE_WAKE_ROOM || kfifo_is_empty(&u->line_in))
		wake_up_interruptible(&u->wait_in);

	slice_ns = sim_rx_slice(u);
	if (!slice_ns) {
		u->rx_busy = false;
	} else {
		hrtimer_set_expires(t, sim_next_slot(u, done, ktime_get(), slice_ns,
						     &u->stats.from_wire_stall_ns));
		ret = HRTIMER_RESTART;
	}
	spin_unlock_irqrestore(&u->sim->lock, flags);
	sim_engine_irq(u->sim);
	return ret;
}

static bool sim_tx_may_start(struct sim_uart *u)
{
	if (!u->tx.count || u->sim->stopping || (u->ctrl & TS7800_STAT_TXBRK))
		return false;
	return !(u->ctrl & TS7800_STAT_HWCTS) || u->cts;
}

/*
 * Move the next slice of characters into the shift register; returns its
 * length in ns, 0 if the transmitter stays idle.
 */
static u64 sim_tx_load(struct sim_uart *u)
{
	u64 ns = sim_char_ns(u);
	unsigned int max;

	if (!ns || !sim_tx_may_start(u))
		return 0;
	u->stats.char_ns = ns;
	max = sim_slice_chars(u, ns);
	for (u->tx_nshift = 0; u->tx_nshift < max && u->tx.count; u->tx_nshift++)
		u->tx_shift[u->tx_nshift] = sim_ring_pop(&u->tx) & sim_char_mask(u);
	u->tx_busy = true;
	/*
	 * MODEL: the TX interrupt event is "TX FIFO at or below half full" after
	 * characters left it (for depth 1: empty), cleared by a STAT read or a
	 * DATA write. The driver must also cope with "empty" only.
	 */
	if (u->tx.count <= u->tx.depth / 2) {
		u->tx_event = true;
		sim_uart_update_irq(u);
	}
	return u->tx_nshift * ns;
}

void sim_uart_tx_kick(struct sim_uart *u)
{
	ktime_t start;
	u64 slice_ns;

	if (u->tx_busy)
		return;
	start = sim_start_time(u->tx_line_free);
	slice_ns = sim_tx_load(u);
	if (!slice_ns)
		return;
	if (!u->stats.to_wire)
		u->stats.to_wire_first_ns = ktime_to_ns(start);
	hrtimer_start(&u->tx_timer, ktime_add_ns(start, slice_ns), SIM_ENGINE_MODE);
}

static enum hrtimer_restart sim_tx_timer(struct hrtimer *t)
{
	struct sim_uart *u = container_of(t, struct sim_uart, tx_timer);
	enum hrtimer_restart ret = HRTIMER_NORESTART;
	ktime_t done = hrtimer_get_expires(t);
	unsigned long flags;
	unsigned int i;
	u64 ns, slice_ns;

	spin_lock_irqsave(&u->sim->lock, flags);
	ns = u->stats.char_ns;
	for (i = 0; i < u->tx_nshift; i++)
		sim_tx_deliver(u, u->tx_shift[i],
			       ktime_sub_ns(done, (u->tx_nshift - 1 - i) * ns));
	u->tx_busy = false;
	u->tx_line_free = done;

	slice_ns = sim_tx_load(u);
	if (!slice_ns) {
		/* The line went idle: the far end sees everything now. */
		wake_up_interruptible(&u->wait_out);
	} else {
		hrtimer_set_expires(t, sim_next_slot(u, done, ktime_get(), slice_ns,
						     &u->stats.to_wire_stall_ns));
		ret = HRTIMER_RESTART;
	}
	spin_unlock_irqrestore(&u->sim->lock, flags);
	sim_engine_irq(u->sim);
	return ret;
}

static u16 sim_stat_read(struct sim_uart *u)
{
	u16 v = u->ctrl;

	if (u->tx.count < u->tx.depth)
		v |= TS7800_STAT_TBRE;
	if (u->rx.count) {
		v |= TS7800_STAT_DR;
		/* MODEL: RXBRK describes the character at the head of the FIFO. */
		if (sim_ring_peek(&u->rx) & SIM_RX_BREAK)
			v |= TS7800_STAT_RXBRK;
	}
	if (u->oerr)
		v |= TS7800_STAT_OERR;
	if (u->cts)
		v |= TS7800_STAT_CTS;
	if (!u->tx.count && !u->tx_busy)
		v |= TS7800_STAT_TRE;

	/* MODEL: reading STAT clears OERR (unless oerr_clear_on_data) and the TX event. */
	if (!sim_oerr_clear_on_data)
		u->oerr = false;
	if (u->tx_event) {
		u->tx_event = false;
		sim_uart_update_irq(u);
	}
	return v;
}

static u16 sim_data_read(struct sim_uart *u)
{
	u16 entry;

	if (!u->rx.count)
		return 0;
	entry = sim_ring_pop(&u->rx);
	if (sim_oerr_clear_on_data)
		u->oerr = false;
	sim_uart_update_irq(u);
	return (entry & SIM_RX_BREAK) ? 0 : entry & sim_char_mask(u);
}

static void sim_data_write(struct sim_uart *u, u16 val)
{
	/* MODEL: a write while the FIFO is full is lost, as on a 16550. */
	if (!sim_ring_push(&u->tx, val & TS7800_DATA_MASK9))
		dev_warn_ratelimited(u->sim->dev, "uart%u: DATA written with TX FIFO full\n",
				     u->idx);
	if (u->tx_event) {
		u->tx_event = false;
		sim_uart_update_irq(u);
	}
	sim_uart_tx_kick(u);
}

static void sim_stat_write(struct sim_uart *u, u16 val)
{
	u16 old = u->ctrl;

	u->ctrl = val & TS7800_STAT_CTRL_MASK;
	if ((u->ctrl & TS7800_STAT_TXBRK) && !(old & TS7800_STAT_TXBRK)) {
		sim_tx_deliver(u, TS7800_SIM_WORD_BREAK, ktime_get());
		wake_up_interruptible(&u->wait_out);
	}
	sim_uart_tx_kick(u);
	sim_uart_rx_kick(u);
}

static u16 sim_half(u32 reg32, unsigned int reg)
{
	return (reg & 2) ? reg32 >> 16 : reg32 & 0xffff;
}

static u32 sim_set_half(u32 reg32, unsigned int reg, u16 val)
{
	return (reg & 2) ? (reg32 & 0xffff) | ((u32)val << 16) :
			   (reg32 & 0xffff0000) | val;
}

int sim_reg_read(void *context, unsigned int reg, unsigned int *val)
{
	struct ts7800_sim *sim = context;
	struct sim_uart *u;
	unsigned long flags, irqflags;

	if (reg == TS7800_DIO_IN)
		sim_dio_hold_read(sim);	/* outside the model lock */
	spin_lock_irqsave(&sim->lock, flags);
	switch (reg) {
	case TS7800_FPGA_ID_LO:
	case TS7800_FPGA_ID_HI:
		*val = sim_half(TS7800_FPGA_ID_MAGIC << 8 | 0x0b, reg);
		break;
	case TS7800_FPGA_PC104_ROWC_LO:
	case TS7800_FPGA_PC104_ROWC_HI:
		*val = sim_half(sim->rowc, reg);
		break;
	case TS7800_DIO_IN:
		*val = sim_dio_read_in(sim);
		break;
	case TS7800_DIO_OUT:
		*val = sim->dio.out;
		break;
	case TS7800_UART_BASE(0) ... TS7800_UART_BASE(TS7800_UART_MAX_PORTS) - 1:
		u = sim_port_of(sim, reg);
		if (!u)
			*val = 0;
		else if ((reg & 3) == TS7800_UART_STAT)
			*val = sim_stat_read(u);
		else
			*val = sim_data_read(u);
		break;
	case TS7800_UART_DIVISOR(0) ... TS7800_UART_DIVISOR(TS7800_UART_NR_CODES):
		*val = sim->divisors[(reg - TS7800_UART_DIVISOR(0)) / 2];
		break;
	case TS7800_FPGA_IRQ_MASK_LO:
	case TS7800_FPGA_IRQ_MASK_HI:
		/* irqsave: sim->lock keeps irqs on under PREEMPT_RT */
		raw_spin_lock_irqsave(&sim->irq_lock, irqflags);
		*val = sim_half(sim->irq_enable, reg);
		raw_spin_unlock_irqrestore(&sim->irq_lock, irqflags);
		break;
	default:
		*val = 0;
		break;
	}
	spin_unlock_irqrestore(&sim->lock, flags);
	ts7800_sim_irq_kick(sim);
	return 0;
}

int sim_reg_write(void *context, unsigned int reg, unsigned int val)
{
	struct ts7800_sim *sim = context;
	struct sim_uart *u;
	unsigned long flags, irqflags;

	/*
	 * MODEL: the window takes 16-bit accesses only (docs/tsuart.md,
	 * "Access width"); a wider value means a driver treats a register as
	 * 32 bits wide.
	 */
	if (val > U16_MAX) {
		dev_err_ratelimited(sim->dev, "write of 0x%x to 0x%03x refused: 16-bit accesses only\n",
				    val, reg);
		return -EINVAL;
	}
	spin_lock_irqsave(&sim->lock, flags);
	switch (reg) {
	case TS7800_FPGA_PC104_ROWC_LO:
	case TS7800_FPGA_PC104_ROWC_HI:
		sim->rowc = sim_set_half(sim->rowc, reg, val);
		break;
	case TS7800_DIO_OUT:
		sim_dio_write_out(sim, val);
		break;
	case TS7800_UART_BASE(0) ... TS7800_UART_BASE(TS7800_UART_MAX_PORTS) - 1:
		u = sim_port_of(sim, reg);
		if (u && (reg & 3) == TS7800_UART_STAT)
			sim_stat_write(u, val);
		else if (u)
			sim_data_write(u, val);
		break;
	case TS7800_UART_DIVISOR(0) ... TS7800_UART_DIVISOR(TS7800_UART_NR_CODES):
		sim->divisors[(reg - TS7800_UART_DIVISOR(0)) / 2] = val;
		break;
	case TS7800_FPGA_IRQ_MASK_LO:
	case TS7800_FPGA_IRQ_MASK_HI:
		/* irqsave: sim->lock keeps irqs on under PREEMPT_RT */
		raw_spin_lock_irqsave(&sim->irq_lock, irqflags);
		sim->irq_enable = sim_set_half(sim->irq_enable, reg, val);
		raw_spin_unlock_irqrestore(&sim->irq_lock, irqflags);
		break;
	default:
		break;	/* MODEL: other registers ignore writes */
	}
	spin_unlock_irqrestore(&sim->lock, flags);
	ts7800_sim_irq_kick(sim);
	return 0;
}

int sim_uart_init(struct ts7800_sim *sim, struct sim_uart *u, unsigned int idx)
{
	u->sim = sim;
	u->idx = idx;
	u->cts = true;
	u->peer = -1;
	u->rx_fault.corrupt_xor = 0x01;
	u->tx_fault.corrupt_xor = 0x01;
	/* MODEL: reset value of STAT control bits: 115200 Bd, 8-bit, RTS off. */
	u->ctrl = 0;
	INIT_KFIFO(u->line_in);
	INIT_KFIFO(u->line_out);
	init_waitqueue_head(&u->wait_in);
	init_waitqueue_head(&u->wait_out);
	u->rx.depth = sim_fifo_depth;
	u->tx.depth = sim_fifo_depth;
	u->stats.fifo_depth = sim_fifo_depth;
	u->rx.buf = devm_kcalloc(sim->dev, sim_fifo_depth, sizeof(u16), GFP_KERNEL);
	u->tx.buf = devm_kcalloc(sim->dev, sim_fifo_depth, sizeof(u16), GFP_KERNEL);
	if (!u->rx.buf || !u->tx.buf)
		return -ENOMEM;
	hrtimer_init(&u->rx_timer, CLOCK_MONOTONIC, SIM_ENGINE_MODE);
	u->rx_timer.function = sim_rx_timer;
	hrtimer_init(&u->tx_timer, CLOCK_MONOTONIC, SIM_ENGINE_MODE);
	u->tx_timer.function = sim_tx_timer;
	return 0;
}

/* Caller has set sim->stopping under the lock: no engine restarts. */
void sim_uart_stop(struct sim_uart *u)
{
	hrtimer_cancel(&u->rx_timer);
	hrtimer_cancel(&u->tx_timer);
	wake_up_interruptible_all(&u->wait_in);
	wake_up_interruptible_all(&u->wait_out);
}
