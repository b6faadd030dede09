// SPDX-License-Identifier: GPL-2.0
/*
 * Simulated TS-7800 FPGA: the wire of each TS-UART, /dev/ts7800-sim/uartN.
 *
 * User space is the far end of the line (protocol in
 * include/uapi/linux/ts7800_sim.h): it reads the words the UART transmitted
 * and writes words for the UART to receive. Data is copied through a small
 * bounce buffer because the queues live under the model's spinlock.
 */
#include <linux/fs.h>
#include <linux/poll.h>
#include <linux/sched/signal.h>
#include <linux/uaccess.h>

#include "ts7800-sim.h"

#define WIRE_BATCH	64	/* words per locked step */
#define LOG_BATCH	32	/* line log events per locked step */

static struct sim_uart *wire_uart(struct file *file)
{
	struct miscdevice *misc = file->private_data;

	return container_of(misc, struct sim_uart, misc);
}

static int wire_open(struct inode *inode, struct file *file)
{
	return nonseekable_open(inode, file);
}

static bool wire_readable(struct sim_uart *u)
{
	return !kfifo_is_empty(&u->line_out) || READ_ONCE(u->sim->stopping);
}

static bool wire_writable(struct sim_uart *u)
{
	return !kfifo_is_full(&u->line_in) || READ_ONCE(u->sim->stopping);
}

static ssize_t wire_read(struct file *file, char __user *buf, size_t count, loff_t *ppos)
{
	struct sim_uart *u = wire_uart(file);
	struct ts7800_sim *sim = u->sim;
	__le16 out[WIRE_BATCH];
	u16 w[WIRE_BATCH];
	size_t done = 0, want;
	unsigned int n, i;
	unsigned long flags;
	int ret;

	if (count < sizeof(u16))
		return -EINVAL;
	while (done + sizeof(u16) <= count) {
		want = min_t(size_t, (count - done) / sizeof(u16), WIRE_BATCH);
		spin_lock_irqsave(&sim->lock, flags);
		n = kfifo_out(&u->line_out, w, want);
		spin_unlock_irqrestore(&sim->lock, flags);
		if (!n) {
			if (done)
				break;
			if (file->f_flags & O_NONBLOCK)
				return -EAGAIN;
			ret = wait_event_interruptible(u->wait_out, wire_readable(u));
			if (ret)
				return ret;
			if (READ_ONCE(sim->stopping))
				return 0;
			continue;
		}
		for (i = 0; i < n; i++)
			out[i] = cpu_to_le16(w[i]);
		if (copy_to_user(buf + done, out, n * sizeof(u16)))
			return done ? done : -EFAULT;
		done += n * sizeof(u16);
	}
	return done;
}

static ssize_t wire_write(struct file *file, const char __user *buf, size_t count,
			  loff_t *ppos)
{
	struct sim_uart *u = wire_uart(file);
	struct ts7800_sim *sim = u->sim;
	__le16 in[WIRE_BATCH];
	u16 w[WIRE_BATCH];
	size_t done = 0, want;
	unsigned int n, i;
	unsigned long flags;
	int ret;

	if (count % sizeof(u16))
		return -EINVAL;
	while (done < count) {
		want = min_t(size_t, (count - done) / sizeof(u16), WIRE_BATCH);
		if (copy_from_user(in, buf + done, want * sizeof(u16)))
			return done ? done : -EFAULT;
		for (i = 0; i < want; i++)
			w[i] = le16_to_cpu(in[i]) & (TS7800_SIM_WORD_CHAR | TS7800_SIM_WORD_FLAGS);

		spin_lock_irqsave(&sim->lock, flags);
		n = sim->stopping ? 0 : kfifo_in(&u->line_in, w, want);
		if (n)
			sim_uart_rx_kick(u);
		spin_unlock_irqrestore(&sim->lock, flags);
		done += n * sizeof(u16);
		if (n == want)
			continue;
		if (done || (file->f_flags & O_NONBLOCK))
			break;
		ret = wait_event_interruptible(u->wait_in, wire_writable(u));
		if (ret)
			return ret;
		if (READ_ONCE(sim->stopping))
			return -ENODEV;
	}
	return done ? done : -EAGAIN;
}

static __poll_t wire_poll(struct file *file, poll_table *wait)
{
	struct sim_uart *u = wire_uart(file);
	__poll_t mask = 0;

	poll_wait(file, &u->wait_out, wait);
	poll_wait(file, &u->wait_in, wait);
	if (!kfifo_is_empty(&u->line_out))
		mask |= EPOLLIN | EPOLLRDNORM;
	if (!kfifo_is_full(&u->line_in))
		mask |= EPOLLOUT | EPOLLWRNORM;
	if (READ_ONCE(u->sim->stopping))
		mask |= EPOLLHUP;
	return mask;
}

/* TS7800_SIM_SET_LOG: the buffer is allocated once, for the device's life. */
static int wire_set_log(struct sim_uart *u, u32 on)
{
	struct ts7800_sim *sim = u->sim;
	struct ts7800_sim_line_event *buf = NULL;
	unsigned long flags;

	if (on > 1)
		return -EINVAL;
	if (on && !kfifo_initialized(&u->log)) {
		buf = devm_kcalloc(sim->dev, TS7800_SIM_LOG_EVENTS, sizeof(*buf), GFP_KERNEL);
		if (!buf)
			return -ENOMEM;
	}
	spin_lock_irqsave(&sim->lock, flags);
	if (buf && !kfifo_initialized(&u->log)) {
		kfifo_init(&u->log, buf, TS7800_SIM_LOG_EVENTS * sizeof(*buf));
		buf = NULL;
	}
	if (on) {
		kfifo_reset(&u->log);
		u->log_dropped = 0;
	}
	u->log_on = on;
	spin_unlock_irqrestore(&sim->lock, flags);
	if (buf)
		devm_kfree(sim->dev, buf);	/* another caller was first */
	return 0;
}

static int wire_read_log(struct sim_uart *u, void __user *arg)
{
	struct ts7800_sim *sim = u->sim;
	struct ts7800_sim_line_event ev[LOG_BATCH];
	struct ts7800_sim_line_event __user *dst;
	struct ts7800_sim_log_read rd;
	unsigned long flags;
	unsigned int n;

	if (copy_from_user(&rd, arg, sizeof(rd)))
		return -EFAULT;
	if (rd.pad)
		return -EINVAL;
	dst = u64_to_user_ptr(rd.events);
	rd.count = 0;
	spin_lock_irqsave(&sim->lock, flags);
	rd.dropped = u->log_dropped;
	u->log_dropped = 0;
	spin_unlock_irqrestore(&sim->lock, flags);
	while (rd.count < rd.max) {
		spin_lock_irqsave(&sim->lock, flags);
		n = kfifo_initialized(&u->log) ?
		    kfifo_out(&u->log, ev, min_t(u32, rd.max - rd.count, LOG_BATCH)) : 0;
		spin_unlock_irqrestore(&sim->lock, flags);
		if (!n)
			break;
		/* Events taken but not copied are lost, like a short read(). */
		if (copy_to_user(dst + rd.count, ev, n * sizeof(ev[0])))
			return -EFAULT;
		rd.count += n;
	}
	return copy_to_user(arg, &rd, sizeof(rd)) ? -EFAULT : 0;
}

static long wire_ioctl(struct file *file, unsigned int cmd, unsigned long arg)
{
	struct sim_uart *u = wire_uart(file);
	struct ts7800_sim *sim = u->sim;
	struct ts7800_sim_wire_stats st;
	struct ts7800_sim_line_gaps gaps;
	unsigned long flags;
	u32 level;

	switch (cmd) {
	case TS7800_SIM_GET_STATS:
		spin_lock_irqsave(&sim->lock, flags);
		st = u->stats;
		st.ctrl = u->ctrl;
		spin_unlock_irqrestore(&sim->lock, flags);
		return copy_to_user((void __user *)arg, &st, sizeof(st)) ? -EFAULT : 0;
	case TS7800_SIM_RESET_STATS:
		spin_lock_irqsave(&sim->lock, flags);
		memset(&u->stats, 0, offsetof(struct ts7800_sim_wire_stats, char_ns));
		memset(&u->gaps, 0, sizeof(u->gaps));
		u->line_end = 0;
		u->line_stall_ns = 0;
		spin_unlock_irqrestore(&sim->lock, flags);
		return 0;
	case TS7800_SIM_GET_GAPS:
		spin_lock_irqsave(&sim->lock, flags);
		gaps = u->gaps;
		spin_unlock_irqrestore(&sim->lock, flags);
		return copy_to_user((void __user *)arg, &gaps, sizeof(gaps)) ? -EFAULT : 0;
	case TS7800_SIM_SET_CTS:
		if (get_user(level, (u32 __user *)arg))
			return -EFAULT;
		if (level > 1)
			return -EINVAL;
		spin_lock_irqsave(&sim->lock, flags);
		u->cts = level;
		sim_uart_tx_kick(u);
		spin_unlock_irqrestore(&sim->lock, flags);
		ts7800_sim_irq_kick(sim);
		return 0;
	case TS7800_SIM_SET_ECHO:
		if (get_user(level, (u32 __user *)arg))
			return -EFAULT;
		if (level > 1)
			return -EINVAL;
		spin_lock_irqsave(&sim->lock, flags);
		u->echo = level;
		spin_unlock_irqrestore(&sim->lock, flags);
		return 0;
	case TS7800_SIM_SET_LOG:
		if (get_user(level, (u32 __user *)arg))
			return -EFAULT;
		return wire_set_log(u, level);
	case TS7800_SIM_READ_LOG:
		return wire_read_log(u, (void __user *)arg);
	default:
		return -ENOTTY;
	}
}

static const struct file_operations wire_fops = {
	.owner		= THIS_MODULE,
	.open		= wire_open,
	.read		= wire_read,
	.write		= wire_write,
	.poll		= wire_poll,
	.unlocked_ioctl	= wire_ioctl,
	.compat_ioctl	= compat_ptr_ioctl,
};

int sim_wire_register(struct sim_uart *u)
{
	snprintf(u->name, sizeof(u->name), "ts7800-sim-uart%u", u->idx);
	snprintf(u->nodename, sizeof(u->nodename), "ts7800-sim/uart%u", u->idx);
	u->misc.minor = MISC_DYNAMIC_MINOR;
	u->misc.name = u->name;
	u->misc.nodename = u->nodename;
	u->misc.fops = &wire_fops;
	u->misc.parent = u->sim->dev;
	return misc_register(&u->misc);
}

void sim_wire_unregister(struct sim_uart *u)
{
	misc_deregister(&u->misc);
}
