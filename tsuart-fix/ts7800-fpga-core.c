// SPDX-License-Identifier: GPL-2.0
/*
 * TS-7800 FPGA core: maps the FPGA window, exposes it to the child drivers as
 * a 16-bit regmap, demultiplexes the FPGA interrupt sources and registers the
 * TS-UART, DIO header and PC/104 bus children. Children never touch MMIO: they take the regmap with
 * dev_get_regmap(parent) and their interrupt from their platform resources,
 * which lets the same child drivers run on the simulator (tests/sim/).
 *
 * The board has no device tree; on a kernel with TS-78xx board support this
 * module creates its own platform device (ts7800-fpga-board.c). Elsewhere it
 * only registers the driver.
 */
#include <linux/io.h>
#include <linux/module.h>
#include <linux/platform_device.h>
#include <linux/regmap.h>
#include <linux/ts7800-fpga.h>

#include "ts7800-fpga-core.h"

static int ts7800_fpga_probe(struct platform_device *pdev)
{
	struct device *dev = &pdev->dev;
	void __iomem *fpga, *doorbell;
	struct irq_domain *domain;
	struct resource *res;
	struct regmap *map;
	int irq, nports, ret;
	u8 rev;

	/*
	 * Mapped without claiming: the board file already registers devices
	 * (NAND, RTC, RNG) inside this window and the Orion register block.
	 */
	res = platform_get_resource(pdev, IORESOURCE_MEM, 0);
	if (!res || resource_size(res) < TS7800_FPGA_WINDOW_SIZE)
		return dev_err_probe(dev, -EINVAL, "no FPGA window\n");
	fpga = devm_ioremap(dev, res->start, TS7800_FPGA_WINDOW_SIZE);
	res = platform_get_resource(pdev, IORESOURCE_MEM, 1);
	if (!res)
		return dev_err_probe(dev, -EINVAL, "no doorbell registers\n");
	doorbell = devm_ioremap(dev, res->start, resource_size(res));
	if (!fpga || !doorbell)
		return -ENOMEM;
	irq = platform_get_irq(pdev, 0);
	if (irq < 0)
		return irq;

	map = devm_regmap_init_mmio(dev, fpga, &ts7800_fpga_regmap_config);
	if (IS_ERR(map))
		return PTR_ERR(map);

	ret = ts7800_fpga_identify(map, &rev);
	if (ret)
		return dev_err_probe(dev, ret, "no TS-7800 FPGA ID\n");
	ret = ts7800_fpga_write_divisors(map);
	if (ret)
		return ret;

	domain = ts7800_fpga_irq_setup(dev, map, doorbell, irq);
	if (IS_ERR(domain))
		return PTR_ERR(domain);

	nports = ts7800_fpga_add_uarts(dev, map, domain);
	if (nports < 0)
		return nports;
	ret = ts7800_fpga_add_dio(dev);
	if (ret)
		return ret;
	/* The PC/104 bus (TS-CAN1), if the board file gave its I/O window. */
	res = platform_get_resource(pdev, IORESOURCE_MEM, 2);
	if (res) {
		ret = ts7800_fpga_add_pc104(dev, domain, res);
		if (ret)
			return ret;
	}

	dev_info(dev, "TS-7800 FPGA revision %u, %d TS-UARTs\n", rev, nports);
	return 0;
}

static struct platform_driver ts7800_fpga_driver = {
	.probe = ts7800_fpga_probe,
	.driver = {
		.name = TS7800_FPGA_DRV_NAME,
	},
};

static int __init ts7800_fpga_init(void)
{
	int ret;

	ret = platform_driver_register(&ts7800_fpga_driver);
	if (ret)
		return ret;
	ret = ts7800_fpga_board_register();
	if (ret)
		platform_driver_unregister(&ts7800_fpga_driver);
	return ret;
}
module_init(ts7800_fpga_init);

static void __exit ts7800_fpga_exit(void)
{
	ts7800_fpga_board_unregister();
	platform_driver_unregister(&ts7800_fpga_driver);
}
module_exit(ts7800_fpga_exit);

MODULE_DESCRIPTION("TS-7800 FPGA core: regmap, interrupt demultiplexer, TS-UART and DIO children");
MODULE_LICENSE("GPL");
MODULE_ALIAS("platform:" TS7800_FPGA_DRV_NAME);
