// SPDX-License-Identifier: GPL-2.0
/*
 * TS-7800 DIO header as a gpiochip (child of the FPGA core or its simulator).
 *
 * The header has an input register (pin levels) and an output latch; an
 * output bit of 0 pulls the pin low, 1 releases it to its pull-up (thesis
 * 7.2.1). So every line is open-drain by construction and direction is
 * emulated the way the seed did it: "input" writes 1 to the latch and reads
 * the input register, "output" writes the value to the latch. Reading an
 * output line also reads the pin, which lets a released line show what the
 * bus does (needed by bit-banged I2C).
 *
 * The FPGA has no known DIO interrupt, so edge events are polled: while at
 * least one line has its interrupt enabled, a delayed work reads the input
 * register every poll_ms milliseconds and runs the nested handler of each
 * line whose enabled edge occurred. Pulses shorter than the poll period may
 * be missed; docs/dio-i2c.md says so.
 */
#include <linux/bitmap.h>
#include <linux/bitops.h>
#include <linux/gpio/driver.h>
#include <linux/interrupt.h>
#include <linux/irq.h>
#include <linux/module.h>
#include <linux/mutex.h>
#include <linux/platform_device.h>
#include <linux/regmap.h>
#include <linux/spinlock.h>
#include <linux/ts7800-fpga.h>
#include <linux/workqueue.h>

static unsigned int poll_ms = 2;
module_param(poll_ms, uint, 0644);
MODULE_PARM_DESC(poll_ms, "Edge polling period in ms while an edge is requested, 1..1000 (default 2)");

static const char * const ts7800_dio_names[TS7800_DIO_NR_PINS] = {
	"DIO_1", "DIO_2", "DIO_3", "DIO_4", "DIO_5", "DIO_6", "DIO_7", "DIO_8",
	"DIO_9", "DIO_10", "DIO_11", "DIO_12", "DIO_13", "DIO_14", "DIO_15",
	"DIO_16",
};

struct ts7800_dio {
	struct gpio_chip gc;
	struct regmap *map;
	spinlock_t lock;	/* out latch shadow and direction */
	u16 out;		/* what was written to the output latch */
	u16 dir_out;		/* lines the user configured as outputs */

	/* polled edge detection */
	struct mutex irq_lock;	/* irq bus lock: the fields below */
	u16 irq_enabled;
	u16 irq_rising;
	u16 irq_falling;
	u16 last_in;		/* input levels at the previous poll */
	struct delayed_work poll;
	bool polling;
	bool dying;		/* unbinding: polling never starts again */
};

static int ts7800_dio_read_in(struct ts7800_dio *dio, u16 *levels)
{
	unsigned int val;
	int ret;

	ret = regmap_read(dio->map, TS7800_DIO_IN, &val);
	if (!ret)
		*levels = val;
	return ret;
}

/* Called with dio->lock held: the latch is written with the shadow updated. */
static int ts7800_dio_latch(struct ts7800_dio *dio, unsigned int offset, int value)
{
	if (value)
		dio->out |= BIT(offset);
	else
		dio->out &= ~BIT(offset);
	return regmap_write(dio->map, TS7800_DIO_OUT, dio->out);
}

static int ts7800_dio_get_direction(struct gpio_chip *gc, unsigned int offset)
{
	struct ts7800_dio *dio = gpiochip_get_data(gc);

	return dio->dir_out & BIT(offset) ? GPIO_LINE_DIRECTION_OUT :
					    GPIO_LINE_DIRECTION_IN;
}

static int ts7800_dio_direction_input(struct gpio_chip *gc, unsigned int offset)
{
	struct ts7800_dio *dio = gpiochip_get_data(gc);
	unsigned long flags;
	int ret;

	spin_lock_irqsave(&dio->lock, flags);
	ret = ts7800_dio_latch(dio, offset, 1);
	if (!ret)
		dio->dir_out &= ~BIT(offset);
	spin_unlock_irqrestore(&dio->lock, flags);
	return ret;
}

static int ts7800_dio_direction_output(struct gpio_chip *gc, unsigned int offset,
				       int value)
{
	struct ts7800_dio *dio = gpiochip_get_data(gc);
	unsigned long flags;
	int ret;

	spin_lock_irqsave(&dio->lock, flags);
	ret = ts7800_dio_latch(dio, offset, value);
	if (!ret)
		dio->dir_out |= BIT(offset);
	spin_unlock_irqrestore(&dio->lock, flags);
	return ret;
}

static int ts7800_dio_get(struct gpio_chip *gc, unsigned int offset)
{
	struct ts7800_dio *dio = gpiochip_get_data(gc);
	u16 levels;
	int ret;

	ret = ts7800_dio_read_in(dio, &levels);
	return ret ? ret : !!(levels & BIT(offset));
}

static int ts7800_dio_get_multiple(struct gpio_chip *gc, unsigned long *mask,
				   unsigned long *bits)
{
	struct ts7800_dio *dio = gpiochip_get_data(gc);
	u16 levels;
	int ret;

	ret = ts7800_dio_read_in(dio, &levels);
	if (ret)
		return ret;
	*bits = (*bits & ~*mask) | (levels & *mask);
	return 0;
}

static void ts7800_dio_set(struct gpio_chip *gc, unsigned int offset, int value)
{
	struct ts7800_dio *dio = gpiochip_get_data(gc);
	unsigned long flags;

	spin_lock_irqsave(&dio->lock, flags);
	ts7800_dio_latch(dio, offset, value);
	spin_unlock_irqrestore(&dio->lock, flags);
}

static void ts7800_dio_set_multiple(struct gpio_chip *gc, unsigned long *mask,
				    unsigned long *bits)
{
	struct ts7800_dio *dio = gpiochip_get_data(gc);
	unsigned long flags;

	spin_lock_irqsave(&dio->lock, flags);
	dio->out = (dio->out & ~*mask) | (*bits & *mask);
	regmap_write(dio->map, TS7800_DIO_OUT, dio->out);
	spin_unlock_irqrestore(&dio->lock, flags);
}

/* The latch can only pull low or release: push-pull is not available. */
static int ts7800_dio_set_config(struct gpio_chip *gc, unsigned int offset,
				 unsigned long config)
{
	switch (pinconf_to_config_param(config)) {
	case PIN_CONFIG_DRIVE_OPEN_DRAIN:
		return 0;
	default:
		return -ENOTSUPP;
	}
}

static int ts7800_dio_init_valid_mask(struct gpio_chip *gc, unsigned long *valid,
				      unsigned int ngpios)
{
	bitmap_clear(valid, 0, ngpios);
	*valid = ~TS7800_DIO_RESERVED & GENMASK(TS7800_DIO_NR_PINS - 1, 0);
	return 0;
}

/* Polled edges ---------------------------------------------------------- */

static void ts7800_dio_poll(struct work_struct *work)
{
	struct ts7800_dio *dio = container_of(to_delayed_work(work),
					      struct ts7800_dio, poll);
	unsigned long fired;
	unsigned int offset;
	u16 now, rose, fell;
	bool polling;

	if (ts7800_dio_read_in(dio, &now))
		goto again;

	mutex_lock(&dio->irq_lock);
	rose = now & ~dio->last_in;
	fell = ~now & dio->last_in;
	fired = ((rose & dio->irq_rising) | (fell & dio->irq_falling)) &
		dio->irq_enabled;
	dio->last_in = now;
	mutex_unlock(&dio->irq_lock);

	for_each_set_bit(offset, &fired, TS7800_DIO_NR_PINS)
		handle_nested_irq(irq_find_mapping(dio->gc.irq.domain, offset));
again:
	mutex_lock(&dio->irq_lock);
	polling = dio->polling;
	mutex_unlock(&dio->irq_lock);
	if (polling)
		schedule_delayed_work(&dio->poll, msecs_to_jiffies(clamp(poll_ms, 1U, 1000U)));
}

static void ts7800_dio_irq_mask(struct irq_data *d)
{
	struct gpio_chip *gc = irq_data_get_irq_chip_data(d);
	struct ts7800_dio *dio = gpiochip_get_data(gc);
	irq_hw_number_t hwirq = irqd_to_hwirq(d);

	dio->irq_enabled &= ~BIT(hwirq);
	gpiochip_disable_irq(gc, hwirq);
}

static void ts7800_dio_irq_unmask(struct irq_data *d)
{
	struct gpio_chip *gc = irq_data_get_irq_chip_data(d);
	struct ts7800_dio *dio = gpiochip_get_data(gc);
	irq_hw_number_t hwirq = irqd_to_hwirq(d);

	gpiochip_enable_irq(gc, hwirq);
	dio->irq_enabled |= BIT(hwirq);
}

static int ts7800_dio_irq_set_type(struct irq_data *d, unsigned int type)
{
	struct gpio_chip *gc = irq_data_get_irq_chip_data(d);
	struct ts7800_dio *dio = gpiochip_get_data(gc);
	u16 bit = BIT(irqd_to_hwirq(d));

	if (type & ~IRQ_TYPE_EDGE_BOTH)
		return -EINVAL;	/* polled: levels cannot be acknowledged */
	dio->irq_rising &= ~bit;
	dio->irq_falling &= ~bit;
	if (type & IRQ_TYPE_EDGE_RISING)
		dio->irq_rising |= bit;
	if (type & IRQ_TYPE_EDGE_FALLING)
		dio->irq_falling |= bit;
	return 0;
}

static void ts7800_dio_irq_bus_lock(struct irq_data *d)
{
	struct gpio_chip *gc = irq_data_get_irq_chip_data(d);
	struct ts7800_dio *dio = gpiochip_get_data(gc);

	mutex_lock(&dio->irq_lock);
}

/* Polling runs exactly while some line has an enabled edge. */
static void ts7800_dio_irq_bus_sync_unlock(struct irq_data *d)
{
	struct gpio_chip *gc = irq_data_get_irq_chip_data(d);
	struct ts7800_dio *dio = gpiochip_get_data(gc);
	bool start = false, stop = false;
	u16 now;

	if (dio->irq_enabled && !dio->polling && !dio->dying) {
		if (!ts7800_dio_read_in(dio, &now))
			dio->last_in = now;
		dio->polling = true;
		start = true;
	} else if (!dio->irq_enabled && dio->polling) {
		dio->polling = false;
		stop = true;
	}
	mutex_unlock(&dio->irq_lock);

	if (start)
		schedule_delayed_work(&dio->poll, 0);
	if (stop)
		cancel_delayed_work_sync(&dio->poll);
}

static const struct irq_chip ts7800_dio_irq_chip = {
	.name			= "ts7800-dio",
	.irq_mask		= ts7800_dio_irq_mask,
	.irq_unmask		= ts7800_dio_irq_unmask,
	.irq_set_type		= ts7800_dio_irq_set_type,
	.irq_bus_lock		= ts7800_dio_irq_bus_lock,
	.irq_bus_sync_unlock	= ts7800_dio_irq_bus_sync_unlock,
	.flags			= IRQCHIP_IMMUTABLE | IRQCHIP_SKIP_SET_WAKE,
	GPIOCHIP_IRQ_RESOURCE_HELPERS,
};

/*
 * Registered after the gpiochip, so devres runs it before the gpiochip and
 * its interrupt domain go away: a poll still running then would look up
 * mappings in the freed domain. A line may still have its interrupt
 * requested (a user-space monitor holds it across the unbind), so polling
 * must also never start again.
 */
static void ts7800_dio_stop_poll(void *data)
{
	struct ts7800_dio *dio = data;

	mutex_lock(&dio->irq_lock);
	dio->dying = true;
	dio->polling = false;
	mutex_unlock(&dio->irq_lock);
	cancel_delayed_work_sync(&dio->poll);
}

static void ts7800_dio_remove_child(void *data)
{
	platform_device_unregister(data);
}

/*
 * The bit-banged I2C bus of the BR-FAN1 board (i2c-max6615/ts7800-dio-i2c.c)
 * is a child of the header, registered after the gpiochip: devres removes
 * it, and so releases its lines, before the gpiochip goes away. Without
 * that driver loaded the device stays unbound and costs nothing.
 */
static int ts7800_dio_add_i2c(struct device *dev)
{
	struct platform_device *child;

	child = platform_device_register_data(dev, TS7800_DIO_I2C_DEV_NAME,
					      PLATFORM_DEVID_NONE, NULL, 0);
	if (IS_ERR(child))
		return dev_err_probe(dev, PTR_ERR(child), "I2C bus device\n");
	return devm_add_action_or_reset(dev, ts7800_dio_remove_child, child);
}

static int ts7800_dio_probe(struct platform_device *pdev)
{
	struct device *dev = &pdev->dev;
	struct gpio_irq_chip *girq;
	struct ts7800_dio *dio;
	unsigned int val;
	int ret;

	if (!dev->parent)
		return -ENODEV;
	dio = devm_kzalloc(dev, sizeof(*dio), GFP_KERNEL);
	if (!dio)
		return -ENOMEM;
	dio->map = dev_get_regmap(dev->parent, NULL);
	if (!dio->map)
		return dev_err_probe(dev, -ENODEV, "no FPGA regmap\n");
	spin_lock_init(&dio->lock);
	mutex_init(&dio->irq_lock);
	INIT_DELAYED_WORK(&dio->poll, ts7800_dio_poll);

	/*
	 * Start from the latch as found (a boot script may hold a line low);
	 * every line reads as an input until a user drives it.
	 */
	ret = regmap_read(dio->map, TS7800_DIO_OUT, &val);
	if (ret)
		return ret;
	dio->out = val;

	dio->gc.label = TS7800_DIO_DEV_NAME;
	dio->gc.parent = dev;
	dio->gc.owner = THIS_MODULE;
	dio->gc.base = -1;
	dio->gc.ngpio = TS7800_DIO_NR_PINS;
	dio->gc.names = ts7800_dio_names;
	dio->gc.can_sleep = false;
	dio->gc.init_valid_mask = ts7800_dio_init_valid_mask;
	/*
	 * gpiolib 6.1 refuses lines outside the valid mask (the power and SPI
	 * pins) only for chips that have a request callback.
	 */
	dio->gc.request = gpiochip_generic_request;
	dio->gc.get_direction = ts7800_dio_get_direction;
	dio->gc.direction_input = ts7800_dio_direction_input;
	dio->gc.direction_output = ts7800_dio_direction_output;
	dio->gc.get = ts7800_dio_get;
	dio->gc.get_multiple = ts7800_dio_get_multiple;
	dio->gc.set = ts7800_dio_set;
	dio->gc.set_multiple = ts7800_dio_set_multiple;
	dio->gc.set_config = ts7800_dio_set_config;

	girq = &dio->gc.irq;
	gpio_irq_chip_set_chip(girq, &ts7800_dio_irq_chip);
	girq->handler = handle_simple_irq;
	girq->default_type = IRQ_TYPE_NONE;
	girq->threaded = true;

	ret = devm_gpiochip_add_data(dev, &dio->gc, dio);
	if (ret)
		return dev_err_probe(dev, ret, "cannot add gpiochip\n");
	ret = devm_add_action_or_reset(dev, ts7800_dio_stop_poll, dio);
	if (ret)
		return ret;
	return ts7800_dio_add_i2c(dev);
}

static struct platform_driver ts7800_dio_driver = {
	.probe	= ts7800_dio_probe,
	.driver	= {
		.name = TS7800_DIO_DEV_NAME,
	},
};
module_platform_driver(ts7800_dio_driver);

MODULE_DESCRIPTION("TS-7800 DIO header gpiochip (open-drain lines, polled edges)");
MODULE_LICENSE("GPL");
MODULE_ALIAS("platform:" TS7800_DIO_DEV_NAME);
