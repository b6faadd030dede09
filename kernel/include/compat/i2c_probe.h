/* SPDX-License-Identifier: GPL-2.0 */
/*
 * i2c_driver probe with the client only: the member is probe_new until 6.2
 * (probe then also took the i2c_device_id) and probe since 6.3 (probe_new
 * went in 6.6). A driver sets .I2C_DRIVER_PROBE = fn.
 */
#ifndef _COMPAT_I2C_PROBE_H
#define _COMPAT_I2C_PROBE_H

#include <linux/version.h>

#if LINUX_VERSION_CODE >= KERNEL_VERSION(6, 3, 0)
#define I2C_DRIVER_PROBE	probe
#else
#define I2C_DRIVER_PROBE	probe_new
#endif

#endif
