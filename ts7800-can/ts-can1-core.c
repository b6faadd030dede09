// SPDX-License-Identifier: GPL-2.0
/*
 * TS-CAN1: Technologic Systems' PC/104 CAN card (an SJA1000 behind a small
 * PLD) as a SocketCAN device, on a PC/104 bus that is memory mapped, such as
 * the TS-7800's.
 *
 * The kernel's own driver for this card (tscan1) is an ISA driver using port
 * I/O, which ARM boards do not have. Here one platform device stands for one
 * PC/104 bus; its provider hands over the bus as either the 8-bit I/O window
 * (a memory resource, mapped here) or a regmap of its parent, and the PC/104
 * interrupt lines as named interrupts (include/linux/ts-can1.h). The probe
 * looks for a PLD at each of the four jumper-selected addresses, reads the
 * interrupt jumpers, opens the SJA1000 register window through the PLD and
 * registers the chip with the kernel's SJA1000 core (sja1000.ko), which does
 * all the CAN work.
 */
#include <linux/bitops.h>
#include <linux/io.h>
#include <linux/ioport.h>
#include <linux/mod_devicetable.h>
#include <linux/module.h>
#include <linux/platform_device.h>
#include <linux/regmap.h>
#include <linux/ts-can1.h>

#include "sja1000-core.h"

/* PC/104 interrupt lines a TS-CAN1 can be jumpered to. */
#define TS_CAN1_FIRST_LINE	5
#define TS_CAN1_NR_LINES	3

static unsigned int pld_ids = GENMASK(TS_CAN1_MAX_CARDS - 1, 0);
module_param(pld_ids, uint, 0444);
MODULE_PARM_DESC(pld_ids,
		 "Bit mask of the card ids (JP1/JP2, PLD at 0x150 + 8 * id) to look for (default 0xf: all four)");

static const u16 ts_can1_windows[TS_CAN1_NR_WINDOWS] = TS_CAN1_WINDOW_BASES;

/* One PC/104 bus: what every card on it shares. */
struct ts_can1_bus {
	struct platform_device *pdev;
	struct regmap *io;
	resource_size_t phys;	/* start of the I/O window, 0 without MMIO */
	int irq[TS_CAN1_NR_LINES];	/* 0 until looked up */
};

/* One card; lives in the netdev's private area behind struct sja1000_priv. */
struct ts_can1_card {
	struct ts_can1_bus *bus;
	struct net_device *ndev;
	unsigned int pld;	/* ISA port of the PLD */
	unsigned int sja;	/* ISA port of the SJA1000 window */
};

static u8 ts_can1_io_read(struct ts_can1_bus *bus, unsigned int port)
{
	unsigned int val;

	/* A failed access reads like an empty bus. */
	if (regmap_read(bus->io, port, &val))
		return TS_CAN1_SJA1000_ABSENT;
	return val;
}

static void ts_can1_io_write(struct ts_can1_bus *bus, unsigned int port, u8 val)
{
	regmap_write(bus->io, port, val);
}

static u8 ts_can1_read_reg(const struct sja1000_priv *priv, int reg)
{
	struct ts_can1_card *card = priv->priv;

	return ts_can1_io_read(card->bus, card->sja + reg);
}

static void ts_can1_write_reg(const struct sja1000_priv *priv, int reg, u8 val)
{
	struct ts_can1_card *card = priv->priv;

	ts_can1_io_write(card->bus, card->sja + reg, val);
}

/*
 * Claim a port range in the physical window, so that two drivers never
 * decode the same PC/104 addresses (other cards use 0x100..0x3ff too).
 * Without MMIO the provider owns the addresses and there is nothing to claim.
 */
static int ts_can1_claim(struct ts_can1_bus *bus, unsigned int port,
			 unsigned int size)
{
	struct device *dev = &bus->pdev->dev;

	if (!bus->phys)
		return 0;
	if (!devm_request_mem_region(dev, bus->phys + port, size, dev_name(dev)))
		return -EBUSY;
	return 0;
}

static void ts_can1_release(struct ts_can1_bus *bus, unsigned int port,
			    unsigned int size)
{
	if (bus->phys)
		devm_release_mem_region(&bus->pdev->dev, bus->phys + port, size);
}

/* Linux interrupt of a PC/104 line, a named resource from the bus provider. */
static int ts_can1_line_irq(struct ts_can1_bus *bus, unsigned int line)
{
	int *irq = &bus->irq[line - TS_CAN1_FIRST_LINE];
	char name[8];

	if (*irq > 0)
		return *irq;
	snprintf(name, sizeof(name), TS_CAN1_IRQ_NAME_FMT, line);
	*irq = platform_get_irq_byname_optional(bus->pdev, name);
	return *irq;
}

/* Undo a registered card; devres calls it on unbind, newest card first. */
static void ts_can1_remove_card(void *data)
{
	struct ts_can1_card *card = data;
	struct ts_can1_bus *bus = card->bus;
	struct net_device *ndev = card->ndev;
	unsigned int pld = card->pld;

	unregister_sja1000dev(ndev);
	/* Close the SJA1000 window: its addresses are free for other cards. */
	ts_can1_io_write(bus, pld + TS_CAN1_PLD_MODE, 0);
	free_sja1000dev(ndev);
}

/*
 * Open the SJA1000 at the first window that is free and answers, as the
 * vendor and mainline drivers do: the window is not jumpered, the PLD decodes
 * whichever one MODE selects.
 */
static int ts_can1_open_window(struct ts_can1_card *card)
{
	struct ts_can1_bus *bus = card->bus;
	unsigned int i, mode = card->pld + TS_CAN1_PLD_MODE;
	int ret;

	for (i = 0; i < TS_CAN1_NR_WINDOWS; i++) {
		card->sja = ts_can1_windows[i];
		if (ts_can1_claim(bus, card->sja, TS_CAN1_SJA1000_SIZE))
			continue;
		ts_can1_io_write(bus, mode, TS_CAN1_MODE_ENABLE | i);
		/*
		 * The core only probes chips with an ioremapped reg_base, so
		 * check here that something answers in the window.
		 */
		if (ts_can1_io_read(bus, card->sja + TS_CAN1_SJA1000_MOD) !=
		    TS_CAN1_SJA1000_ABSENT) {
			ret = register_sja1000dev(card->ndev);
			if (!ret)
				return 0;
			dev_dbg(&bus->pdev->dev, "SJA1000 window 0x%x: %d\n",
				card->sja, ret);
		}
		ts_can1_io_write(bus, mode, 0);
		ts_can1_release(bus, card->sja, TS_CAN1_SJA1000_SIZE);
	}
	return -ENXIO;
}

static int ts_can1_setup_card(struct ts_can1_bus *bus, unsigned int id,
			      unsigned int pld, u8 version, unsigned int line,
			      int irq)
{
	struct device *dev = &bus->pdev->dev;
	struct ts_can1_card *card;
	struct sja1000_priv *priv;
	struct net_device *ndev;
	int ret;

	ndev = alloc_sja1000dev(sizeof(*card));
	if (!ndev)
		return -ENOMEM;
	priv = netdev_priv(ndev);
	card = priv->priv;
	card->bus = bus;
	card->ndev = ndev;
	card->pld = pld;

	SET_NETDEV_DEV(ndev, dev);
	ndev->dev_port = id;
	ndev->irq = irq;
	priv->irq_flags = IRQF_SHARED;	/* cards may share a jumpered line */
	priv->read_reg = ts_can1_read_reg;
	priv->write_reg = ts_can1_write_reg;
	priv->can.clock.freq = TS_CAN1_XTAL_HZ / 2;
	priv->cdr = CDR_CBP | CDR_CLK_OFF;
	priv->ocr = OCR_TX0_PUSHPULL;

	ret = ts_can1_open_window(card);
	if (ret) {
		free_sja1000dev(ndev);
		return dev_err_probe(dev, ret,
				     "TS-CAN1 %u: no free SJA1000 window answers\n", id);
	}
	/* The vendor's convention: LED off once the card is in use. */
	ts_can1_io_write(bus, pld + TS_CAN1_PLD_LED, 0);
	netdev_info(ndev, "TS-CAN1 %u (PLD version %u) at 0x%x, SJA1000 at 0x%x, PC/104 IRQ%u (irq %d), %u Hz CAN clock\n",
		    id, version, pld, card->sja, line, irq, priv->can.clock.freq);
	return devm_add_action_or_reset(dev, ts_can1_remove_card, card);
}

/* Return: 0 with a card registered, -ENODEV if no card is there, or an error. */
static int ts_can1_add_card(struct ts_can1_bus *bus, unsigned int id)
{
	struct device *dev = &bus->pdev->dev;
	unsigned int pld = TS_CAN1_PLD_BASE(id);
	unsigned int line;
	u8 id1, id2, version;
	int irq, ret;

	ret = ts_can1_claim(bus, pld, TS_CAN1_PLD_SIZE);
	if (ret) {
		dev_info(dev, "TS-CAN1 %u: PLD addresses 0x%x in use, not probed\n", id, pld);
		return -ENODEV;
	}
	id1 = ts_can1_io_read(bus, pld + TS_CAN1_PLD_ID1);
	id2 = ts_can1_io_read(bus, pld + TS_CAN1_PLD_ID2);
	if (id1 != TS_CAN1_ID1_VALUE || id2 != TS_CAN1_ID2_VALUE) {
		/* An empty bus reads 0xff; anything else is another card. */
		if (id1 != 0xff || id2 != 0xff)
			dev_info(dev, "not a TS-CAN1 at 0x%x: ID 0x%02x 0x%02x\n",
				 pld, id1, id2);
		ret = -ENODEV;
		goto release;
	}
	version = ts_can1_io_read(bus, pld + TS_CAN1_PLD_VERSION);
	line = ts_can1_jumper_line(ts_can1_io_read(bus, pld + TS_CAN1_PLD_JUMPERS));
	if (!line) {
		dev_err(dev, "TS-CAN1 %u at 0x%x: no interrupt jumpered (set JP4 and/or JP5)\n",
			id, pld);
		ret = -EINVAL;
		goto release;
	}
	irq = ts_can1_line_irq(bus, line);
	if (irq < 0) {
		ret = dev_err_probe(dev, irq, "TS-CAN1 %u: no interrupt for PC/104 IRQ%u\n",
				    id, line);
		goto release;
	}
	ret = ts_can1_setup_card(bus, id, pld, version, line, irq);
	if (!ret)
		return 0;
release:
	ts_can1_release(bus, pld, TS_CAN1_PLD_SIZE);
	return ret;
}

/*
 * The TS-7800 powers up with the PC/104 pins as GPIOs; an 8-bit card needs
 * rows A and B in bus function. Rows C/D stay as they are: pins C14..C19 are
 * TS-UART 8/9. Done through the FPGA's regmap when the parent has one.
 */
static int ts_can1_enable_bus(struct device *dev)
{
	static const unsigned int rows[] = {
		TS7800_FPGA_PC104_ROWA_LO, TS7800_FPGA_PC104_ROWA_LO + 2,
		TS7800_FPGA_PC104_ROWB_LO, TS7800_FPGA_PC104_ROWB_LO + 2,
	};
	struct regmap *fpga;
	unsigned int i;
	int ret;

	fpga = dev->parent ? dev_get_regmap(dev->parent, "fpga") : NULL;
	if (!fpga)
		return 0;
	for (i = 0; i < ARRAY_SIZE(rows); i++) {
		ret = regmap_write(fpga, rows[i], TS7800_FPGA_PC104_FUNC_BUS);
		if (ret)
			return ret;
	}
	return 0;
}

static const struct regmap_config ts_can1_io_regmap_config = {
	.name		= TS_CAN1_IO_REGMAP,
	.reg_bits	= 32,
	.val_bits	= 8,
	.max_register	= TS_CAN1_IO_SIZE - 1,
	.readable_reg	= ts_can1_io_readable,
	.writeable_reg	= ts_can1_io_readable,
	.precious_reg	= ts_can1_io_precious,
	.cache_type	= REGCACHE_NONE,
};

static int ts_can1_map_bus(struct ts_can1_bus *bus)
{
	struct device *dev = &bus->pdev->dev;
	struct resource *res;
	void __iomem *base;

	if (dev->parent) {
		bus->io = dev_get_regmap(dev->parent, TS_CAN1_IO_REGMAP);
		if (bus->io)
			return 0;
	}
	res = platform_get_resource(bus->pdev, IORESOURCE_MEM, 0);
	if (!res || resource_size(res) < TS_CAN1_IO_SIZE)
		return dev_err_probe(dev, -EINVAL, "no PC/104 I/O window\n");
	/* Mapped whole, claimed per card (ts_can1_claim). */
	base = devm_ioremap(dev, res->start, TS_CAN1_IO_SIZE);
	if (!base)
		return -ENOMEM;
	bus->io = devm_regmap_init_mmio(dev, base, &ts_can1_io_regmap_config);
	if (IS_ERR(bus->io))
		return PTR_ERR(bus->io);
	bus->phys = res->start;
	return 0;
}

static int ts_can1_probe(struct platform_device *pdev)
{
	struct device *dev = &pdev->dev;
	struct ts_can1_bus *bus;
	unsigned int id, found = 0;
	int ret;

	bus = devm_kzalloc(dev, sizeof(*bus), GFP_KERNEL);
	if (!bus)
		return -ENOMEM;
	bus->pdev = pdev;

	ret = ts_can1_map_bus(bus);
	if (ret)
		return ret;
	ret = ts_can1_enable_bus(dev);
	if (ret)
		return dev_err_probe(dev, ret, "PC/104 bus function\n");

	for (id = 0; id < TS_CAN1_MAX_CARDS; id++) {
		if (!(pld_ids & BIT(id)))
			continue;
		ret = ts_can1_add_card(bus, id);
		if (!ret)
			found++;
		else if (ret == -ENOMEM || ret == -EPROBE_DEFER)
			return ret;
		/* Other errors are the card's: the next card may work. */
	}
	if (!found) {
		dev_info(dev, "no TS-CAN1 card found\n");
		return -ENODEV;
	}
	return 0;
}

static const struct platform_device_id ts_can1_ids[] = {
	{ .name = TS_CAN1_DEV_NAME },
	{ }
};
MODULE_DEVICE_TABLE(platform, ts_can1_ids);

static struct platform_driver ts_can1_driver = {
	.probe = ts_can1_probe,
	.id_table = ts_can1_ids,
	.driver = {
		.name = TS_CAN1_DEV_NAME,
	},
};

module_platform_driver(ts_can1_driver);

MODULE_DESCRIPTION("TS-CAN1 PC/104 CAN card (SJA1000) on a memory-mapped PC/104 bus");
MODULE_LICENSE("GPL");
