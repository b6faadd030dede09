// SPDX-License-Identifier: GPL-2.0
/*
 * rs485-user.c - what user space sees: read() of event frames (one frame per
 * call, as n_hdlc does), write() of raw request frames, poll() and the
 * ioctls of <linux/n_rs485.h>.
 */
#include <linux/compat.h>
#include <linux/poll.h>
#include <linux/sched/signal.h>
#include <linux/slab.h>
#include <linux/uaccess.h>

#include "n_rs485.h"

#define RS485_TIMEOUT_MIN_US	100
#define RS485_TIMEOUT_MAX_US	10000000
#define RS485_RETRIES_MAX	16
#define RS485_GAP_MIN		2
#define RS485_GAP_MAX		255
#define RS485_BAUD_MIN		300
#define RS485_BAUD_MAX		4000000

/* Called by the RX machine (no sleeping): a frame for read(). */
void rs485_event_queue(struct rs485_bus *bus, const u8 *frame, unsigned int len)
{
	struct rs485_event *ev = kmalloc(sizeof(*ev), GFP_ATOMIC);
	unsigned long flags;

	spin_lock_irqsave(&bus->lock, flags);
	if (!(frame[2] & N_RS485_RESP_EVENT))
		bus->stats.unexpected++;
	if (!ev || bus->nevents >= RS485_EVENT_QUEUE_MAX) {
		bus->stats.events_dropped++;
		spin_unlock_irqrestore(&bus->lock, flags);
		kfree(ev);
		return;
	}
	memcpy(ev->buf, frame, len);
	ev->len = len;
	list_add_tail(&ev->node, &bus->events);
	bus->nevents++;
	bus->stats.events++;
	spin_unlock_irqrestore(&bus->lock, flags);
	wake_up_interruptible(&bus->tty->read_wait);
}

static struct rs485_event *rs485_event_take(struct rs485_bus *bus)
{
	struct rs485_event *ev;
	unsigned long flags;

	spin_lock_irqsave(&bus->lock, flags);
	ev = list_first_entry_or_null(&bus->events, struct rs485_event, node);
	if (ev) {
		list_del(&ev->node);
		bus->nevents--;
	}
	spin_unlock_irqrestore(&bus->lock, flags);
	return ev;
}

void rs485_events_flush(struct rs485_bus *bus)
{
	struct rs485_event *ev;

	while ((ev = rs485_event_take(bus)))
		kfree(ev);
}

/*
 * The tty core calls read with a 64-byte kernel buffer as long as *cookie is
 * set: the first call takes a frame and keeps it in the cookie, later calls
 * copy from @offset, and a call with nr == 0 (user buffer too short) drops
 * the frame with -EOVERFLOW.
 */
ssize_t rs485_read(struct tty_struct *tty, struct file *file, u8 *kbuf, size_t nr,
		   void **cookie, unsigned long offset)
{
	struct rs485_bus *bus = tty->disc_data;
	struct rs485_event *ev = *cookie;
	DEFINE_WAIT_FUNC(wait, woken_wake_function);
	ssize_t ret = 0;

	if (ev)
		goto have_frame;

	add_wait_queue(&tty->read_wait, &wait);
	for (;;) {
		if (test_bit(TTY_OTHER_CLOSED, &tty->flags)) {
			ret = -EIO;
			break;
		}
		if (tty_hung_up_p(file))
			break;
		ev = rs485_event_take(bus);
		if (ev)
			break;
		if (tty_io_nonblock(tty, file)) {
			ret = -EAGAIN;
			break;
		}
		wait_woken(&wait, TASK_INTERRUPTIBLE, MAX_SCHEDULE_TIMEOUT);
		if (signal_pending(current)) {
			ret = -ERESTARTSYS;
			break;
		}
	}
	remove_wait_queue(&tty->read_wait, &wait);
	if (!ev)
		return ret;
	*cookie = ev;

have_frame:
	if (offset >= ev->len)
		goto done;
	ret = -EOVERFLOW;
	if (!nr)
		goto done;
	ret = min_t(size_t, ev->len - offset, nr);
	memcpy(kbuf, ev->buf + offset, ret);
	if (offset + ret < ev->len)
		return ret;
done:
	*cookie = NULL;
	kfree(ev);
	return ret;
}

static bool rs485_queue_room(struct rs485_bus *bus)
{
	unsigned long flags;
	bool room;

	spin_lock_irqsave(&bus->lock, flags);
	room = bus->queued < RS485_REQ_QUEUE_MAX || bus->dead;
	spin_unlock_irqrestore(&bus->lock, flags);
	return room;
}

/* write(): one frame ADDR INSTR FLAGS LEN DATA, sent as is after the queue. */
ssize_t rs485_write(struct tty_struct *tty, struct file *file, const u8 *buf, size_t nr)
{
	struct rs485_bus *bus = tty->disc_data;
	struct rs485_req *req;
	int ret;

	if (nr < N_RS485_HEADER_LEN || nr != N_RS485_HEADER_LEN + buf[3])
		return -EINVAL;
	req = rs485_req_alloc();
	if (!req)
		return -ENOMEM;
	memcpy(&req->frame, buf, nr);
	req->timeout_us = READ_ONCE(bus->cfg.timeout_us);
	/* The response, if any, goes to read(): wait for it once, no retries. */
	req->expect_resp = buf[0] != N_RS485_ADDR_BROADCAST && !(buf[2] & N_RS485_REQ_NOACK);
	for (;;) {
		ret = rs485_req_submit(bus, req);
		if (ret != -EAGAIN || tty_io_nonblock(tty, file))
			break;
		/* The request queue is full: wait until the worker took one. */
		ret = wait_event_interruptible(tty->write_wait, rs485_queue_room(bus) ||
					       test_bit(TTY_LDISC_CHANGING, &tty->flags));
		if (!ret && test_bit(TTY_LDISC_CHANGING, &tty->flags))
			ret = -EIO;	/* the discipline is being detached */
		if (ret)
			break;
	}
	rs485_req_put(req);
	return ret ? ret : nr;
}

__poll_t rs485_poll(struct tty_struct *tty, struct file *file, struct poll_table_struct *wait)
{
	struct rs485_bus *bus = tty->disc_data;
	unsigned long flags;
	__poll_t mask = 0;

	poll_wait(file, &tty->read_wait, wait);
	poll_wait(file, &tty->write_wait, wait);

	spin_lock_irqsave(&bus->lock, flags);
	if (bus->nevents)
		mask |= EPOLLIN | EPOLLRDNORM;
	if (bus->queued < RS485_REQ_QUEUE_MAX && !bus->dead)
		mask |= EPOLLOUT | EPOLLWRNORM;
	spin_unlock_irqrestore(&bus->lock, flags);
	if (test_bit(TTY_OTHER_CLOSED, &tty->flags) || tty_hung_up_p(file))
		mask |= EPOLLHUP;
	return mask;
}

int rs485_config_check(const struct n_rs485_config *cfg)
{
	unsigned int i;

	for (i = 0; i < ARRAY_SIZE(cfg->reserved); i++)
		if (cfg->reserved[i])
			return -EINVAL;
	if (cfg->flags & ~N_RS485_CFG_ECHO)
		return -EINVAL;
	if (cfg->baud < RS485_BAUD_MIN || cfg->baud > RS485_BAUD_MAX ||
	    cfg->timeout_us < RS485_TIMEOUT_MIN_US || cfg->timeout_us > RS485_TIMEOUT_MAX_US ||
	    cfg->retries > RS485_RETRIES_MAX ||
	    cfg->gap_chars < RS485_GAP_MIN || cfg->gap_chars > RS485_GAP_MAX)
		return -EINVAL;
	return 0;
}

static int rs485_ioc_xfer(struct rs485_bus *bus, void __user *arg)
{
	struct n_rs485_xfer *x;
	struct rs485_req *req;
	int ret;

	x = kzalloc(sizeof(*x), GFP_KERNEL);
	if (!x)
		return -ENOMEM;
	ret = -EFAULT;
	if (copy_from_user(&x->req, arg, sizeof(x->req)) ||
	    copy_from_user(&x->timeout_us, arg + offsetof(struct n_rs485_xfer, timeout_us),
			   2 * sizeof(u32)))
		goto out;
	ret = -EINVAL;
	if ((x->req.flags & ~N_RS485_REQ_NOACK) ||
	    (x->timeout_us != N_RS485_DEFAULT && (x->timeout_us < RS485_TIMEOUT_MIN_US ||
						x->timeout_us > RS485_TIMEOUT_MAX_US)) ||
	    (x->retries != N_RS485_DEFAULT && x->retries > RS485_RETRIES_MAX))
		goto out;
	ret = -ENOMEM;
	req = rs485_req_alloc();
	if (!req)
		goto out;
	memcpy(&req->frame, &x->req, N_RS485_HEADER_LEN + x->req.len);
	req->timeout_us = x->timeout_us == N_RS485_DEFAULT ? READ_ONCE(bus->cfg.timeout_us) :
							   x->timeout_us;
	req->retries = x->retries == N_RS485_DEFAULT ? READ_ONCE(bus->cfg.retries) : x->retries;
	req->expect_resp = x->req.addr != N_RS485_ADDR_BROADCAST &&
			   !(x->req.flags & N_RS485_REQ_NOACK);
	req->is_xfer = true;

	ret = rs485_req_submit(bus, req);
	if (!ret)
		ret = rs485_req_wait(bus, req);
	if (!ret) {
		memcpy(&x->resp, &req->resp, sizeof(x->resp));
		x->timeout_us = req->timeout_us;
		x->retries = req->retries;
		x->status = req->status;
		x->attempts = req->attempts;
		if (copy_to_user(arg, x, sizeof(*x)))
			ret = -EFAULT;
	}
	rs485_req_put(req);
out:
	kfree(x);
	return ret;
}

static int rs485_ioc_set_config(struct rs485_bus *bus, void __user *arg)
{
	struct n_rs485_config cfg;
	int ret;

	if (copy_from_user(&cfg, arg, sizeof(cfg)))
		return -EFAULT;
	ret = rs485_config_check(&cfg);
	if (ret)
		return ret;
	/* The line belongs to the worker: change it between two requests. */
	ret = mutex_lock_interruptible(&bus->line_mutex);
	if (ret)
		return ret;
	ret = rs485_line_set_config(bus, &cfg);
	mutex_unlock(&bus->line_mutex);
	return ret;
}

/*
 * cfg is written under line_mutex and lock: lock suffices to read it, and
 * does not wait for the transaction the worker runs under line_mutex.
 */
static int rs485_ioc_get_config(struct rs485_bus *bus, void __user *arg)
{
	struct n_rs485_config cfg;
	unsigned long flags;

	memset(&cfg, 0, sizeof(cfg));
	spin_lock_irqsave(&bus->lock, flags);
	cfg = bus->cfg;
	spin_unlock_irqrestore(&bus->lock, flags);
	return copy_to_user(arg, &cfg, sizeof(cfg)) ? -EFAULT : 0;
}

/* @size: what the caller's struct n_rs485_stats holds (older: a prefix) */
static int rs485_ioc_get_stats(struct rs485_bus *bus, void __user *arg, size_t size)
{
	struct n_rs485_stats st;
	unsigned long flags;

	memset(&st, 0, sizeof(st));
	spin_lock_irqsave(&bus->lock, flags);
	st = bus->stats;
	spin_unlock_irqrestore(&bus->lock, flags);
	return copy_to_user(arg, &st, size) ? -EFAULT : 0;
}

static int rs485_ioc_node(struct rs485_bus *bus, void __user *arg, bool reset)
{
	struct n_rs485_node node;
	unsigned long flags;
	u16 err;

	if (copy_from_user(&node, arg, sizeof(node)))
		return -EFAULT;
	if (node.pad)
		return -EINVAL;
	spin_lock_irqsave(&bus->lock, flags);
	if (reset)
		bus->node_err[node.addr] = 0;
	err = bus->node_err[node.addr];
	spin_unlock_irqrestore(&bus->lock, flags);
	if (reset)
		return 0;
	node.errors = err;
	node.state = err >= RS485_ERR_OFF ? N_RS485_NODE_OFF :
		     err >= RS485_ERR_PASSIVE ? N_RS485_NODE_PASSIVE : N_RS485_NODE_ACTIVE;
	return copy_to_user(arg, &node, sizeof(node)) ? -EFAULT : 0;
}

static int rs485_ioc_fionread(struct rs485_bus *bus, int __user *arg)
{
	struct rs485_event *ev;
	unsigned long flags;
	int len = 0;

	spin_lock_irqsave(&bus->lock, flags);
	ev = list_first_entry_or_null(&bus->events, struct rs485_event, node);
	if (ev)
		len = ev->len;
	spin_unlock_irqrestore(&bus->lock, flags);
	return put_user(len, arg);
}

int rs485_ioctl(struct tty_struct *tty, unsigned int cmd, unsigned long arg)
{
	struct rs485_bus *bus = tty->disc_data;
	void __user *uarg = (void __user *)arg;

	switch (cmd) {
	case N_RS485_IOC_XFER:
		return rs485_ioc_xfer(bus, uarg);
	case N_RS485_IOC_GET_CONFIG:
		return rs485_ioc_get_config(bus, uarg);
	case N_RS485_IOC_SET_CONFIG:
		return rs485_ioc_set_config(bus, uarg);
	case N_RS485_IOC_GET_STATS:
	case N_RS485_IOC_GET_STATS_V1:
		return rs485_ioc_get_stats(bus, uarg, _IOC_SIZE(cmd));
	case N_RS485_IOC_GET_NODE:
		return rs485_ioc_node(bus, uarg, false);
	case N_RS485_IOC_RESET_NODE:
		return rs485_ioc_node(bus, uarg, true);
	case FIONREAD:
		return rs485_ioc_fionread(bus, uarg);
	default:
		return n_tty_ioctl_helper(tty, cmd, arg);
	}
}

#ifdef CONFIG_COMPAT
/* Every argument is made of fixed-size fields: only the pointer differs. */
int rs485_compat_ioctl(struct tty_struct *tty, unsigned int cmd, unsigned long arg)
{
	switch (cmd) {
	case N_RS485_IOC_XFER:
	case N_RS485_IOC_GET_CONFIG:
	case N_RS485_IOC_SET_CONFIG:
	case N_RS485_IOC_GET_STATS:
	case N_RS485_IOC_GET_STATS_V1:
	case N_RS485_IOC_GET_NODE:
	case N_RS485_IOC_RESET_NODE:
	case FIONREAD:
		return rs485_ioctl(tty, cmd, (unsigned long)compat_ptr(arg));
	default:
		return -ENOIOCTLCMD;
	}
}
#endif
