// SPDX-License-Identifier: GPL-2.0
/*
 * Simulated TS-7800 FPGA: fault injection and wiring through debugfs.
 *
 * /sys/kernel/debug/ts7800-sim/uartN/
 *   rx_drop, rx_corrupt   drop / corrupt the next N characters the UART receives
 *   tx_drop, tx_corrupt   same for the characters it transmits
 *   rx_corrupt_xor, tx_corrupt_xor   bits flipped by corruption (default 0x001)
 *   noise                 write N: N random characters arrive on the line
 *   peer                  cross-connect to port M (both ways), -1 to undo
 * /sys/kernel/debug/ts7800-sim/irq_hold
 *                         1: deliver no interrupt (a late CPU), 0: deliver again
 * /sys/kernel/debug/ts7800-sim/irq_raise
 *                         write k: a spurious interrupt of source k (if enabled)
 */
#include <linux/debugfs.h>
#include <linux/random.h>

#include "ts7800-sim.h"

#define SIM_DEBUGFS_DIR	"ts7800-sim"

/* Every fault knob is read and written under the model lock. */
static int knob_get(void *data, u64 *val)
{
	struct sim_knob *k = data;
	unsigned long flags;

	spin_lock_irqsave(&k->u->sim->lock, flags);
	*val = *k->val;
	spin_unlock_irqrestore(&k->u->sim->lock, flags);
	return 0;
}

static int knob_set(void *data, u64 val)
{
	struct sim_knob *k = data;
	unsigned long flags;

	if (val > k->max)
		return -EINVAL;
	spin_lock_irqsave(&k->u->sim->lock, flags);
	*k->val = val;
	spin_unlock_irqrestore(&k->u->sim->lock, flags);
	return 0;
}
DEFINE_DEBUGFS_ATTRIBUTE(knob_fops, knob_get, knob_set, "%llu\n");

static void sim_knob_add(struct sim_uart *u, struct dentry *dir, unsigned int i,
			 const char *name, u32 *val, u32 max)
{
	struct sim_knob *k = &u->knobs[i];

	k->u = u;
	k->val = val;
	k->max = max;
	debugfs_create_file_unsafe(name, 0600, dir, k, &knob_fops);
}

static int noise_set(void *data, u64 val)
{
	struct sim_uart *u = data;
	unsigned long flags;
	u16 w;

	if (val > SIM_WIRE_WORDS)
		return -EINVAL;
	spin_lock_irqsave(&u->sim->lock, flags);
	while (val--) {
		w = get_random_u32() & TS7800_SIM_WORD_CHAR;
		if (!kfifo_put(&u->line_in, w))
			break;
	}
	sim_uart_rx_kick(u);
	spin_unlock_irqrestore(&u->sim->lock, flags);
	return 0;
}
DEFINE_DEBUGFS_ATTRIBUTE(noise_fops, NULL, noise_set, "%llu\n");

static int peer_get(void *data, u64 *val)
{
	struct sim_uart *u = data;

	*val = (u64)(s64)READ_ONCE(u->peer);
	return 0;
}

static int peer_set(void *data, u64 val)
{
	struct sim_uart *u = data, *old;
	struct ts7800_sim *sim = u->sim;
	s64 peer = (s64)val;
	unsigned long flags;

	if (peer < -1 || peer >= sim->nports || peer == u->idx)
		return -EINVAL;
	spin_lock_irqsave(&sim->lock, flags);
	if (u->peer >= 0) {
		old = &sim->uart[u->peer];
		old->peer = -1;
	}
	u->peer = peer;
	if (peer >= 0) {
		old = &sim->uart[peer];
		if (old->peer >= 0)
			sim->uart[old->peer].peer = -1;
		old->peer = u->idx;
	}
	spin_unlock_irqrestore(&sim->lock, flags);
	return 0;
}
DEFINE_DEBUGFS_ATTRIBUTE(peer_fops, peer_get, peer_set, "%lld\n");

static int irq_hold_get(void *data, u64 *val)
{
	struct ts7800_sim *sim = data;

	*val = READ_ONCE(sim->irq_hold);
	return 0;
}

static int irq_hold_set(void *data, u64 val)
{
	if (val > 1)
		return -EINVAL;
	ts7800_sim_irq_set_hold(data, val);
	return 0;
}
DEFINE_DEBUGFS_ATTRIBUTE(irq_hold_fops, irq_hold_get, irq_hold_set, "%llu\n");

static int irq_raise_set(void *data, u64 val)
{
	if (val >= TS7800_FPGA_NR_IRQS)
		return -EINVAL;
	ts7800_sim_irq_raise(data, val);
	return 0;
}
DEFINE_DEBUGFS_ATTRIBUTE(irq_raise_fops, NULL, irq_raise_set, "%llu\n");

void sim_debugfs_init(struct ts7800_sim *sim)
{
	struct dentry *dir;
	unsigned int n;
	char name[16];	/* "uart" and any unsigned int (W=1: -Wformat-truncation) */

	sim->debugfs = debugfs_create_dir(SIM_DEBUGFS_DIR, NULL);
	debugfs_create_file_unsafe("irq_hold", 0600, sim->debugfs, sim, &irq_hold_fops);
	debugfs_create_file_unsafe("irq_raise", 0200, sim->debugfs, sim, &irq_raise_fops);
	for (n = 0; n < sim->nports; n++) {
		struct sim_uart *u = &sim->uart[n];

		snprintf(name, sizeof(name), "uart%u", n);
		dir = debugfs_create_dir(name, sim->debugfs);
		sim_knob_add(u, dir, 0, "rx_drop", &u->rx_fault.drop, U32_MAX);
		sim_knob_add(u, dir, 1, "rx_corrupt", &u->rx_fault.corrupt, U32_MAX);
		sim_knob_add(u, dir, 2, "rx_corrupt_xor", &u->rx_fault.corrupt_xor,
			     TS7800_SIM_WORD_CHAR);
		sim_knob_add(u, dir, 3, "tx_drop", &u->tx_fault.drop, U32_MAX);
		sim_knob_add(u, dir, 4, "tx_corrupt", &u->tx_fault.corrupt, U32_MAX);
		sim_knob_add(u, dir, 5, "tx_corrupt_xor", &u->tx_fault.corrupt_xor,
			     TS7800_SIM_WORD_CHAR);
		debugfs_create_file_unsafe("noise", 0200, dir, u, &noise_fops);
		debugfs_create_file_unsafe("peer", 0600, dir, u, &peer_fops);
	}
}
