// SPDX-License-Identifier: GPL-2.0
/*
 * TS-CAN1 on a TS-78xx board-file kernel (Debian's armel "marvell"): the
 * PC/104 bus device and its interrupts.
 *
 * mach-orion5x describes nothing of the PC/104 bus. On that machine this
 * registers the bus device as a child of the FPGA core's device (whose
 * "fpga" regmap switches the PC/104 pins to bus function), with the FPGA's
 * 8-bit PC/104 I/O window as its memory resource. The PC/104 lines IRQ5/6/7
 * are FPGA interrupt sources 5/6/7 (ts7800-notes 1.6); they are mapped in the
 * FPGA core's irq domain when a card needs one.
 */
#include <linux/irq.h>
#include <linux/irqdomain.h>
#include <linux/module.h>
#include <linux/platform_device.h>
#include <linux/ts-can1.h>
#include <linux/ts7800-fpga.h>
#include <asm/mach-types.h>

#include "ts-can1.h"

#define TS7800_FPGA_DEV_NAME	"ts7800-fpga"

static ulong io_base = 0xee000000;
module_param(io_base, ulong, 0444);
MODULE_PARM_DESC(io_base,
		 "Physical address of the TS-7800's PC/104 8-bit I/O window (default 0xee000000)");

/* The FPGA core is needed first: it owns the pins and the interrupts. */
MODULE_SOFTDEP("pre: ts7800-fpga");

static struct platform_device *ts_can1_board_dev;

int ts_can1_board_register(void)
{
	struct platform_device_info info = { };
	struct platform_device *pdev;
	struct resource res;
	struct device *fpga;

	if (!machine_is_ts78xx())
		return 0;
	fpga = bus_find_device_by_name(&platform_bus_type, NULL, TS7800_FPGA_DEV_NAME);
	if (!fpga) {
		pr_info("ts-can1: no %s device (module not loaded?): no PC/104 bus\n",
			TS7800_FPGA_DEV_NAME);
		return 0;
	}

	res = (struct resource)DEFINE_RES_MEM_NAMED(io_base, TS_CAN1_IO_SIZE, "pc104-io");
	info.parent = fpga;
	info.name = TS_CAN1_DEV_NAME;
	info.id = PLATFORM_DEVID_NONE;
	info.res = &res;
	info.num_res = 1;
	pdev = platform_device_register_full(&info);
	put_device(fpga);	/* the child holds its own reference */
	if (IS_ERR(pdev))
		return PTR_ERR(pdev);
	ts_can1_board_dev = pdev;
	return 0;
}

void ts_can1_board_unregister(void)
{
	platform_device_unregister(ts_can1_board_dev);
	ts_can1_board_dev = NULL;
}

static int ts_can1_match_uart(struct device *dev, void *data)
{
	return !strcmp(to_platform_device(dev)->name, TS7800_UART_DEV_NAME);
}

/*
 * The FPGA core keeps its irq domain to itself and hands each child its
 * interrupt; every TS-UART child's interrupt lives in that domain, so one of
 * them leads to it.
 */
static struct irq_domain *ts_can1_fpga_domain(struct device *fpga)
{
	struct irq_domain *domain = NULL;
	struct irq_data *data;
	struct device *uart;
	int irq;

	uart = device_find_child(fpga, NULL, ts_can1_match_uart);
	if (!uart)
		return NULL;
	irq = platform_get_irq_optional(to_platform_device(uart), 0);
	if (irq > 0) {
		data = irq_get_irq_data(irq);
		if (data)
			domain = data->domain;
	}
	put_device(uart);
	return domain;
}

static void ts_can1_dispose_irq(void *data)
{
	irq_dispose_mapping((uintptr_t)data);
}

/**
 * ts_can1_board_irq - Linux interrupt of a PC/104 interrupt line
 * @dev: the bus device (child of the FPGA device)
 * @line: PC/104 line 5, 6 or 7
 *
 * Return: the interrupt number, mapped until @dev unbinds, or a negative error.
 */
int ts_can1_board_irq(struct device *dev, unsigned int line)
{
	struct irq_domain *domain;
	unsigned int virq;
	int ret;

	if (!machine_is_ts78xx() || !dev->parent)
		return -ENXIO;
	domain = ts_can1_fpga_domain(dev->parent);
	if (!domain)
		return dev_err_probe(dev, -EPROBE_DEFER,
				     "FPGA interrupt domain not there yet\n");
	/* FPGA source k is PC/104 IRQk for k = 5..7. */
	virq = irq_create_mapping(domain, line);
	if (!virq)
		return -ENXIO;
	ret = devm_add_action_or_reset(dev, ts_can1_dispose_irq, (void *)(uintptr_t)virq);
	return ret ? ret : virq;
}
