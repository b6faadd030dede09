// SPDX-License-Identifier: GPL-2.0
/*
 * TS-7800 FPGA interrupt demultiplexer.
 *
 * The FPGA raises its 32 interrupt sources as MSI writes into the Orion
 * host-to-CPU doorbell: source k sets doorbell cause bit k. The doorbell is
 * one main interrupt of the SoC (the parent). A source is delivered only
 * while it is enabled both in the doorbell mask and in the FPGA's own enable
 * mask at offset 0x204, so mask/unmask keep the two in step.
 *
 * The FPGA's enable mask is reached through the window's regmap, 16 bits at
 * a time like every FPGA register (docs/tsuart.md, "Access width"): source
 * k lives in one half, so switching it is one read-modify-write of that
 * half. The doorbell registers are the SoC's own, 32 bits wide.
 *
 * Doorbell cause bits are cleared by writing 0; writing 1 leaves a bit alone
 * (derived from the vendor's code, see docs/tsuart.md), so ack writes ~bit
 * and never races with a new MSI for another source.
 */
#include <linux/bitops.h>
#include <linux/io.h>
#include <linux/irq.h>
#include <linux/irqchip/chained_irq.h>
#include <linux/irqdomain.h>
#include <linux/regmap.h>
#include <linux/spinlock.h>
#include <linux/ts7800-fpga.h>

#include "ts7800-fpga-core.h"

#define DOORBELL_CAUSE	0x0
#define DOORBELL_MASK	0x4

struct ts7800_fpga_irq {
	struct regmap *fpga;
	void __iomem *doorbell;
	raw_spinlock_t lock;	/* read-modify-write of both mask registers */
	struct irq_domain *domain;
	struct fwnode_handle *fwnode;
	int parent_irq;
};

static void ts7800_fpga_irq_update(struct irq_data *d, bool enable)
{
	struct ts7800_fpga_irq *fi = irq_data_get_irq_chip_data(d);
	irq_hw_number_t hwirq = irqd_to_hwirq(d);
	unsigned int half = hwirq < 16 ? TS7800_FPGA_IRQ_MASK_LO : TS7800_FPGA_IRQ_MASK_HI;
	unsigned int fbit = BIT(hwirq % 16);
	u32 bit = BIT(hwirq);
	unsigned long flags;
	u32 db;

	raw_spin_lock_irqsave(&fi->lock, flags);
	db = readl(fi->doorbell + DOORBELL_MASK);
	if (enable)
		db |= bit;
	else
		db &= ~bit;
	regmap_update_bits(fi->fpga, half, fbit, enable ? fbit : 0);
	writel(db, fi->doorbell + DOORBELL_MASK);
	raw_spin_unlock_irqrestore(&fi->lock, flags);
}

static void ts7800_fpga_irq_mask(struct irq_data *d)
{
	ts7800_fpga_irq_update(d, false);
}

static void ts7800_fpga_irq_unmask(struct irq_data *d)
{
	ts7800_fpga_irq_update(d, true);
}

static void ts7800_fpga_irq_ack(struct irq_data *d)
{
	struct ts7800_fpga_irq *fi = irq_data_get_irq_chip_data(d);

	writel(~BIT(irqd_to_hwirq(d)), fi->doorbell + DOORBELL_CAUSE);
}

static struct irq_chip ts7800_fpga_irq_chip = {
	.name		= "ts7800-fpga",
	.irq_ack	= ts7800_fpga_irq_ack,
	.irq_mask	= ts7800_fpga_irq_mask,
	.irq_unmask	= ts7800_fpga_irq_unmask,
};

static void ts7800_fpga_irq_demux(struct irq_desc *desc)
{
	struct ts7800_fpga_irq *fi = irq_desc_get_handler_data(desc);
	struct irq_chip *chip = irq_desc_get_chip(desc);
	unsigned long pending;
	unsigned int bit;

	chained_irq_enter(chip, desc);
	pending = readl(fi->doorbell + DOORBELL_CAUSE) &
		  readl(fi->doorbell + DOORBELL_MASK);
	for_each_set_bit(bit, &pending, TS7800_FPGA_NR_IRQS)
		generic_handle_domain_irq(fi->domain, bit);
	chained_irq_exit(chip, desc);
}

static int ts7800_fpga_irq_map(struct irq_domain *d, unsigned int virq,
			       irq_hw_number_t hwirq)
{
	irq_set_chip_data(virq, d->host_data);
	irq_set_chip_and_handler(virq, &ts7800_fpga_irq_chip, handle_level_irq);
	irq_set_noprobe(virq);
	return 0;
}

static const struct irq_domain_ops ts7800_fpga_irq_domain_ops = {
	.map	= ts7800_fpga_irq_map,
	.xlate	= irq_domain_xlate_onecell,
};

static void ts7800_fpga_irq_mask_all(struct regmap *fpga)
{
	regmap_write(fpga, TS7800_FPGA_IRQ_MASK_LO, 0);
	regmap_write(fpga, TS7800_FPGA_IRQ_MASK_HI, 0);
}

static void ts7800_fpga_irq_teardown(void *data)
{
	struct ts7800_fpga_irq *fi = data;

	irq_set_chained_handler_and_data(fi->parent_irq, NULL, NULL);
	ts7800_fpga_irq_mask_all(fi->fpga);
	writel(0, fi->doorbell + DOORBELL_MASK);
	irq_domain_remove(fi->domain);
	irq_domain_free_fwnode(fi->fwnode);
}

/**
 * ts7800_fpga_irq_setup - demultiplex the doorbell into an irq domain
 * @dev: FPGA device (owns the devres)
 * @fpga: the FPGA window's regmap
 * @doorbell: mapped doorbell cause/mask registers
 * @parent_irq: the SoC's doorbell interrupt
 *
 * Return: the domain (hwirq k = FPGA source k) or an ERR_PTR.
 */
struct irq_domain *ts7800_fpga_irq_setup(struct device *dev,
					 struct regmap *fpga,
					 void __iomem *doorbell,
					 int parent_irq)
{
	struct ts7800_fpga_irq *fi;
	int ret;

	fi = devm_kzalloc(dev, sizeof(*fi), GFP_KERNEL);
	if (!fi)
		return ERR_PTR(-ENOMEM);
	fi->fpga = fpga;
	fi->doorbell = doorbell;
	fi->parent_irq = parent_irq;
	raw_spin_lock_init(&fi->lock);

	/* Start with every source off and nothing pending. */
	ts7800_fpga_irq_mask_all(fpga);
	writel(0, doorbell + DOORBELL_MASK);
	writel(0, doorbell + DOORBELL_CAUSE);

	fi->fwnode = irq_domain_alloc_named_fwnode(dev_name(dev));
	if (!fi->fwnode)
		return ERR_PTR(-ENOMEM);
	fi->domain = irq_domain_create_linear(fi->fwnode, TS7800_FPGA_NR_IRQS,
					      &ts7800_fpga_irq_domain_ops, fi);
	if (!fi->domain) {
		irq_domain_free_fwnode(fi->fwnode);
		return ERR_PTR(-ENOMEM);
	}
	irq_set_chained_handler_and_data(parent_irq, ts7800_fpga_irq_demux, fi);

	ret = devm_add_action_or_reset(dev, ts7800_fpga_irq_teardown, fi);
	return ret ? ERR_PTR(ret) : fi->domain;
}
