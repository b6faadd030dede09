// SPDX-License-Identifier: GPL-2.0
/*
 * rs485-main.c - the n_rs485 line discipline: registration, attach, detach,
 * hangup and the receive hook.
 *
 * Attaching turns the tty into the master of a 9-bit multidrop bus (wire
 * protocol: docs/rs485proto.md): the discipline sets the port to the bus
 * rate, 8 data bits and space parity (the 9th bit), and restores the port's
 * termios on detach.
 */
#include <linux/module.h>
#include <linux/slab.h>
#include <linux/tty.h>
#include <compat/tty_ldisc_receive_buf.h>

#include "n_rs485.h"

#define RS485_DEFAULT_BAUD	115200
#define RS485_DEFAULT_TIMEOUT_US	10000
#define RS485_DEFAULT_RETRIES	2
#define RS485_DEFAULT_GAP	2
/* receive_buf is offered this much at a time (the RX machine takes all). */
#define RS485_RECEIVE_ROOM	65536

static int ldisc = N_RS485_DEFAULT_LDISC;
module_param(ldisc, int, 0444);
MODULE_PARM_DESC(ldisc, "line discipline number (default 29 = N_DEVELOPMENT)");

/*
 * The bus rate at attach: the port's speed if someone set one (ldattach -s,
 * stty), i.e. it differs from the speed the tty driver starts its ports
 * with; else the protocol's default. A speed set equal to the driver's
 * initial one cannot be told apart from none: the log says which rule
 * applied.
 */
static void rs485_attach_baud(struct rs485_bus *bus)
{
	struct tty_struct *tty = bus->tty;
	struct n_rs485_config cfg = bus->cfg;
	speed_t initial = tty_termios_baud_rate(&tty->driver->init_termios);

	down_read(&tty->termios_rwsem);
	cfg.baud = tty_termios_baud_rate(&tty->termios);
	up_read(&tty->termios_rwsem);
	if (cfg.baud != initial && !rs485_config_check(&cfg)) {
		bus->cfg.baud = cfg.baud;
		pr_info("%s: n_rs485: %u Bd, the port's speed\n", tty_name(tty), cfg.baud);
	} else {
		pr_info("%s: n_rs485: %u Bd, the default (port at %u Bd, its initial speed)\n",
			tty_name(tty), bus->cfg.baud, cfg.baud);
	}
}

static int rs485_open(struct tty_struct *tty)
{
	struct rs485_bus *bus;
	int ret;

	if (!tty->ops->write)
		return -EOPNOTSUPP;
	bus = kzalloc(sizeof(*bus), GFP_KERNEL);
	if (!bus)
		return -ENOMEM;
	bus->tty = tty;
	spin_lock_init(&bus->lock);
	mutex_init(&bus->line_mutex);
	INIT_LIST_HEAD(&bus->queue);
	INIT_LIST_HEAD(&bus->events);
	init_waitqueue_head(&bus->resp_wait);
	INIT_WORK(&bus->work, rs485_xact_work);
	bus->cfg.baud = RS485_DEFAULT_BAUD;
	bus->cfg.timeout_us = RS485_DEFAULT_TIMEOUT_US;
	bus->cfg.retries = RS485_DEFAULT_RETRIES;
	bus->cfg.gap_chars = RS485_DEFAULT_GAP;
	rs485_attach_baud(bus);
	rs485_rx_reset(bus);

	bus->wq = alloc_ordered_workqueue("n_rs485/%s", 0, tty->name);
	if (!bus->wq) {
		ret = -ENOMEM;
		goto err_free;
	}
	ret = rs485_line_setup(bus);
	if (ret)
		goto err_wq;

	tty->disc_data = bus;
	tty->receive_room = RS485_RECEIVE_ROOM;
	tty_driver_flush_buffer(tty);
	return 0;

err_wq:
	destroy_workqueue(bus->wq);
err_free:
	kfree(bus);
	return ret;
}

static void rs485_close(struct tty_struct *tty)
{
	struct rs485_bus *bus = tty->disc_data;

	if (!bus)
		return;
	rs485_xact_kill(bus);
	/* Waits for the worker: it sees "dead" and ends the request it runs. */
	destroy_workqueue(bus->wq);
	rs485_line_restore(bus);
	rs485_events_flush(bus);
	tty->disc_data = NULL;
	kfree(bus);
}

static void rs485_hangup(struct tty_struct *tty)
{
	struct rs485_bus *bus = tty->disc_data;

	rs485_xact_kill(bus);
	wake_up_interruptible_all(&tty->read_wait);
}

/*
 * TCIFLUSH (and hangup): drop the event frames and the frame being received.
 * The receive state machine belongs to receive_buf, which may be running:
 * it resets itself at its next call.
 */
static void rs485_flush_buffer(struct tty_struct *tty)
{
	struct rs485_bus *bus = tty->disc_data;
	unsigned long flags;

	spin_lock_irqsave(&bus->lock, flags);
	bus->rx_flush = true;
	spin_unlock_irqrestore(&bus->lock, flags);
	rs485_events_flush(bus);
}

static void rs485_receive(struct tty_struct *tty, const u8 *cp, const u8 *fp,
			  size_t count)
{
	rs485_rx_chars(tty->disc_data, cp, fp, count);
}

DEFINE_LDISC_RECEIVE_BUF(rs485_receive_buf, rs485_receive)

static struct tty_ldisc_ops rs485_ldisc = {
	.owner		= THIS_MODULE,
	.num		= N_RS485_DEFAULT_LDISC,
	.name		= "n_rs485",
	.open		= rs485_open,
	.close		= rs485_close,
	.hangup		= rs485_hangup,
	.flush_buffer	= rs485_flush_buffer,
	.read		= rs485_read,
	.write		= rs485_write,
	.ioctl		= rs485_ioctl,
#ifdef CONFIG_COMPAT
	.compat_ioctl	= rs485_compat_ioctl,
#endif
	.poll		= rs485_poll,
	.receive_buf	= rs485_receive_buf,
};

/*
 * tty_register_ldisc() silently replaces whatever discipline holds the
 * number. The kernel offers no way to ask whether a number is taken, so only
 * the one the kernel leaves free for out-of-tree disciplines is accepted;
 * every other number is assigned to an in-tree discipline (and a kernel that
 * adds one raises NR_LDISCS, so numbers beyond our headers are refused too).
 */
static int __init rs485_init(void)
{
	if (ldisc != N_DEVELOPMENT) {
		pr_err("n_rs485: line discipline %d is assigned to another discipline; only %d (N_DEVELOPMENT) is free for this one\n",
		       ldisc, N_DEVELOPMENT);
		return -EBUSY;
	}
	rs485_crc_init();
	rs485_ldisc.num = ldisc;
	return tty_register_ldisc(&rs485_ldisc);
}

static void __exit rs485_exit(void)
{
	tty_unregister_ldisc(&rs485_ldisc);
}

module_init(rs485_init);
module_exit(rs485_exit);

MODULE_DESCRIPTION("9-bit RS-485 multidrop bus master line discipline");
MODULE_LICENSE("GPL");
MODULE_ALIAS_LDISC(N_DEVELOPMENT);
