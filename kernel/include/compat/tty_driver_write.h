/* SPDX-License-Identifier: GPL-2.0 */
/*
 * tty_operations.write takes a size_t count and returns ssize_t since 6.6
 * (an int each until then; the buffer is const u8 either way). A driver
 * declares its callback as
 * TTY_DRIVER_WRITE_RET fn(struct tty_struct *tty, const u8 *buf,
 *			   TTY_DRIVER_WRITE_COUNT count).
 */
#ifndef _COMPAT_TTY_DRIVER_WRITE_H
#define _COMPAT_TTY_DRIVER_WRITE_H

#include <linux/types.h>
#include <linux/version.h>

#if LINUX_VERSION_CODE >= KERNEL_VERSION(6, 6, 0)
#define TTY_DRIVER_WRITE_RET	ssize_t
#define TTY_DRIVER_WRITE_COUNT	size_t
#else
#define TTY_DRIVER_WRITE_RET	int
#define TTY_DRIVER_WRITE_COUNT	int
#endif

#endif
