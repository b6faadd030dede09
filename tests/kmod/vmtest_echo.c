// SPDX-License-Identifier: GPL-2.0
/*
 * vmtest_echo - a misc device that returns on read() what was written to it.
 *
 * Test-only module of the VM lanes: the smallest piece of project kernel code
 * that user space can exercise, so that the harness proves end to end that a
 * module built here loads, works and unloads on every target kernel.
 */

#include <linux/fs.h>
#include <linux/kfifo.h>
#include <linux/miscdevice.h>
#include <linux/module.h>
#include <linux/mutex.h>
#include <linux/poll.h>
#include <linux/wait.h>

#define VMTEST_ECHO_FIFO_SIZE	4096

static DEFINE_KFIFO(echo_fifo, unsigned char, VMTEST_ECHO_FIFO_SIZE);
/* kfifo_{to,from}_user may fault and sleep: a mutex, not a spinlock. */
static DEFINE_MUTEX(echo_lock);
static DECLARE_WAIT_QUEUE_HEAD(echo_wait);

static ssize_t echo_read(struct file *file, char __user *buf, size_t count,
			 loff_t *ppos)
{
	unsigned int copied;
	int ret;

	if (!count)
		return 0;

	for (;;) {
		if (mutex_lock_interruptible(&echo_lock))
			return -ERESTARTSYS;
		if (!kfifo_is_empty(&echo_fifo))
			break;
		mutex_unlock(&echo_lock);
		if (file->f_flags & O_NONBLOCK)
			return -EAGAIN;
		if (wait_event_interruptible(echo_wait, !kfifo_is_empty(&echo_fifo)))
			return -ERESTARTSYS;
	}
	ret = kfifo_to_user(&echo_fifo, buf, count, &copied);
	mutex_unlock(&echo_lock);
	if (ret)
		return ret;
	wake_up_interruptible(&echo_wait);
	return copied;
}

static ssize_t echo_write(struct file *file, const char __user *buf,
			  size_t count, loff_t *ppos)
{
	unsigned int copied;
	int ret;

	if (!count)
		return 0;
	if (mutex_lock_interruptible(&echo_lock))
		return -ERESTARTSYS;
	if (kfifo_is_full(&echo_fifo)) {
		mutex_unlock(&echo_lock);
		return -EAGAIN;
	}
	ret = kfifo_from_user(&echo_fifo, buf, count, &copied);
	mutex_unlock(&echo_lock);
	if (ret)
		return ret;
	wake_up_interruptible(&echo_wait);
	return copied;
}

static __poll_t echo_poll(struct file *file, poll_table *wait)
{
	__poll_t mask = 0;

	poll_wait(file, &echo_wait, wait);
	if (!kfifo_is_empty(&echo_fifo))
		mask |= EPOLLIN | EPOLLRDNORM;
	if (!kfifo_is_full(&echo_fifo))
		mask |= EPOLLOUT | EPOLLWRNORM;
	return mask;
}

static const struct file_operations echo_fops = {
	.owner = THIS_MODULE,
	.read = echo_read,
	.write = echo_write,
	.poll = echo_poll,
	.llseek = noop_llseek,
};

static struct miscdevice echo_misc = {
	.minor = MISC_DYNAMIC_MINOR,
	.name = "vmtest-echo",
	.fops = &echo_fops,
};

module_misc_device(echo_misc);

MODULE_DESCRIPTION("Echo misc device for the project's VM test lanes");
MODULE_LICENSE("GPL");
MODULE_INFO(test, "Y");
