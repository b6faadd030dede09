/* SPDX-License-Identifier: GPL-2.0 */
/*
 * platform_driver remove returning void: remove_new from 6.3 (and in
 * Debian's 6.1, which has it from the stable series) until 6.12, remove since
 * 6.11 (remove_new went in 6.13). A driver sets .PLATFORM_DRIVER_REMOVE = fn.
 */
#ifndef _COMPAT_PLATFORM_REMOVE_H
#define _COMPAT_PLATFORM_REMOVE_H

#include <linux/version.h>

#if LINUX_VERSION_CODE >= KERNEL_VERSION(6, 11, 0)
#define PLATFORM_DRIVER_REMOVE	remove
#else
#define PLATFORM_DRIVER_REMOVE	remove_new
#endif

#endif
