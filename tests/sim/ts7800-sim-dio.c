// SPDX-License-Identifier: GPL-2.0
/*
 * Simulated TS-7800 FPGA: the DIO header.
 *
 * Every pin is a wired-AND with a pull-up, as on the board (thesis 7.2.1):
 * it reads low when the output latch holds 0, when an outside device pulls
 * it low (debugfs "ext_low", "pause", "fan_fail") or when the simulated
 * MAX6615 pulls it (SDA of its bus, its FAN_FAIL output). Any change of the
 * levels is fed to the bit-level I2C slave before the register access
 * returns, so a bit-banging master sees the slave's answer on its next read.
 *
 * /sys/kernel/debug/ts7800-sim/dio/
 *   levels     read: the input register (pin levels)
 *   ext_low    bit n-1 set: an outside device holds header pin n low
 *   pause      1: the PAUSE signal is asserted (its pin pulled low)
 *   fan_fail   1: pull the FAN_FAIL pin low as a failing fan board would
 *   in_hold    write N (1..5000): the next read of the input register is held
 *              until 0 is written or N ms have passed; read: enum sim_dio_hold
 *              (0 off, 1 armed, 2 holding a read, 3 the last hold expired)
 */
#include <linux/debugfs.h>
#include <linux/ktime.h>
#include <linux/module.h>

#include "ts7800-sim.h"

/*
 * MODEL (?): the pins of the BR-FAN1 board on the header are not documented
 * anywhere we have; these defaults match i2c-max6615/ts7800-dio-i2c.c and
 * docs/dio-i2c.md.
 */
static unsigned int sim_scl_pin = 1;
module_param_named(dio_scl_pin, sim_scl_pin, uint, 0444);
MODULE_PARM_DESC(dio_scl_pin, "Header pin of the simulated MAX6615's SCL (default 1)");

static unsigned int sim_sda_pin = 3;
module_param_named(dio_sda_pin, sim_sda_pin, uint, 0444);
MODULE_PARM_DESC(dio_sda_pin, "Header pin of the simulated MAX6615's SDA (default 3)");

static unsigned int sim_pause_pin = 5;
module_param_named(dio_pause_pin, sim_pause_pin, uint, 0444);
MODULE_PARM_DESC(dio_pause_pin, "Header pin of the PAUSE input (default 5)");

static unsigned int sim_fan_fail_pin = 7;
module_param_named(dio_fan_fail_pin, sim_fan_fail_pin, uint, 0444);
MODULE_PARM_DESC(dio_fan_fail_pin, "Header pin of the MAX6615 FAN_FAIL output (default 7)");

#define SIM_DIO_PINS	GENMASK(TS7800_DIO_NR_PINS - 1, 0)

static bool sim_dio_pin_ok(unsigned int pin)
{
	return pin >= 1 && pin <= TS7800_DIO_NR_PINS &&
	       !(TS7800_DIO_BIT(pin) & TS7800_DIO_RESERVED);
}

int sim_dio_init(struct ts7800_sim *sim)
{
	struct sim_dio *dio = &sim->dio;

	if (!sim_dio_pin_ok(sim_scl_pin) || !sim_dio_pin_ok(sim_sda_pin) ||
	    !sim_dio_pin_ok(sim_pause_pin) || !sim_dio_pin_ok(sim_fan_fail_pin))
		return dev_err_probe(sim->dev, -EINVAL, "DIO pin parameter names a reserved pin\n");
	if (hweight16(TS7800_DIO_BIT(sim_scl_pin) | TS7800_DIO_BIT(sim_sda_pin) |
		      TS7800_DIO_BIT(sim_pause_pin) | TS7800_DIO_BIT(sim_fan_fail_pin)) != 4)
		return dev_err_probe(sim->dev, -EINVAL, "DIO pin parameters must differ\n");
	dio->scl = sim_scl_pin;
	dio->sda = sim_sda_pin;
	dio->pause = sim_pause_pin;
	dio->fan_fail = sim_fan_fail_pin;
	/* MODEL (?): the latch resets to all ones, every pin released. */
	dio->out = SIM_DIO_PINS;
	sim->i2c.scl = true;
	sim->i2c.sda = true;
	return 0;
}

/*
 * MODEL (?): the power pins (2, 16) read 0; nothing says what the FPGA
 * returns for them.
 */
static u16 sim_dio_levels(struct sim_dio *dio)
{
	u16 low = ~dio->out | dio->ext_low | dio->chip_low;

	return ~low & SIM_DIO_PINS & ~TS7800_DIO_POWER_PINS;
}

/*
 * Let the bus settle: the slave may change SDA in answer to an SCL edge,
 * which is itself a level change (with SCL low, so at most one more round).
 */
void sim_dio_update(struct ts7800_sim *sim)
{
	struct sim_dio *dio = &sim->dio;
	unsigned int round;
	bool scl, sda;
	u16 levels;

	if (sim_max6615_fan_fail(&sim->fan))
		dio->chip_low |= TS7800_DIO_BIT(dio->fan_fail);
	else
		dio->chip_low &= ~TS7800_DIO_BIT(dio->fan_fail);

	for (round = 0; round < 4; round++) {
		levels = sim_dio_levels(dio);
		scl = levels & TS7800_DIO_BIT(dio->scl);
		sda = levels & TS7800_DIO_BIT(dio->sda);
		if (scl == sim->i2c.scl && sda == sim->i2c.sda)
			break;
		sim_i2c_bus(sim, scl, sda);
		if (sim->i2c.drive_low)
			dio->chip_low |= TS7800_DIO_BIT(dio->sda);
		else
			dio->chip_low &= ~TS7800_DIO_BIT(dio->sda);
	}
}

u16 sim_dio_read_in(struct ts7800_sim *sim)
{
	sim_dio_update(sim);
	return sim_dio_levels(&sim->dio);
}

/*
 * A test holds one read of the input register to hold the DIO driver's
 * edge poll in the middle of its work while it unbinds the driver (the
 * teardown order of the poll and the gpiochip, dio-i2c/unbind-poll). The
 * regmap calls this with its spinlock held, interrupts off: a busy wait,
 * bounded by hold_ms; the levels are sampled after it, so a change made
 * while the read is held is what the read returns.
 */
#define SIM_DIO_HOLD_MAX_MS	5000

void sim_dio_hold_read(struct ts7800_sim *sim)
{
	struct sim_dio *dio = &sim->dio;
	ktime_t end;

	if (atomic_cmpxchg(&dio->hold, SIM_DIO_HOLD_ARMED,
			   SIM_DIO_HOLD_HOLDING) != SIM_DIO_HOLD_ARMED)
		return;
	end = ktime_add_ms(ktime_get(), READ_ONCE(dio->hold_ms));
	while (atomic_read(&dio->hold) == SIM_DIO_HOLD_HOLDING) {
		if (ktime_after(ktime_get(), end)) {
			atomic_cmpxchg(&dio->hold, SIM_DIO_HOLD_HOLDING,
				       SIM_DIO_HOLD_EXPIRED);
			break;
		}
		cpu_relax();
	}
}

void sim_dio_write_out(struct ts7800_sim *sim, u16 val)
{
	sim->dio.out = val;
	sim_dio_update(sim);
}

/* debugfs ---------------------------------------------------------------- */

static int levels_get(void *data, u64 *val)
{
	struct ts7800_sim *sim = data;
	unsigned long flags;

	spin_lock_irqsave(&sim->lock, flags);
	*val = sim_dio_read_in(sim);
	spin_unlock_irqrestore(&sim->lock, flags);
	return 0;
}
DEFINE_DEBUGFS_ATTRIBUTE(levels_fops, levels_get, NULL, "0x%04llx\n");

static int ext_low_get(void *data, u64 *val)
{
	struct ts7800_sim *sim = data;

	*val = READ_ONCE(sim->dio.ext_low);
	return 0;
}

static int ext_low_set(void *data, u64 val)
{
	struct ts7800_sim *sim = data;
	unsigned long flags;

	if (val & ~(u64)SIM_DIO_PINS)
		return -EINVAL;
	spin_lock_irqsave(&sim->lock, flags);
	sim->dio.ext_low = val;
	sim_dio_update(sim);
	spin_unlock_irqrestore(&sim->lock, flags);
	return 0;
}
DEFINE_DEBUGFS_ATTRIBUTE(ext_low_fops, ext_low_get, ext_low_set, "0x%04llx\n");

/* One named input: asserted = pulled low by the outside. */
static int sim_dio_pin_get(struct ts7800_sim *sim, unsigned int pin, u64 *val)
{
	*val = !!(READ_ONCE(sim->dio.ext_low) & TS7800_DIO_BIT(pin));
	return 0;
}

static int sim_dio_pin_set(struct ts7800_sim *sim, unsigned int pin, u64 val)
{
	unsigned long flags;

	if (val > 1)
		return -EINVAL;
	spin_lock_irqsave(&sim->lock, flags);
	if (val)
		sim->dio.ext_low |= TS7800_DIO_BIT(pin);
	else
		sim->dio.ext_low &= ~TS7800_DIO_BIT(pin);
	sim_dio_update(sim);
	spin_unlock_irqrestore(&sim->lock, flags);
	return 0;
}

static int pause_get(void *data, u64 *val)
{
	struct ts7800_sim *sim = data;

	return sim_dio_pin_get(sim, sim->dio.pause, val);
}

static int pause_set(void *data, u64 val)
{
	struct ts7800_sim *sim = data;

	return sim_dio_pin_set(sim, sim->dio.pause, val);
}
DEFINE_DEBUGFS_ATTRIBUTE(pause_fops, pause_get, pause_set, "%llu\n");

static int fan_fail_get(void *data, u64 *val)
{
	struct ts7800_sim *sim = data;

	return sim_dio_pin_get(sim, sim->dio.fan_fail, val);
}

static int fan_fail_set(void *data, u64 val)
{
	struct ts7800_sim *sim = data;

	return sim_dio_pin_set(sim, sim->dio.fan_fail, val);
}
DEFINE_DEBUGFS_ATTRIBUTE(fan_fail_fops, fan_fail_get, fan_fail_set, "%llu\n");

static int in_hold_get(void *data, u64 *val)
{
	struct ts7800_sim *sim = data;

	*val = atomic_read(&sim->dio.hold);
	return 0;
}

/* 0 releases a held read (or disarms); N arms the next read for N ms. */
static int in_hold_set(void *data, u64 val)
{
	struct ts7800_sim *sim = data;

	if (val > SIM_DIO_HOLD_MAX_MS)
		return -EINVAL;
	if (!val) {
		atomic_set(&sim->dio.hold, SIM_DIO_HOLD_OFF);
		return 0;
	}
	if (atomic_read(&sim->dio.hold) == SIM_DIO_HOLD_HOLDING)
		return -EBUSY;
	WRITE_ONCE(sim->dio.hold_ms, val);
	atomic_set(&sim->dio.hold, SIM_DIO_HOLD_ARMED);
	return 0;
}
DEFINE_DEBUGFS_ATTRIBUTE(in_hold_fops, in_hold_get, in_hold_set, "%llu\n");

void sim_dio_debugfs_init(struct ts7800_sim *sim)
{
	struct dentry *dir = debugfs_create_dir("dio", sim->debugfs);

	debugfs_create_file_unsafe("levels", 0400, dir, sim, &levels_fops);
	debugfs_create_file_unsafe("ext_low", 0600, dir, sim, &ext_low_fops);
	debugfs_create_file_unsafe("pause", 0600, dir, sim, &pause_fops);
	debugfs_create_file_unsafe("fan_fail", 0600, dir, sim, &fan_fail_fops);
	debugfs_create_file_unsafe("in_hold", 0600, dir, sim, &in_hold_fops);
	debugfs_create_u32("scl_pin", 0400, dir, &sim->dio.scl);
	debugfs_create_u32("sda_pin", 0400, dir, &sim->dio.sda);
	debugfs_create_u32("pause_pin", 0400, dir, &sim->dio.pause);
	debugfs_create_u32("fan_fail_pin", 0400, dir, &sim->dio.fan_fail);
}
