/* SPDX-License-Identifier: GPL-2.0 */
/*
 * tty_ldisc_ops.receive_buf takes u8 flags and a size_t count since 6.6
 * (char flags and an int count until then; the flags are TTY_NORMAL, ...,
 * all below 128, so the same bytes either way).
 * DEFINE_LDISC_RECEIVE_BUF(name, fn) defines the callback name for this
 * kernel, calling
 * void fn(struct tty_struct *tty, const u8 *cp, const u8 *fp, size_t count).
 */
#ifndef _COMPAT_TTY_LDISC_RECEIVE_BUF_H
#define _COMPAT_TTY_LDISC_RECEIVE_BUF_H

#include <linux/tty.h>
#include <linux/types.h>
#include <linux/version.h>

#if LINUX_VERSION_CODE >= KERNEL_VERSION(6, 6, 0)
#define DEFINE_LDISC_RECEIVE_BUF(name, fn)				\
static void name(struct tty_struct *tty, const u8 *cp, const u8 *fp,	\
		 size_t count)						\
{									\
	fn(tty, cp, fp, count);						\
}
#else
#define DEFINE_LDISC_RECEIVE_BUF(name, fn)				\
static void name(struct tty_struct *tty, const u8 *cp, const char *fp,	\
		 int count)						\
{									\
	fn(tty, cp, (const u8 *)fp, count);				\
}
#endif

#endif
