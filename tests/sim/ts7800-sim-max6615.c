// SPDX-License-Identifier: GPL-2.0
/*
 * Simulated TS-7800 FPGA: register model of the BR-FAN1 board's MAX6615,
 * reached through the bit-level I2C slave (ts7800-sim-i2c.c).
 *
 * Follows ../shared/specs/max6615.md. The model is evaluated lazily: every
 * register access and debugfs read first brings the chip up to the present
 * (OT and tach status, automatic target duty, ramp of the instantaneous
 * duty by the time elapsed). Every choice the spec marks (?) or 3P is
 * tagged MODEL below.
 *
 * /sys/kernel/debug/ts7800-sim/max6615/
 *   temp1, temp2     millidegrees C (write: set the sensor, 1/8 degree steps)
 *   fan1_rpm, fan2_rpm   fan speed; the tach count follows (0 = stalled)
 *   regs             read: all 256 registers as the master would read them
 *   bus              read: STARTs, STOPs, address ACKs/NACKs seen on the bus
 */
#include <linux/debugfs.h>
#include <linux/kernel.h>
#include <linux/math64.h>
#include <linux/module.h>
#include <linux/seq_file.h>

#include "ts7800-sim.h"

static unsigned int sim_chip_addr = 0x18;
module_param_named(max6615_addr, sim_chip_addr, uint, 0444);
MODULE_PARM_DESC(max6615_addr, "Bus address of the simulated MAX6615 (default 0x18, BR-FAN1)");

#define REG_TEMP(ch)		(0x00 + (ch))
#define REG_CONFIG		0x02
#define REG_OT_LIMIT(ch)	(0x03 + (ch))
#define REG_OT_STATUS		0x05
#define REG_START_DUTY(f)	(0x07 + (f))
#define REG_MAX_DUTY(f)		(0x09 + (f))
#define REG_TARGET_DUTY(f)	(0x0b + (f))
#define REG_INST_DUTY(f)	(0x0d + (f))
#define REG_START_TEMP(ch)	(0x0f + (ch))
#define REG_FAN_CONFIG		0x11
#define REG_DUTY_RATE		0x12
#define REG_DUTY_STEP		0x13
#define REG_PWM_FREQ		0x14
#define REG_TACH(f)		(0x18 + (f))
#define REG_TACH_LIMIT(f)	(0x1a + (f))
#define REG_FAN_STATUS		0x1c
#define REG_TEMP_EXT(ch)	(0x1e + (ch))
#define REG_REVISION		0xfd
#define REG_DEVICE_ID		0xfe
#define REG_MANUFACTURER	0xff

#define CONFIG_POR		BIT(6)
#define CONFIG_MIN_DUTY		BIT(2)
#define FAN_CONFIG_HYST_10	BIT(7)
#define FAN_CONFIG_STEP_2	BIT(6)
#define FAN_FOLLOWS(f, ch)	BIT(5 - 2 * (f) - (ch))
#define FAN_STATUS_FAIL(f)	BIT(7 - (f))
#define FAN_STATUS_TACH_OFF(f)	BIT(5 - (f))
#define FAN_STATUS_PIN_MASK	BIT(1)
#define FAN_STATUS_WRITABLE	GENMASK(5, 0)
#define OT_STATUS_BIT(ch)	BIT(7 - (ch))
#define DUTY_FULL		240
#define TACH_RPM_FACTOR		58500	/* 3P: RPM = 58500 / count */
#define TACH_STALLED		0xff

/* Read-only registers: writes are ignored. */
static bool sim_reg_readonly(u8 reg)
{
	switch (reg) {
	case REG_TEMP(0): case REG_TEMP(1):
	case REG_OT_STATUS:
	case REG_INST_DUTY(0): case REG_INST_DUTY(1):
	case REG_TACH(0): case REG_TACH(1):
	case REG_TEMP_EXT(0): case REG_TEMP_EXT(1):
	case REG_REVISION: case REG_DEVICE_ID: case REG_MANUFACTURER:
		return true;
	default:
		return false;
	}
}

/* Power-on values (DS unless tagged); temperatures and fans are kept. */
static void sim_max6615_por(struct sim_max6615 *chip)
{
	memset(chip->reg, 0, sizeof(chip->reg));
	chip->reg[REG_CONFIG] = 0x18;
	chip->reg[REG_OT_LIMIT(0)] = 110;	/* MODEL (?): reset value unknown */
	chip->reg[REG_OT_LIMIT(1)] = 110;
	chip->reg[REG_START_DUTY(0)] = 0x60;
	chip->reg[REG_START_DUTY(1)] = 0x60;
	chip->reg[REG_MAX_DUTY(0)] = 0xf0;
	chip->reg[REG_MAX_DUTY(1)] = 0xf0;
	chip->reg[REG_DUTY_RATE] = 0xb4;
	chip->reg[REG_DUTY_STEP] = 0x55;
	chip->reg[REG_PWM_FREQ] = 0x40;
	chip->reg[REG_TACH(0)] = TACH_STALLED;
	chip->reg[REG_TACH(1)] = TACH_STALLED;
	chip->reg[REG_TACH_LIMIT(0)] = 0xff;
	chip->reg[REG_TACH_LIMIT(1)] = 0xff;
	chip->reg[REG_REVISION] = 0x01;
	chip->reg[REG_DEVICE_ID] = 0x68;
	chip->reg[REG_MANUFACTURER] = 0x4d;
	memset(chip->fan_on, 0, sizeof(chip->fan_on));
	chip->ramp_t[0] = ktime_get();
	chip->ramp_t[1] = chip->ramp_t[0];
}

void sim_max6615_init(struct sim_max6615 *chip, u8 addr)
{
	chip->addr = addr;
	chip->temp_mc[0] = 25000;
	chip->temp_mc[1] = 25000;
	sim_max6615_por(chip);
	sim_max6615_update(chip);
}

/* MODEL: temperatures below 0 read 0, above 255.875 read 255.875 (DS). */
static void sim_max6615_temps(struct sim_max6615 *chip)
{
	unsigned int ch, eighths;

	for (ch = 0; ch < 2; ch++) {
		eighths = clamp(chip->temp_mc[ch], 0, 255875) / 125;
		chip->reg[REG_TEMP(ch)] = eighths >> 3;
		chip->reg[REG_TEMP_EXT(ch)] = (eighths & 7) << 5;
		if (chip->reg[REG_TEMP(ch)] > chip->reg[REG_OT_LIMIT(ch)])
			chip->reg[REG_OT_STATUS] |= OT_STATUS_BIT(ch);
		else
			chip->reg[REG_OT_STATUS] &= ~OT_STATUS_BIT(ch);
	}
}

/* Tach count from the set speed; a count above the limit is a failed fan. */
static void sim_max6615_tachs(struct sim_max6615 *chip)
{
	unsigned int f, count;
	u8 *status = &chip->reg[REG_FAN_STATUS];

	for (f = 0; f < 2; f++) {
		if (*status & FAN_STATUS_TACH_OFF(f))
			continue;
		count = chip->rpm[f] ? TACH_RPM_FACTOR / chip->rpm[f] : TACH_STALLED;
		chip->reg[REG_TACH(f)] = min_t(unsigned int, count, TACH_STALLED);
		/* MODEL (?): fails when count > limit; latched until read */
		if (chip->reg[REG_TACH(f)] > chip->reg[REG_TACH_LIMIT(f)])
			*status |= FAN_STATUS_FAIL(f);
	}
}

/*
 * MODEL (formula rebuilt from the DS variables, see the spec): the fan
 * starts at the fan-start temperature with the start duty and gains
 * 2 * step / 240 per temperature step (1 or 2 degrees) above it, up to the
 * max duty. Falling, it keeps running until the temperature is the
 * hysteresis (5 or 10 degrees) below the fan-start temperature; stopped, it
 * runs at 0, or at the start duty with MIN_DUTY.
 */
static unsigned int sim_max6615_curve(struct sim_max6615 *chip, unsigned int f,
				      unsigned int ch)
{
	u8 fan_config = chip->reg[REG_FAN_CONFIG];
	unsigned int temp = chip->reg[REG_TEMP(ch)];
	unsigned int start = chip->reg[REG_START_TEMP(ch)];
	unsigned int hyst = fan_config & FAN_CONFIG_HYST_10 ? 10 : 5;
	unsigned int tstep = fan_config & FAN_CONFIG_STEP_2 ? 2 : 1;
	unsigned int dstep = 2 * ((chip->reg[REG_DUTY_STEP] >> (f ? 0 : 4)) & 0xf);
	unsigned int duty;

	if (temp >= start)
		chip->fan_on[f][ch] = true;
	else if (temp + hyst < start)
		chip->fan_on[f][ch] = false;

	if (!chip->fan_on[f][ch])
		return chip->reg[REG_CONFIG] & CONFIG_MIN_DUTY ?
			chip->reg[REG_START_DUTY(f)] : 0;
	duty = chip->reg[REG_START_DUTY(f)];
	if (temp > start)
		duty += (temp - start) / tstep * dstep;
	return min_t(unsigned int, duty, chip->reg[REG_MAX_DUTY(f)]);
}

/* MODEL (?): code 0 instant, code n = 62.5 ms << (n - 1) per 2/240 step. */
static u64 sim_max6615_ramp_ns(struct sim_max6615 *chip, unsigned int f)
{
	unsigned int code = (chip->reg[REG_DUTY_RATE] >> (f ? 2 : 5)) & 7;

	return code ? (62500000ULL << (code - 1)) : 0;
}

static void sim_max6615_duty(struct sim_max6615 *chip, unsigned int f, ktime_t now)
{
	u8 fan_config = chip->reg[REG_FAN_CONFIG];
	unsigned int target, inst, ch, steps;
	u64 period, elapsed;

	if (fan_config & (FAN_FOLLOWS(f, 0) | FAN_FOLLOWS(f, 1))) {
		target = 0;
		/* MODEL (?): following both channels, the higher duty wins. */
		for (ch = 0; ch < 2; ch++)
			if (fan_config & FAN_FOLLOWS(f, ch))
				target = max(target, sim_max6615_curve(chip, f, ch));
		/* DS: fan 1 failed and bit 0 set: fan 2 at full speed */
		if (f == 1 && (chip->reg[REG_FAN_STATUS] & BIT(0)) &&
		    (chip->reg[REG_FAN_STATUS] & FAN_STATUS_FAIL(0)))
			target = DUTY_FULL;
		chip->reg[REG_TARGET_DUTY(f)] = target;
	}
	target = chip->reg[REG_TARGET_DUTY(f)];
	inst = chip->reg[REG_INST_DUTY(f)];
	period = sim_max6615_ramp_ns(chip, f);
	if (!period || inst == target) {
		chip->reg[REG_INST_DUTY(f)] = target;
		chip->ramp_t[f] = now;
		return;
	}
	elapsed = ktime_to_ns(ktime_sub(now, chip->ramp_t[f]));
	steps = min_t(u64, div64_u64(elapsed, period), 255);
	if (!steps)
		return;
	chip->ramp_t[f] = ktime_add_ns(chip->ramp_t[f], steps * period);
	if (inst < target)
		inst = min(inst + 2 * steps, target);
	else
		inst = target + 2 * steps >= inst ? target : inst - 2 * steps;
	chip->reg[REG_INST_DUTY(f)] = inst;
}

/* Bring every derived register up to the present. */
void sim_max6615_update(struct sim_max6615 *chip)
{
	ktime_t now = ktime_get();

	sim_max6615_temps(chip);
	sim_max6615_tachs(chip);
	sim_max6615_duty(chip, 0, now);
	sim_max6615_duty(chip, 1, now);
}

/* FAN_FAIL pin (open drain, active low): a failed fan unless masked. */
bool sim_max6615_fan_fail(struct sim_max6615 *chip)
{
	u8 status = chip->reg[REG_FAN_STATUS];

	return (status & (FAN_STATUS_FAIL(0) | FAN_STATUS_FAIL(1))) &&
	       !(status & FAN_STATUS_PIN_MASK);
}

/* Receive byte: the register at the pointer (MODEL (?): no auto-increment). */
u8 sim_max6615_read(struct sim_max6615 *chip)
{
	u8 val;

	sim_max6615_update(chip);
	val = chip->reg[chip->ptr];
	/* MODEL (?): fan failure bits clear when read, if the fan recovered */
	if (chip->ptr == REG_FAN_STATUS)
		chip->reg[REG_FAN_STATUS] &= ~(FAN_STATUS_FAIL(0) | FAN_STATUS_FAIL(1));
	return val;
}

void sim_max6615_write(struct sim_max6615 *chip, u8 val, bool pointer)
{
	u8 reg = chip->ptr;

	if (pointer) {
		chip->ptr = val;
		return;
	}
	sim_max6615_update(chip);
	if (sim_reg_readonly(reg))
		return;
	if (reg == REG_CONFIG && (val & CONFIG_POR)) {
		sim_max6615_por(chip);
	} else if (reg == REG_FAN_STATUS) {
		chip->reg[reg] = (chip->reg[reg] & ~FAN_STATUS_WRITABLE) |
				 (val & FAN_STATUS_WRITABLE);
	} else {
		chip->reg[reg] = val;
	}
	sim_max6615_update(chip);
}

/* debugfs ---------------------------------------------------------------- */

static int temp_get(void *data, u64 *val)
{
	struct sim_chip_knob *k = data;

	*val = (u64)(s64)READ_ONCE(k->sim->fan.temp_mc[k->idx]);
	return 0;
}

static int temp_set(void *data, u64 val)
{
	struct sim_chip_knob *k = data;
	s64 mc = (s64)val;
	unsigned long flags;

	if (mc < -273000 || mc > 300000)
		return -EINVAL;
	spin_lock_irqsave(&k->sim->lock, flags);
	k->sim->fan.temp_mc[k->idx] = mc;
	sim_max6615_update(&k->sim->fan);
	sim_dio_update(k->sim);
	spin_unlock_irqrestore(&k->sim->lock, flags);
	return 0;
}
DEFINE_DEBUGFS_ATTRIBUTE(temp_fops, temp_get, temp_set, "%lld\n");

static int rpm_get(void *data, u64 *val)
{
	struct sim_chip_knob *k = data;

	*val = READ_ONCE(k->sim->fan.rpm[k->idx]);
	return 0;
}

static int rpm_set(void *data, u64 val)
{
	struct sim_chip_knob *k = data;
	unsigned long flags;

	if (val > 100000)
		return -EINVAL;
	spin_lock_irqsave(&k->sim->lock, flags);
	k->sim->fan.rpm[k->idx] = val;
	sim_max6615_update(&k->sim->fan);
	sim_dio_update(k->sim);
	spin_unlock_irqrestore(&k->sim->lock, flags);
	return 0;
}
DEFINE_DEBUGFS_ATTRIBUTE(rpm_fops, rpm_get, rpm_set, "%llu\n");

/* Register image without side effects (status bits are not cleared). */
static int regs_show(struct seq_file *s, void *unused)
{
	struct ts7800_sim *sim = s->private;
	unsigned long flags;
	u8 *image;
	unsigned int r;

	image = kmalloc(sizeof(sim->fan.reg), GFP_KERNEL);
	if (!image)
		return -ENOMEM;
	spin_lock_irqsave(&sim->lock, flags);
	sim_max6615_update(&sim->fan);
	memcpy(image, sim->fan.reg, sizeof(sim->fan.reg));
	spin_unlock_irqrestore(&sim->lock, flags);
	for (r = 0; r < sizeof(sim->fan.reg); r++)
		seq_printf(s, "%02x%c", image[r], (r & 15) == 15 ? '\n' : ' ');
	kfree(image);
	return 0;
}
DEFINE_SHOW_ATTRIBUTE(regs);

static int bus_show(struct seq_file *s, void *unused)
{
	struct ts7800_sim *sim = s->private;
	struct sim_i2c bus;
	unsigned long flags;

	spin_lock_irqsave(&sim->lock, flags);
	bus = sim->i2c;
	spin_unlock_irqrestore(&sim->lock, flags);
	seq_printf(s, "starts %u\nstops %u\naddr_acks %u\naddr_nacks %u\n",
		   bus.starts, bus.stops, bus.addr_acks, bus.addr_nacks);
	return 0;
}
DEFINE_SHOW_ATTRIBUTE(bus);

void sim_max6615_debugfs_init(struct ts7800_sim *sim)
{
	struct dentry *dir = debugfs_create_dir("max6615", sim->debugfs);
	struct sim_chip_knob *knobs = sim->fan.knobs;
	unsigned int i;

	for (i = 0; i < 2; i++) {
		knobs[i].sim = sim;
		knobs[i].idx = i;
	}
	debugfs_create_file_unsafe("temp1", 0600, dir, &knobs[0], &temp_fops);
	debugfs_create_file_unsafe("temp2", 0600, dir, &knobs[1], &temp_fops);
	debugfs_create_file_unsafe("fan1_rpm", 0600, dir, &knobs[0], &rpm_fops);
	debugfs_create_file_unsafe("fan2_rpm", 0600, dir, &knobs[1], &rpm_fops);
	debugfs_create_file("regs", 0400, dir, sim, &regs_fops);
	debugfs_create_file("bus", 0400, dir, sim, &bus_fops);
}

/* The address from the module parameter, or -EINVAL. */
int sim_max6615_param_addr(void)
{
	return sim_chip_addr >= 0x03 && sim_chip_addr <= 0x77 ? sim_chip_addr : -EINVAL;
}
