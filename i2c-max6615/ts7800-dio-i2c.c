// SPDX-License-Identifier: GPL-2.0
/*
 * Bit-banged I2C (SMBus) adapter on two TS-7800 DIO header pins, for the
 * BR-FAN1 fan board (its MAX6615 is handled by max6615.c).
 *
 * The seed did this from user space through /dev/mem (thesis 7.2.1). Here
 * the lines come from the DIO gpiochip (tsuart-fix/ts7800-dio.c) as
 * open-drain GPIOs: "1" releases the line to its pull-up, "0" pulls it low,
 * and both lines read back through the DIO input register. So SCL can be
 * read, i2c-algo-bit waits for a slave stretching the clock, and a slave
 * that holds SDA low after an interrupted transfer is freed with nine clocks
 * and a STOP (the i2c core's generic recovery) before the next transfer.
 *
 * The device is a child of the DIO header device (registered by
 * ts7800-dio.c once its gpiochip exists, removed before it); this module
 * binds to it and names its two lines in a GPIO lookup table.
 */
#include <linux/gpio/consumer.h>
#include <linux/gpio/machine.h>
#include <linux/i2c.h>
#include <linux/i2c-algo-bit.h>
#include <linux/module.h>
#include <linux/platform_device.h>
#include <linux/ts7800-fpga.h>
#include <compat/platform_remove.h>

/* BR-FAN1 default wiring (docs/dio-i2c.md); the seed's pins are unknown. */
static unsigned int scl_pin = 1;
module_param(scl_pin, uint, 0444);
MODULE_PARM_DESC(scl_pin, "DIO header pin of SCL (default 1)");

static unsigned int sda_pin = 3;
module_param(sda_pin, uint, 0444);
MODULE_PARM_DESC(sda_pin, "DIO header pin of SDA (default 3)");

static unsigned int bus_khz = 100;
module_param(bus_khz, uint, 0444);
MODULE_PARM_DESC(bus_khz, "Nominal SCL frequency in kHz, 1..100 (default 100)");

struct dio_i2c {
	struct i2c_adapter adap;
	struct i2c_algo_bit_data bit;
	struct i2c_bus_recovery_info recovery;
	struct gpio_desc *scl;
	struct gpio_desc *sda;
};

static void dio_i2c_setsda(void *data, int state)
{
	struct dio_i2c *bus = data;

	gpiod_set_value(bus->sda, state);
}

static void dio_i2c_setscl(void *data, int state)
{
	struct dio_i2c *bus = data;

	gpiod_set_value(bus->scl, state);
}

static int dio_i2c_getsda(void *data)
{
	struct dio_i2c *bus = data;

	return gpiod_get_value(bus->sda);
}

static int dio_i2c_getscl(void *data)
{
	struct dio_i2c *bus = data;

	return gpiod_get_value(bus->scl);
}

/*
 * Before every transfer: a previous transfer cut short (a signal, a glitch
 * on the wires) can leave a slave in the middle of a byte, holding SDA low.
 * Clock it out and send a STOP; if that fails the transfer would fail
 * anyway, so say why.
 */
static int dio_i2c_pre_xfer(struct i2c_adapter *adap)
{
	struct dio_i2c *bus = i2c_get_adapdata(adap);
	int ret;

	if (gpiod_get_value(bus->sda) > 0)
		return 0;
	dev_dbg(&adap->dev, "SDA held low before a transfer: bus recovery\n");
	ret = i2c_recover_bus(adap);
	if (ret)
		dev_warn_ratelimited(&adap->dev, "SDA held low, bus recovery failed: %d\n", ret);
	return ret;
}

static int dio_i2c_probe(struct platform_device *pdev)
{
	struct device *dev = &pdev->dev;
	struct dio_i2c *bus;
	int ret;

	bus = devm_kzalloc(dev, sizeof(*bus), GFP_KERNEL);
	if (!bus)
		return -ENOMEM;

	/* Released (high) from the start: nothing to disturb on the bus. */
	bus->scl = devm_gpiod_get(dev, "scl", GPIOD_OUT_HIGH_OPEN_DRAIN);
	if (IS_ERR(bus->scl))
		return dev_err_probe(dev, PTR_ERR(bus->scl), "SCL (DIO_%u)\n", scl_pin);
	bus->sda = devm_gpiod_get(dev, "sda", GPIOD_OUT_HIGH_OPEN_DRAIN);
	if (IS_ERR(bus->sda))
		return dev_err_probe(dev, PTR_ERR(bus->sda), "SDA (DIO_%u)\n", sda_pin);
	ret = gpiod_set_consumer_name(bus->scl, "i2c-scl");
	if (!ret)
		ret = gpiod_set_consumer_name(bus->sda, "i2c-sda");
	if (ret)
		return ret;

	bus->bit.data = bus;
	bus->bit.setsda = dio_i2c_setsda;
	bus->bit.setscl = dio_i2c_setscl;
	bus->bit.getsda = dio_i2c_getsda;
	bus->bit.getscl = dio_i2c_getscl;
	bus->bit.pre_xfer = dio_i2c_pre_xfer;
	/* udelay is half an SCL period: 5 us for 100 kHz */
	bus->bit.udelay = DIV_ROUND_UP(500, bus_khz);
	bus->bit.timeout = msecs_to_jiffies(100);

	bus->recovery.recover_bus = i2c_generic_scl_recovery;
	bus->recovery.scl_gpiod = bus->scl;
	bus->recovery.sda_gpiod = bus->sda;

	bus->adap.owner = THIS_MODULE;
	bus->adap.class = I2C_CLASS_HWMON;
	bus->adap.algo_data = &bus->bit;
	bus->adap.bus_recovery_info = &bus->recovery;
	bus->adap.dev.parent = dev;
	bus->adap.nr = -1;
	snprintf(bus->adap.name, sizeof(bus->adap.name),
		 "TS-7800 DIO I2C (SCL DIO_%u, SDA DIO_%u)", scl_pin, sda_pin);
	i2c_set_adapdata(&bus->adap, bus);

	ret = i2c_bit_add_bus(&bus->adap);
	if (ret)
		return dev_err_probe(dev, ret, "cannot add the adapter\n");
	platform_set_drvdata(pdev, bus);
	return 0;
}

static void dio_i2c_remove(struct platform_device *pdev)
{
	struct dio_i2c *bus = platform_get_drvdata(pdev);

	i2c_del_adapter(&bus->adap);
}

static struct platform_driver dio_i2c_driver = {
	.probe	= dio_i2c_probe,
	.PLATFORM_DRIVER_REMOVE = dio_i2c_remove,
	.driver	= {
		.name = TS7800_DIO_I2C_DEV_NAME,
	},
};

static struct gpiod_lookup_table dio_i2c_lookup = {
	.dev_id = TS7800_DIO_I2C_DEV_NAME,
	.table = {
		/* hardware numbers filled in from the module parameters */
		GPIO_LOOKUP(TS7800_DIO_DEV_NAME, 0, "scl", GPIO_OPEN_DRAIN),
		GPIO_LOOKUP(TS7800_DIO_DEV_NAME, 0, "sda", GPIO_OPEN_DRAIN),
		{ }
	},
};

static bool dio_i2c_pin_ok(unsigned int pin)
{
	return pin >= 1 && pin <= TS7800_DIO_NR_PINS &&
	       !(TS7800_DIO_BIT(pin) & TS7800_DIO_RESERVED);
}

static int __init dio_i2c_init(void)
{
	int ret;

	if (!dio_i2c_pin_ok(scl_pin) || !dio_i2c_pin_ok(sda_pin) ||
	    scl_pin == sda_pin) {
		pr_err("ts7800-dio-i2c: scl_pin/sda_pin must be two different free DIO pins\n");
		return -EINVAL;
	}
	if (!bus_khz || bus_khz > 100) {
		pr_err("ts7800-dio-i2c: bus_khz must be 1..100\n");
		return -EINVAL;
	}
	dio_i2c_lookup.table[0].chip_hwnum = scl_pin - 1;
	dio_i2c_lookup.table[1].chip_hwnum = sda_pin - 1;
	gpiod_add_lookup_table(&dio_i2c_lookup);

	ret = platform_driver_register(&dio_i2c_driver);
	if (ret)
		gpiod_remove_lookup_table(&dio_i2c_lookup);
	return ret;
}
module_init(dio_i2c_init);

static void __exit dio_i2c_exit(void)
{
	platform_driver_unregister(&dio_i2c_driver);
	gpiod_remove_lookup_table(&dio_i2c_lookup);
}
module_exit(dio_i2c_exit);

MODULE_DESCRIPTION("Bit-banged I2C on TS-7800 DIO pins (BR-FAN1 fan board)");
MODULE_LICENSE("GPL");
MODULE_ALIAS("platform:" TS7800_DIO_I2C_DEV_NAME);
