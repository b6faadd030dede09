/* SPDX-License-Identifier: GPL-2.0 */
/* TS-CAN1 driver: interfaces between the files of ts-can1.ko. */
#ifndef TS_CAN1_H
#define TS_CAN1_H

#include <linux/device.h>

#ifdef CONFIG_MACH_TS78XX
int ts_can1_board_register(void);
void ts_can1_board_unregister(void);
int ts_can1_board_irq(struct device *dev, unsigned int line);
#else
/* No TS-78xx board support: only a bus glue such as the simulator binds. */
static inline int ts_can1_board_register(void) { return 0; }
static inline void ts_can1_board_unregister(void) { }
static inline int ts_can1_board_irq(struct device *dev, unsigned int line)
{
	return -ENXIO;
}
#endif

#endif /* TS_CAN1_H */
