// SPDX-License-Identifier: GPL-2.0
/*
 * TS-7800 FPGA: board identification and child devices.
 *
 * Shared by the hardware FPGA core and the test-only simulator so that both
 * present exactly the same children to the same child drivers: one
 * "ts7800-uart" platform device per TS-UART, with its register block as an
 * IORESOURCE_REG resource (an offset into the parent's regmap, never MMIO)
 * and its interrupt mapped through the parent's irq domain.
 */
#include <linux/device.h>
#include <linux/export.h>
#include <linux/ioport.h>
#include <linux/irqdomain.h>
#include <linux/module.h>
#include <linux/platform_device.h>
#include <linux/regmap.h>
#include <linux/ts-can1.h>
#include <linux/ts7800-fpga.h>

/* Divisors as written by the vendor's TS-7800 loader: round(12.5 MHz / baud). */
const struct ts7800_uart_rate ts7800_uart_rates[TS7800_UART_NR_CODES] = {
	{ 115200, 108 },
	{ 57600, 217 },
	{ 38400, 326 },
	{ 19200, 651 },
	{ 9600, 1302 },
	{ 4800, 2604 },
	{ 2400, 5208 },
};
EXPORT_SYMBOL_GPL(ts7800_uart_rates);

/*
 * The blocks of the window that our drivers own. Everything else (NAND,
 * RTC, random number generator, registers of unknown meaning) belongs to
 * other drivers or to nobody: not even a regmap debugfs dump may read it.
 */
static bool ts7800_fpga_readable_reg(struct device *dev, unsigned int reg)
{
	switch (reg) {
	case TS7800_FPGA_ID_LO ... TS7800_FPGA_ID_HI:
	case TS7800_DIO_IN ... TS7800_DIO_OUT + 2:
	case TS7800_FPGA_PC104_FUNC_FIRST ... TS7800_FPGA_PC104_FUNC_LAST:
	case TS7800_UART_BASE(0) ... TS7800_UART_DIVISOR(TS7800_UART_NR_CODES - 1):
	case TS7800_FPGA_IRQ_MASK_LO ... TS7800_FPGA_IRQ_MASK_HI:
		return true;
	default:
		return false;
	}
}

/*
 * Reads with side effects: DATA pops the receive FIFO, STAT may clear OERR
 * and the transmit event (docs/tsuart.md). Only the TS-UART driver reads
 * them; a debugfs dump must not.
 */
static bool ts7800_fpga_precious_reg(struct device *dev, unsigned int reg)
{
	return reg >= TS7800_UART_BASE(0) &&
	       reg < TS7800_UART_BASE(TS7800_UART_MAX_PORTS);
}

/*
 * The FPGA window as the child drivers see it. Every access is 16 bits wide
 * (docs/tsuart.md, "Access width"): 32-bit registers are two halves, low
 * first. Used by the hardware core (over MMIO) and by the simulator (with
 * its own reg_read/reg_write), so both enforce the same rules.
 */
const struct regmap_config ts7800_fpga_regmap_config = {
	.name		= TS7800_FPGA_REGMAP_NAME,
	.reg_bits	= 32,
	.val_bits	= 16,
	.reg_stride	= 2,
	.max_register	= TS7800_FPGA_WINDOW_SIZE - 2,
	.readable_reg	= ts7800_fpga_readable_reg,
	.writeable_reg	= ts7800_fpga_readable_reg,
	.precious_reg	= ts7800_fpga_precious_reg,
	.cache_type	= REGCACHE_NONE,
	/* Used by the irqchip (mask/unmask, hard irq context even on RT). */
	.use_raw_spinlock = true,
};
EXPORT_SYMBOL_GPL(ts7800_fpga_regmap_config);

static int ts7800_fpga_read32(struct regmap *map, unsigned int lo, u32 *val)
{
	unsigned int l, h;
	int ret;

	ret = regmap_read(map, lo, &l);
	if (!ret)
		ret = regmap_read(map, lo + 2, &h);
	if (!ret)
		*val = (h << 16) | (l & 0xffff);
	return ret;
}

/**
 * ts7800_fpga_identify - check the ID magic at offset 0
 * @map: the FPGA window
 * @revision: FPGA revision (bits 7..0 of the ID word)
 *
 * Return: 0 on a TS-7800 FPGA, -ENODEV on another ID, or a regmap error.
 */
int ts7800_fpga_identify(struct regmap *map, u8 *revision)
{
	u32 id;
	int ret;

	ret = ts7800_fpga_read32(map, TS7800_FPGA_ID_LO, &id);
	if (ret)
		return ret;
	if ((id >> 8) != TS7800_FPGA_ID_MAGIC)
		return -ENODEV;
	*revision = id & 0xff;
	return 0;
}
EXPORT_SYMBOL_GPL(ts7800_fpga_identify);

/**
 * ts7800_fpga_write_divisors - load the board-wide TS-UART divisor table
 * @map: the FPGA window
 *
 * The table is shared by all ports, so it belongs to the parent, not to a
 * UART: children only select a slot through the baud code in STAT.
 */
int ts7800_fpga_write_divisors(struct regmap *map)
{
	unsigned int code;
	int ret;

	for (code = 0; code < TS7800_UART_NR_CODES; code++) {
		ret = regmap_write(map, TS7800_UART_DIVISOR(code),
				   ts7800_uart_rates[code].divisor);
		if (ret)
			return ret;
	}
	return 0;
}
EXPORT_SYMBOL_GPL(ts7800_fpga_write_divisors);

/*
 * Ports 8 and 9 use PC/104 pins C14..C19. They exist only while those pins
 * are in GPIO function; the vendor loader then clears the row's upper bits.
 */
static int ts7800_fpga_uart_count(struct device *dev, struct regmap *map)
{
	u32 rowc;
	int ret;

	ret = ts7800_fpga_read32(map, TS7800_FPGA_PC104_ROWC_LO, &rowc);
	if (ret)
		return ret;
	if (rowc & TS7800_FPGA_ROWC_UART89_PINS) {
		dev_info(dev, "PC/104 row C pins in bus use: TS-UART 8/9 not available\n");
		return TS7800_UART_ALWAYS_PORTS;
	}
	ret = regmap_write(map, TS7800_FPGA_PC104_ROWC_HI, 0);
	if (!ret)
		ret = regmap_write(map, TS7800_FPGA_PC104_ROWC_LO,
				   rowc & TS7800_FPGA_ROWC_KEEP);
	return ret ? ret : TS7800_UART_MAX_PORTS;
}

static void ts7800_fpga_dispose_irq(void *data)
{
	irq_dispose_mapping((uintptr_t)data);
}

static void ts7800_fpga_remove_child(void *data)
{
	platform_device_unregister(data);
}

/*
 * Map FPGA interrupt source @hwirq in @domain for a child and describe it in
 * @res. The mapping belongs to @parent: its devres disposes of it after the
 * children registered later are gone.
 */
static int ts7800_fpga_child_irq(struct device *parent, struct irq_domain *domain,
				 irq_hw_number_t hwirq, const char *name,
				 struct resource *res)
{
	unsigned int virq;
	int ret;

	virq = irq_create_mapping(domain, hwirq);
	if (!virq)
		return -EINVAL;
	ret = devm_add_action_or_reset(parent, ts7800_fpga_dispose_irq,
				       (void *)(uintptr_t)virq);
	if (ret)
		return ret;
	res->start = virq;
	res->end = virq;
	res->flags = IORESOURCE_IRQ;
	res->name = name;
	return 0;
}

/* Register a child of @info->parent, removed by the parent's devres. */
static int ts7800_fpga_add_child(const struct platform_device_info *info)
{
	struct platform_device *pdev;

	pdev = platform_device_register_full(info);
	if (IS_ERR(pdev))
		return PTR_ERR(pdev);
	return devm_add_action_or_reset(info->parent, ts7800_fpga_remove_child, pdev);
}

static int ts7800_fpga_add_uart(struct device *parent,
				struct irq_domain *domain, unsigned int n)
{
	struct platform_device_info info = { };
	struct resource res[2];
	int ret;

	memset(res, 0, sizeof(res));
	ret = ts7800_fpga_child_irq(parent, domain, TS7800_FPGA_HWIRQ_UART(n), NULL, &res[1]);
	if (ret)
		return ret;
	res[0].start = TS7800_UART_BASE(n);
	res[0].end = TS7800_UART_BASE(n) + TS7800_UART_REGS_SIZE - 1;
	res[0].flags = IORESOURCE_REG;
	res[0].name = "ts-uart";

	info.parent = parent;
	info.name = TS7800_UART_DEV_NAME;
	info.id = n;
	info.res = res;
	info.num_res = ARRAY_SIZE(res);
	return ts7800_fpga_add_child(&info);
}

/**
 * ts7800_fpga_add_uarts - register the TS-UART child devices
 * @parent: FPGA device; owns the regmap (dev_get_regmap) the children use
 * @map: the FPGA window
 * @domain: irq domain whose hwirq k is FPGA interrupt source k
 *
 * The children are removed automatically (devres of @parent) before anything
 * the parent set up earlier is torn down.
 *
 * Return: number of ports registered, or a negative error.
 */
int ts7800_fpga_add_uarts(struct device *parent, struct regmap *map,
			  struct irq_domain *domain)
{
	int nports, ret;
	unsigned int n;

	nports = ts7800_fpga_uart_count(parent, map);
	if (nports < 0)
		return nports;

	for (n = 0; n < nports; n++) {
		ret = ts7800_fpga_add_uart(parent, domain, n);
		if (ret)
			return dev_err_probe(parent, ret, "TS-UART %u\n", n);
	}
	return nports;
}
EXPORT_SYMBOL_GPL(ts7800_fpga_add_uarts);

/**
 * ts7800_fpga_add_dio - register the DIO header child device
 * @parent: FPGA device; the child reads and writes the DIO registers through
 *	    the parent's regmap
 *
 * The FPGA has no known DIO interrupt source, so the child gets no
 * interrupt: its driver polls for edges (docs/dio-i2c.md). The child is
 * removed automatically (devres of @parent).
 *
 * Return: 0 or a negative error.
 */
int ts7800_fpga_add_dio(struct device *parent)
{
	struct platform_device_info info = { };
	struct resource res;
	int ret;

	memset(&res, 0, sizeof(res));
	res.start = TS7800_DIO_IN;
	res.end = TS7800_DIO_OUT + 1;
	res.flags = IORESOURCE_REG;
	res.name = "dio";

	info.parent = parent;
	info.name = TS7800_DIO_DEV_NAME;
	info.id = PLATFORM_DEVID_NONE;
	info.res = &res;
	info.num_res = 1;
	ret = ts7800_fpga_add_child(&info);
	return ret ? dev_err_probe(parent, ret, "DIO header\n") : 0;
}
EXPORT_SYMBOL_GPL(ts7800_fpga_add_dio);

/*
 * PC/104 IRQ5/6/7 are FPGA interrupt sources 5/6/7 (ts7800-notes 1.6); the
 * TS-CAN1 driver finds them as the named resources "irq5".."irq7".
 */
#define TS7800_FPGA_PC104_FIRST_IRQ	5
#define TS7800_FPGA_PC104_NR_IRQS	3

/**
 * ts7800_fpga_add_pc104 - register the PC/104 bus device (driver: ts-can1)
 * @parent: FPGA device (or the simulator of the bus)
 * @domain: @parent's irq domain, hwirq k = FPGA interrupt source k
 * @io: the PC/104 8-bit I/O window (physical), or NULL when @parent has a
 *	regmap named TS_CAN1_IO_REGMAP instead
 *
 * The device is a child of @parent and everything it uses belongs to
 * @parent: the interrupt mappings are made here and disposed of by @parent's
 * devres after the child is gone, so unbinding @parent removes the bus
 * device (and unbinds its driver) before the irq domain goes away.
 *
 * Return: 0 or a negative error.
 */
int ts7800_fpga_add_pc104(struct device *parent, struct irq_domain *domain,
			  const struct resource *io)
{
	static const char * const names[TS7800_FPGA_PC104_NR_IRQS] = {
		"irq5", "irq6", "irq7",
	};
	struct resource res[TS7800_FPGA_PC104_NR_IRQS + 1];
	struct platform_device_info info = { };
	unsigned int n;
	int ret;

	memset(res, 0, sizeof(res));
	for (n = 0; n < TS7800_FPGA_PC104_NR_IRQS; n++) {
		ret = ts7800_fpga_child_irq(parent, domain, TS7800_FPGA_PC104_FIRST_IRQ + n,
					    names[n], &res[n]);
		if (ret)
			return ret;
	}
	if (io)
		res[n++] = *io;

	info.parent = parent;
	info.name = TS_CAN1_DEV_NAME;
	info.id = PLATFORM_DEVID_NONE;
	info.res = res;
	info.num_res = n;
	ret = ts7800_fpga_add_child(&info);
	return ret ? dev_err_probe(parent, ret, "PC/104 bus device\n") : 0;
}
EXPORT_SYMBOL_GPL(ts7800_fpga_add_pc104);
