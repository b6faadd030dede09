// SPDX-License-Identifier: GPL-2.0
/*
 * Simulated TS-7800 FPGA (test only, never loaded on the robot).
 *
 * Registers a parent device that looks to the child drivers exactly like the
 * hardware FPGA core: a 16-bit regmap of the FPGA window and an irq domain
 * whose hwirq k is FPGA interrupt source k. The children are registered by
 * the core's own ts7800_fpga_add_uarts(), so the same TS-UART driver binds
 * to them. Behind the registers sits a model of the TS-UARTs
 * (ts7800-sim-uart.c), a wire per port (ts7800-sim-wire.c), debugfs fault
 * injection (ts7800-sim-debugfs.c), and the DIO header (ts7800-sim-dio.c)
 * with the BR-FAN1 board's MAX6615 on two of its pins (ts7800-sim-i2c.c,
 * ts7800-sim-max6615.c). The DIO child is registered by the core's
 * ts7800_fpga_add_dio().
 */
#include <linux/debugfs.h>
#include <linux/irq.h>
#include <linux/irqdomain.h>
#include <linux/module.h>
#include <linux/platform_device.h>
#include <linux/regmap.h>

#include "ts7800-sim.h"

#define SIM_DRV_NAME		"ts7800-sim"
#define SIM_FIFO_DEPTH_MAX	256

unsigned int sim_fifo_depth = 16;
module_param_named(fifo_depth, sim_fifo_depth, uint, 0444);
MODULE_PARM_DESC(fifo_depth, "RX and TX FIFO depth of every port, 1..256 (default 16)");

static bool sim_edge_irq;
module_param_named(edge_irq, sim_edge_irq, bool, 0444);
MODULE_PARM_DESC(edge_irq, "Sources are events (rising edge) instead of levels (default level)");

bool sim_oerr_clear_on_data;
module_param_named(oerr_clear_on_data, sim_oerr_clear_on_data, bool, 0444);
MODULE_PARM_DESC(oerr_clear_on_data, "OERR clears on the next DATA read instead of on STAT read");

static bool sim_rowc_bus;
module_param_named(pc104_rowc_bus, sim_rowc_bus, bool, 0444);
MODULE_PARM_DESC(pc104_rowc_bus, "PC/104 pins C14..C19 in bus use: only TS-UART 0..7 exist");

static struct platform_device *sim_pdev;

/*
 * The interrupt rule of the model, in one place (unknown on the hardware):
 * a TS-UART source is "high" while its RX FIFO holds a character or its TX
 * FIFO ran empty since STAT was last read. The FPGA turns the source into a
 * doorbell cause bit that stays set until acked:
 *  - level (default): whenever the source is high and enabled in the FPGA
 *    mask (so also again at unmask time while it is still high);
 *  - edge (edge_irq=1): only when the source rises while enabled; a rise
 *    while masked is lost, as an MSI that was never sent.
 */
void ts7800_sim_irq_source(struct ts7800_sim *sim, unsigned int hwirq, bool level)
{
	u32 bit = BIT(hwirq);
	unsigned long flags;
	bool rose;

	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	rose = level && !(sim->irq_level & bit);
	if (level)
		sim->irq_level |= bit;
	else
		sim->irq_level &= ~bit;
	if ((sim->irq_enable & bit) && (sim->edge ? rose : level))
		sim->irq_cause |= bit;
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
}

/* Latched, enabled and not held: what the CPU would be interrupted for now. */
static unsigned long sim_irq_pending(struct ts7800_sim *sim)
{
	unsigned long pending, flags;

	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	pending = sim->irq_hold ? 0 : sim->irq_cause & sim->irq_enable;
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
	return pending;
}

/*
 * Deliver every pending source. Only from hard irq context with no model
 * lock held: the simulator's own timers (directly, saving an IPI per
 * character; on PREEMPT_RT they run in the softirq thread and kick the
 * irq_work instead) and the irq_work below.
 */
void ts7800_sim_irq_deliver(struct ts7800_sim *sim)
{
	unsigned long pending = sim_irq_pending(sim);
	unsigned int bit;

	for_each_set_bit(bit, &pending, TS7800_FPGA_NR_IRQS)
		generic_handle_domain_irq(sim->domain, bit);
}

/*
 * Delivery after a register access: the caller may be the driver's own ISR
 * (holding its port lock), so the interrupt is raised through irq_work.
 */
void ts7800_sim_irq_kick(struct ts7800_sim *sim)
{
	if (sim_irq_pending(sim))
		irq_work_queue(&sim->irq_work);
}

/*
 * Fault injection: while held, latched interrupts are not delivered, as if
 * the CPU were busy elsewhere; the UARTs keep running (and overrun).
 */
void ts7800_sim_irq_set_hold(struct ts7800_sim *sim, bool hold)
{
	unsigned long flags;

	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	sim->irq_hold = hold;
	if (!hold && (sim->irq_cause & sim->irq_enable))
		irq_work_queue(&sim->irq_work);
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
}

/*
 * Fault injection: the doorbell rings for an enabled source that has nothing
 * to report (a spurious interrupt, as a glitch or a stale MSI would cause).
 */
void ts7800_sim_irq_raise(struct ts7800_sim *sim, unsigned int hwirq)
{
	unsigned long flags;

	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	sim->irq_cause |= BIT(hwirq) & sim->irq_enable;
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
	ts7800_sim_irq_kick(sim);
}

static void sim_irq_work(struct irq_work *work)
{
	ts7800_sim_irq_deliver(container_of(work, struct ts7800_sim, irq_work));
}

static void sim_irq_ack(struct irq_data *d)
{
	struct ts7800_sim *sim = irq_data_get_irq_chip_data(d);
	unsigned long flags;

	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	sim->irq_cause &= ~BIT(irqd_to_hwirq(d));
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
}

static void sim_irq_mask(struct irq_data *d)
{
	struct ts7800_sim *sim = irq_data_get_irq_chip_data(d);
	unsigned long flags;

	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	sim->irq_enable &= ~BIT(irqd_to_hwirq(d));
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
}

static void sim_irq_unmask(struct irq_data *d)
{
	struct ts7800_sim *sim = irq_data_get_irq_chip_data(d);
	u32 bit = BIT(irqd_to_hwirq(d));
	unsigned long flags;

	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	sim->irq_enable |= bit;
	if (!sim->edge && (sim->irq_level & bit))
		sim->irq_cause |= bit;
	if ((sim->irq_cause & bit) && !sim->irq_hold)
		irq_work_queue(&sim->irq_work);
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
}

static struct irq_chip sim_irq_chip = {
	.name		= SIM_DRV_NAME,
	.irq_ack	= sim_irq_ack,
	.irq_mask	= sim_irq_mask,
	.irq_unmask	= sim_irq_unmask,
};

static int sim_irq_map(struct irq_domain *d, unsigned int virq, irq_hw_number_t hwirq)
{
	struct ts7800_sim *sim = d->host_data;

	irq_set_chip_data(virq, sim);
	irq_set_chip_and_handler(virq, &sim_irq_chip,
				 sim->edge ? handle_edge_irq : handle_level_irq);
	irq_set_noprobe(virq);
	return 0;
}

static const struct irq_domain_ops sim_irq_domain_ops = {
	.map	= sim_irq_map,
	.xlate	= irq_domain_xlate_onecell,
};

static void sim_remove_domain(void *data)
{
	struct ts7800_sim *sim = data;

	irq_domain_remove(sim->domain);
	irq_domain_free_fwnode(sim->fwnode);
}

static int sim_setup_irq(struct ts7800_sim *sim)
{
	sim->edge = sim_edge_irq;
	raw_spin_lock_init(&sim->irq_lock);
	/* Deliver in hard irq context even on PREEMPT_RT, like a real irq. */
	sim->irq_work = IRQ_WORK_INIT_HARD(sim_irq_work);

	sim->fwnode = irq_domain_alloc_named_fwnode(SIM_DRV_NAME);
	if (!sim->fwnode)
		return -ENOMEM;
	sim->domain = irq_domain_create_linear(sim->fwnode, TS7800_FPGA_NR_IRQS,
					       &sim_irq_domain_ops, sim);
	if (!sim->domain) {
		irq_domain_free_fwnode(sim->fwnode);
		return -ENOMEM;
	}
	return devm_add_action_or_reset(sim->dev, sim_remove_domain, sim);
}

static void sim_stop_engines(void *data)
{
	struct ts7800_sim *sim = data;
	unsigned long flags;
	unsigned int n;

	spin_lock_irqsave(&sim->lock, flags);
	sim->stopping = true;
	spin_unlock_irqrestore(&sim->lock, flags);
	for (n = 0; n < sim->nports; n++)
		sim_uart_stop(&sim->uart[n]);
	irq_work_sync(&sim->irq_work);
}

static void sim_remove_wires(void *data)
{
	struct ts7800_sim *sim = data;
	unsigned int n;

	for (n = 0; n < sim->nports; n++)
		sim_wire_unregister(&sim->uart[n]);
}

static void sim_remove_debugfs(void *data)
{
	struct ts7800_sim *sim = data;

	debugfs_remove_recursive(sim->debugfs);
}

static int sim_probe(struct platform_device *pdev)
{
	struct device *dev = &pdev->dev;
	struct regmap_config map_config;
	struct ts7800_sim *sim;
	struct regmap *map;
	unsigned int n;
	int ret, nports;
	u8 rev;

	sim = devm_kzalloc(dev, sizeof(*sim), GFP_KERNEL);
	if (!sim)
		return -ENOMEM;
	sim->dev = dev;
	spin_lock_init(&sim->lock);
	/* MODEL: after power-up the row C pins are GPIO unless told otherwise. */
	sim->rowc = sim_rowc_bus ? TS7800_FPGA_ROWC_UART89_PINS : 0;
	sim->nports = sim_rowc_bus ? TS7800_UART_ALWAYS_PORTS : TS7800_UART_MAX_PORTS;

	ret = sim_setup_irq(sim);
	if (ret)
		return ret;
	ret = sim_dio_init(sim);
	if (ret)
		return ret;
	ret = sim_max6615_param_addr();
	if (ret < 0)
		return dev_err_probe(dev, ret, "bad max6615_addr\n");
	sim_max6615_init(&sim->fan, ret);
	for (n = 0; n < sim->nports; n++) {
		ret = sim_uart_init(sim, &sim->uart[n], n);
		if (ret)
			return ret;
	}
	ret = devm_add_action_or_reset(dev, sim_stop_engines, sim);
	if (ret)
		return ret;

	/* The hardware core's register rules, over the model instead of MMIO. */
	map_config = ts7800_fpga_regmap_config;
	map_config.fast_io = true;	/* used from interrupt handlers */
	map_config.use_raw_spinlock = false;	/* the model's lock is a spinlock_t */
	map_config.reg_read = sim_reg_read;
	map_config.reg_write = sim_reg_write;
	map = devm_regmap_init(dev, NULL, sim, &map_config);
	if (IS_ERR(map))
		return PTR_ERR(map);

	for (n = 0; n < sim->nports; n++) {
		ret = sim_wire_register(&sim->uart[n]);
		if (ret) {
			while (n--)
				sim_wire_unregister(&sim->uart[n]);
			return ret;
		}
	}
	ret = devm_add_action_or_reset(dev, sim_remove_wires, sim);
	if (ret)
		return ret;

	sim_debugfs_init(sim);
	sim_dio_debugfs_init(sim);
	sim_max6615_debugfs_init(sim);
	ret = devm_add_action_or_reset(dev, sim_remove_debugfs, sim);
	if (ret)
		return ret;

	/* From here on exactly what the hardware core does. */
	ret = ts7800_fpga_identify(map, &rev);
	if (ret)
		return ret;
	ret = ts7800_fpga_write_divisors(map);
	if (ret)
		return ret;
	nports = ts7800_fpga_add_uarts(dev, map, sim->domain);
	if (nports < 0)
		return nports;
	ret = ts7800_fpga_add_dio(dev);
	if (ret)
		return ret;

	dev_info(dev, "simulated TS-7800 FPGA rev %u: %d TS-UARTs, FIFO depth %u, %s interrupts\n",
		 rev, nports, sim_fifo_depth, sim->edge ? "edge" : "level");
	return 0;
}

static struct platform_driver sim_driver = {
	.probe	= sim_probe,
	.driver	= {
		.name = SIM_DRV_NAME,
		/* The wires and debugfs files must not outlive an unbind. */
		.suppress_bind_attrs = true,
	},
};

static int __init sim_init(void)
{
	int ret;

	if (!sim_fifo_depth || sim_fifo_depth > SIM_FIFO_DEPTH_MAX)
		return -EINVAL;
	ret = platform_driver_register(&sim_driver);
	if (ret)
		return ret;
	sim_pdev = platform_device_register_simple(SIM_DRV_NAME, PLATFORM_DEVID_NONE, NULL, 0);
	if (IS_ERR(sim_pdev)) {
		platform_driver_unregister(&sim_driver);
		return PTR_ERR(sim_pdev);
	}
	return 0;
}
module_init(sim_init);

static void __exit sim_exit(void)
{
	platform_device_unregister(sim_pdev);
	platform_driver_unregister(&sim_driver);
}
module_exit(sim_exit);

MODULE_DESCRIPTION("Simulated TS-7800 FPGA with TS-UARTs, DIO and a MAX6615 (test only)");
MODULE_LICENSE("GPL");
MODULE_INFO(test, "Y");
