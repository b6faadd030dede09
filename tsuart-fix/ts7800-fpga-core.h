/* SPDX-License-Identifier: GPL-2.0 */
/* TS-7800 FPGA core: interfaces between the files of ts7800-fpga.ko. */
#ifndef TS7800_FPGA_CORE_H
#define TS7800_FPGA_CORE_H

#include <linux/device.h>
#include <linux/irqdomain.h>
#include <linux/regmap.h>
#include <linux/types.h>

#define TS7800_FPGA_DRV_NAME	"ts7800-fpga"

struct ts7800_fpga_irq;

struct irq_domain *ts7800_fpga_irq_setup(struct device *dev,
					 struct regmap *fpga,
					 void __iomem *doorbell,
					 int parent_irq);

#ifdef CONFIG_MACH_TS78XX
int ts7800_fpga_board_register(void);
void ts7800_fpga_board_unregister(void);
#else
/* No TS-78xx board support in this kernel: the driver only registers. */
static inline int ts7800_fpga_board_register(void) { return 0; }
static inline void ts7800_fpga_board_unregister(void) { }
#endif

#endif /* TS7800_FPGA_CORE_H */
