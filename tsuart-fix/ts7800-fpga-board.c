// SPDX-License-Identifier: GPL-2.0
/*
 * TS-7800 FPGA: the platform device on a TS-78xx board-file kernel.
 *
 * mach-orion5x describes the board in C, not in a device tree, and creates no
 * device for the FPGA core. Only on that machine this creates one, with the
 * FPGA window, the Orion host-to-CPU doorbell registers, the doorbell's
 * main interrupt and the PC/104 8-bit I/O window (handed to the PC/104 bus
 * child); the probe then checks the FPGA ID before using anything.
 */
#include <linux/ioport.h>
#include <linux/platform_device.h>
#include <linux/ts-can1.h>
#include <linux/ts7800-fpga.h>
#include <asm/mach-types.h>

#include "ts7800-fpga-core.h"

#define TS7800_FPGA_PHYS		0xe8000000
/* PC/104 8-bit I/O cycles: this window + ISA port (ts7800-notes 3.3). */
#define TS7800_PC104_IO_PHYS		0xee000000
#define ORION5X_DOORBELL_H2C_PHYS	0xf1020400
#define ORION5X_DOORBELL_REGS_SIZE	8
/* mach-orion5x numbers its main interrupts 1 + cause bit; doorbell = bit 1. */
#define ORION5X_IRQ_DOORBELL_H2C	(1 + 1)

static struct platform_device *ts7800_fpga_board_dev;

int ts7800_fpga_board_register(void)
{
	static const struct resource res[] = {
		DEFINE_RES_MEM(TS7800_FPGA_PHYS, TS7800_FPGA_WINDOW_SIZE),
		DEFINE_RES_MEM(ORION5X_DOORBELL_H2C_PHYS, ORION5X_DOORBELL_REGS_SIZE),
		DEFINE_RES_IRQ(ORION5X_IRQ_DOORBELL_H2C),
		DEFINE_RES_MEM_NAMED(TS7800_PC104_IO_PHYS, TS_CAN1_IO_SIZE, "pc104-io"),
	};
	struct platform_device *pdev;

	if (!machine_is_ts78xx())
		return 0;

	pdev = platform_device_register_simple(TS7800_FPGA_DRV_NAME, PLATFORM_DEVID_NONE,
					       res, ARRAY_SIZE(res));
	if (IS_ERR(pdev))
		return PTR_ERR(pdev);
	ts7800_fpga_board_dev = pdev;
	return 0;
}

void ts7800_fpga_board_unregister(void)
{
	platform_device_unregister(ts7800_fpga_board_dev);
	ts7800_fpga_board_dev = NULL;
}
