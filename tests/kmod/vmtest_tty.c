// SPDX-License-Identifier: GPL-2.0
/*
 * vmtest_tty - a tty whose write room the test sets.
 *
 * Test-only module of the VM lanes. How a line discipline waits for room in
 * a full driver buffer cannot be tested on a UART (serial_core keeps a page
 * of buffer and the discipline drains every frame) nor on a pty (it clears
 * PARENB, which n_rs485 needs). /dev/ttyVT0 takes only as many characters as
 * debugfs vmtest_tty/room allows; writing a number there gives that much
 * room (until then it has no limit) and calls tty_wakeup(), as a UART's
 * transmit interrupt does. It starts with the sticky parity n_rs485 needs
 * (PARENB | CMSPAR) and, having no set_termios, keeps its hardware bits
 * whatever is asked (tty_termios_copy_hw()). What it was sent waits in
 * vmtest_tty/sent until read; vmtest_tty/starved counts the writes that
 * found no room at all (the caller now waits for room).
 */

#include <linux/debugfs.h>
#include <linux/fs.h>
#include <linux/kfifo.h>
#include <linux/module.h>
#include <linux/mutex.h>
#include <linux/spinlock.h>
#include <linux/tty.h>
#include <linux/tty_driver.h>
#include <linux/uaccess.h>

#include <compat/tty_driver_write.h>

#define VT_SENT_SIZE	4096

static struct tty_driver *vt_driver;
static struct tty_port vt_port;
static struct dentry *vt_dir;

/* vt_room, vt_starved and the kfifo's input side: vt_write() against the room file. */
static DEFINE_SPINLOCK(vt_lock);
static unsigned int vt_room = UINT_MAX;	/* no limit until a test sets one */
static u32 vt_starved;
static DEFINE_KFIFO(vt_sent, u8, VT_SENT_SIZE);
/* The kfifo's output side: kfifo_to_user() may fault, so not the spinlock. */
static DEFINE_MUTEX(vt_read_lock);

static int vt_open(struct tty_struct *tty, struct file *filp)
{
	return tty_port_open(&vt_port, tty, filp);
}

static void vt_close(struct tty_struct *tty, struct file *filp)
{
	tty_port_close(&vt_port, tty, filp);
}

static unsigned int vt_room_locked(void)
{
	return min_t(unsigned int, vt_room, kfifo_avail(&vt_sent));
}

static TTY_DRIVER_WRITE_RET vt_write(struct tty_struct *tty, const u8 *buf,
				     TTY_DRIVER_WRITE_COUNT count)
{
	unsigned long flags;
	unsigned int n;

	spin_lock_irqsave(&vt_lock, flags);
	n = kfifo_in(&vt_sent, buf, min_t(size_t, count, vt_room_locked()));
	vt_room -= n;
	if (count && !n)
		vt_starved++;
	spin_unlock_irqrestore(&vt_lock, flags);
	return n;
}

static unsigned int vt_write_room(struct tty_struct *tty)
{
	unsigned long flags;
	unsigned int room;

	spin_lock_irqsave(&vt_lock, flags);
	room = vt_room_locked();
	spin_unlock_irqrestore(&vt_lock, flags);
	return room;
}

static const struct tty_operations vt_ops = {
	.open = vt_open,
	.close = vt_close,
	.write = vt_write,
	.write_room = vt_write_room,
};

static const struct tty_port_operations vt_port_ops = {};

static ssize_t vt_room_write(struct file *file, const char __user *ubuf, size_t count,
			     loff_t *ppos)
{
	unsigned long flags;
	unsigned int room;
	int ret;

	ret = kstrtouint_from_user(ubuf, count, 0, &room);
	if (ret)
		return ret;
	spin_lock_irqsave(&vt_lock, flags);
	vt_room = room;
	spin_unlock_irqrestore(&vt_lock, flags);
	if (room)
		tty_port_tty_wakeup(&vt_port);
	return count;
}

static const struct file_operations vt_room_fops = {
	.owner = THIS_MODULE,
	.open = simple_open,
	.write = vt_room_write,
};

static ssize_t vt_sent_read(struct file *file, char __user *ubuf, size_t count, loff_t *ppos)
{
	unsigned int copied;
	int ret;

	if (mutex_lock_interruptible(&vt_read_lock))
		return -ERESTARTSYS;
	ret = kfifo_to_user(&vt_sent, ubuf, count, &copied);
	mutex_unlock(&vt_read_lock);
	return ret ? ret : copied;
}

static const struct file_operations vt_sent_fops = {
	.owner = THIS_MODULE,
	.open = simple_open,
	.read = vt_sent_read,
};

static int __init vt_init(void)
{
	struct device *dev;
	int ret;

	vt_driver = tty_alloc_driver(1, TTY_DRIVER_REAL_RAW | TTY_DRIVER_DYNAMIC_DEV);
	if (IS_ERR(vt_driver))
		return PTR_ERR(vt_driver);
	vt_driver->driver_name = "vmtest_tty";
	vt_driver->name = "ttyVT";
	vt_driver->type = TTY_DRIVER_TYPE_SERIAL;
	vt_driver->subtype = SERIAL_TYPE_NORMAL;
	vt_driver->init_termios = tty_std_termios;
	vt_driver->init_termios.c_cflag |= CLOCAL | PARENB | CMSPAR;
	tty_set_operations(vt_driver, &vt_ops);
	tty_port_init(&vt_port);
	vt_port.ops = &vt_port_ops;
	tty_port_link_device(&vt_port, vt_driver, 0);

	ret = tty_register_driver(vt_driver);
	if (ret)
		goto err_put;
	dev = tty_register_device(vt_driver, 0, NULL);
	if (IS_ERR(dev)) {
		ret = PTR_ERR(dev);
		goto err_unregister;
	}
	vt_dir = debugfs_create_dir("vmtest_tty", NULL);
	debugfs_create_file("room", 0200, vt_dir, NULL, &vt_room_fops);
	debugfs_create_file("sent", 0400, vt_dir, NULL, &vt_sent_fops);
	debugfs_create_u32("starved", 0400, vt_dir, &vt_starved);
	return 0;

err_unregister:
	tty_unregister_driver(vt_driver);
err_put:
	tty_driver_kref_put(vt_driver);
	tty_port_destroy(&vt_port);
	return ret;
}

static void __exit vt_exit(void)
{
	debugfs_remove_recursive(vt_dir);
	tty_unregister_device(vt_driver, 0);
	tty_unregister_driver(vt_driver);
	tty_driver_kref_put(vt_driver);
	tty_port_destroy(&vt_port);
}

module_init(vt_init);
module_exit(vt_exit);

MODULE_DESCRIPTION("Test tty whose write room is set through debugfs");
MODULE_LICENSE("GPL");
