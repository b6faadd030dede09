// SPDX-License-Identifier: GPL-2.0
/*
 * Hardware monitoring driver for the Maxim MAX6615 and MAX6616: two
 * thermistor (or one thermistor and the die) temperature channels, two PWM
 * fan outputs with a temperature-driven automatic mode, and two tachometer
 * inputs with fan-failure detection.
 *
 * Datasheet: Maxim 19-3713 Rev 2, "Dual-Channel Temperature Monitors and
 * Fan-Speed Controllers with Thermistor Inputs".
 *
 * The chip speaks SMBus byte-data only. Its settings belong to whoever
 * configured the board: the driver identifies the chip before it writes
 * anything and never rewrites a setting on its own.
 */

#include <linux/bitfield.h>
#include <linux/bits.h>
#include <linux/err.h>
#include <linux/hwmon.h>
#include <linux/hwmon-sysfs.h>
#include <linux/i2c.h>
#include <linux/kernel.h>
#include <linux/minmax.h>
#include <linux/module.h>
#include <linux/mod_devicetable.h>
#include <linux/mutex.h>
#include <linux/regmap.h>
#include <linux/util_macros.h>
#include <compat/i2c_probe.h>

/* Register map (datasheet table 3) */
#define MAX6615_REG_TEMP(ch)		(0x00 + (ch))
#define MAX6615_REG_CONFIG		0x02
#define MAX6615_REG_OT_LIMIT(ch)	(0x03 + (ch))
#define MAX6615_REG_OT_STATUS		0x05
#define MAX6615_REG_OT_MASK		0x06
#define MAX6615_REG_START_DUTY(ch)	(0x07 + (ch))
#define MAX6615_REG_MAX_DUTY(ch)	(0x09 + (ch))
#define MAX6615_REG_TARGET_DUTY(ch)	(0x0b + (ch))
#define MAX6615_REG_INST_DUTY(ch)	(0x0d + (ch))
#define MAX6615_REG_FAN_START_TEMP(ch)	(0x0f + (ch))
#define MAX6615_REG_FAN_CONFIG		0x11
#define MAX6615_REG_DUTY_RATE		0x12
#define MAX6615_REG_DUTY_STEP		0x13
#define MAX6615_REG_PWM_FREQ		0x14
#define MAX6615_REG_GPIO_FUNC		0x15	/* MAX6616 only */
#define MAX6615_REG_GPIO_VALUE		0x16	/* MAX6616 only */
#define MAX6615_REG_THERM_OFFSET	0x17
#define MAX6615_REG_TACH(ch)		(0x18 + (ch))
#define MAX6615_REG_TACH_LIMIT(ch)	(0x1a + (ch))
#define MAX6615_REG_FAN_STATUS		0x1c
#define MAX6615_REG_TEMP_EXT(ch)	(0x1e + (ch))
#define MAX6615_REG_REVISION		0xfd
#define MAX6615_REG_DEVICE_ID		0xfe
#define MAX6615_REG_MANUFACTURER_ID	0xff

/* Identification (datasheet table 3); the MAX6616 answers the same. */
#define MAX6615_REVISION		0x01
#define MAX6615_DEVICE_ID		0x68
#define MAX6615_MANUFACTURER_ID		0x4d

/* CONFIG (02h), bits 7..2 from datasheet table 4 */
#define MAX6615_CONFIG_STANDBY		BIT(7)

/* TEMPn_EXT: bits 7..5 are 1/2, 1/4 and 1/8 degree (datasheet table 1) */
#define MAX6615_TEMP_EXT_MASK		GENMASK(7, 5)
#define MAX6615_TEMP_MC_PER_LSB		125	/* 1/8 degree in m°C */

/* THERM_OFFSET (17h): 4-bit two's complement per channel, 2 °C/LSB (DS) */
#define MAX6615_OFFSET_SHIFT(ch)	((ch) ? 0 : 4)
#define MAX6615_OFFSET_MASK(ch)		(GENMASK(3, 0) << MAX6615_OFFSET_SHIFT(ch))
#define MAX6615_OFFSET_SIGN_BIT		3
#define MAX6615_OFFSET_MC_PER_LSB	2000
#define MAX6615_OFFSET_MIN_MC		(-8 * MAX6615_OFFSET_MC_PER_LSB)
#define MAX6615_OFFSET_MAX_MC		(7 * MAX6615_OFFSET_MC_PER_LSB)

/* FAN_CONFIG (11h): fan n follows temperature channel t (DS table 3) */
#define MAX6615_FAN_CONFIG_FOLLOWS(fan, temp)	BIT(5 - 2 * (fan) - (temp))
/* both "follows" bits of one fan */
#define MAX6615_FAN_CONFIG_AUTO_MASK(fan)	(GENMASK(1, 0) << (4 - 2 * (fan)))

/* FAN_STATUS (1Ch, DS table 3) */
#define MAX6615_FAN_STATUS_FAIL(ch)		BIT(7 - (ch))
#define MAX6615_FAN_STATUS_TACH_DISABLE(ch)	BIT(5 - (ch))

/* Duty registers count in 1/240; anything above 240 is 100 % (DS). */
#define MAX6615_DUTY_FULL		240

/* A tach limit of FFh can never be exceeded: fan-fail detection is off. */
#define MAX6615_TACH_LIMIT_OFF		0xff

/*
 * Register facts that the public datasheet copies leave open. Each one is
 * a single definition here so that a check against the chip changes one
 * line. Sources: DS = datasheet 19-3713, TH = thesis of the team that used
 * the chip on the BR-FAN1 board, 3P = third-party code that agrees.
 */

/*
 * RPM = 58500 / count at 2 pulses per revolution (3P, three sources agree;
 * the application note read literally gives twice that)
 */
#define MAX6615_TACH_RPM_FACTOR		58500
/* Tach value FFh: fan stalled or not measured yet (DS) */
#define MAX6615_TACH_STALLED		0xff
/* PWM_FREQ (14h) bits 7..6: 20/33/50/100 Hz (3P; 33 Hz = POR 40h per DS) */
#define MAX6615_PWM_FREQ_LOW_MASK	GENMASK(7, 6)
static const unsigned int max6615_pwm_freq_low_hz[] = { 20, 33, 50, 100 };
/* PWM_FREQ (14h) bit 5 selects 35 kHz for logic-level PWM inputs (3P) */
#define MAX6615_PWM_FREQ_FAST		BIT(5)
#define MAX6615_PWM_FREQ_FAST_HZ	35000
/* OT_STATUS (05h): bit 7 channel 1, bit 6 channel 2 (3P) */
#define MAX6615_OT_STATUS_ALARM(ch)	BIT(7 - (ch))
/* CONFIG bit 1: temperature channel 2 measures the die, not TH2 (TH) */
#define MAX6615_CONFIG_TEMP2_LOCAL	BIT(1)
/* CONFIG bit 0: fan spin-up disabled (TH); documented, not used */
#define MAX6615_CONFIG_SPINUP_DISABLE	BIT(0)

/* hwmon_temp_type values (Documentation/ABI/testing/sysfs-class-hwmon) */
#define MAX6615_TEMP_TYPE_DIODE		3	/* the die sensor is a diode (DS) */
#define MAX6615_TEMP_TYPE_THERMISTOR	4

#define MAX6615_CHANNELS		2
#define MAX6615_DUTY_REGS		6	/* start, max, target x 2 */

struct max6615_duty_shadow {
	bool valid;
	unsigned int regval;	/* what the write put in the register */
	long pwm;		/* the ABI value that was written */
};

struct max6615_data {
	struct regmap *regmap;
	/*
	 * Serialises every register sequence and the shadows below: the 6.1
	 * hwmon core calls read/write without a lock of its own.
	 */
	struct mutex lock;
	/* temperature channels (bit 0 = temp1) used when pwmN_enable is set to 2 */
	unsigned int auto_channels[MAX6615_CHANNELS];
	/*
	 * 256 pwm values map onto 241 duty steps; remembering the last write
	 * lets a value read back unchanged while the chip keeps the register.
	 */
	struct max6615_duty_shadow duty[MAX6615_DUTY_REGS];
	/*
	 * Alarm and fault bits seen in OT_STATUS and FAN_STATUS but not yet
	 * reported through their attribute. The fan-fail bits may clear when
	 * FAN_STATUS is read, and every fan attribute reads it: without this
	 * a failure read by fanN_input would never reach fanN_fault.
	 */
	unsigned int ot_latched;
	unsigned int fan_latched;
};

static bool max6615_readable_reg(struct device *dev, unsigned int reg)
{
	/* 15h/16h exist on the MAX6616 only; this driver leaves the GPIOs alone. */
	return (reg <= MAX6615_REG_TEMP_EXT(1) && reg != MAX6615_REG_GPIO_FUNC &&
		reg != MAX6615_REG_GPIO_VALUE) || reg >= MAX6615_REG_REVISION;
}

static bool max6615_writeable_reg(struct device *dev, unsigned int reg)
{
	switch (reg) {
	case MAX6615_REG_CONFIG:
	case MAX6615_REG_OT_LIMIT(0) ... MAX6615_REG_OT_LIMIT(1):
	case MAX6615_REG_OT_MASK ... MAX6615_REG_TARGET_DUTY(1):
	case MAX6615_REG_FAN_START_TEMP(0) ... MAX6615_REG_PWM_FREQ:
	case MAX6615_REG_THERM_OFFSET:
	case MAX6615_REG_TACH_LIMIT(0) ... MAX6615_REG_FAN_STATUS:
		return true;
	default:
		return false;
	}
}

/* Registers that the chip itself changes: never served from the cache. */
static bool max6615_volatile_reg(struct device *dev, unsigned int reg)
{
	switch (reg) {
	case MAX6615_REG_TEMP(0):
	case MAX6615_REG_TEMP(1):
	case MAX6615_REG_OT_STATUS:
	case MAX6615_REG_TARGET_DUTY(0):
	case MAX6615_REG_TARGET_DUTY(1):
	case MAX6615_REG_INST_DUTY(0):
	case MAX6615_REG_INST_DUTY(1):
	case MAX6615_REG_GPIO_VALUE:
	case MAX6615_REG_TACH(0):
	case MAX6615_REG_TACH(1):
	case MAX6615_REG_FAN_STATUS:
	case MAX6615_REG_TEMP_EXT(0):
	case MAX6615_REG_TEMP_EXT(1):
		return true;
	default:
		return false;
	}
}

static const struct regmap_config max6615_regmap_config = {
	.reg_bits = 8,
	.val_bits = 8,
	.max_register = MAX6615_REG_MANUFACTURER_ID,
	.readable_reg = max6615_readable_reg,
	.writeable_reg = max6615_writeable_reg,
	.volatile_reg = max6615_volatile_reg,
	.cache_type = REGCACHE_RBTREE,
	/* SMBus byte-data only: no auto-increment on this chip */
	.use_single_read = true,
	.use_single_write = true,
};

static long max6615_duty_to_pwm(unsigned int regval)
{
	if (regval >= MAX6615_DUTY_FULL)
		return 255;
	return DIV_ROUND_CLOSEST(regval * 255, MAX6615_DUTY_FULL);
}

static unsigned int max6615_pwm_to_duty(long pwm)
{
	return DIV_ROUND_CLOSEST(clamp_val(pwm, 0, 255) * MAX6615_DUTY_FULL, 255);
}

static int max6615_duty_index(unsigned int reg)
{
	return reg - MAX6615_REG_START_DUTY(0);
}

/* Caller holds data->lock. */
static int max6615_read_duty(struct max6615_data *data, unsigned int reg,
			     long *val)
{
	struct max6615_duty_shadow *shadow = &data->duty[max6615_duty_index(reg)];
	unsigned int regval;
	int ret;

	ret = regmap_read(data->regmap, reg, &regval);
	if (ret)
		return ret;
	if (shadow->valid && shadow->regval == regval)
		*val = shadow->pwm;
	else
		*val = max6615_duty_to_pwm(regval);
	return 0;
}

/* Caller holds data->lock. */
static int max6615_write_duty(struct max6615_data *data, unsigned int reg,
			      long val)
{
	struct max6615_duty_shadow *shadow = &data->duty[max6615_duty_index(reg)];
	unsigned int regval = max6615_pwm_to_duty(val);
	int ret;

	ret = regmap_write(data->regmap, reg, regval);
	if (ret) {
		shadow->valid = false;
		return ret;
	}
	shadow->valid = true;
	shadow->regval = regval;
	shadow->pwm = clamp_val(val, 0, 255);
	return 0;
}

static long max6615_tach_to_rpm(unsigned int count)
{
	if (count == MAX6615_TACH_STALLED)
		return 0;
	return DIV_ROUND_CLOSEST(MAX6615_TACH_RPM_FACTOR, max(count, 1U));
}

/*
 * Caller holds data->lock. The datasheet does not say whether reading TEMPn
 * latches TEMPn_EXT (?): when a conversion ends between the two reads, the
 * MSB changes and the EXT read is repeated to match the new MSB.
 */
static int max6615_read_temp(struct max6615_data *data, int channel, long *val)
{
	unsigned int msb, msb_again, ext;
	int ret;

	ret = regmap_read(data->regmap, MAX6615_REG_TEMP(channel), &msb);
	if (ret)
		return ret;
	ret = regmap_read(data->regmap, MAX6615_REG_TEMP_EXT(channel), &ext);
	if (ret)
		return ret;
	ret = regmap_read(data->regmap, MAX6615_REG_TEMP(channel), &msb_again);
	if (ret)
		return ret;
	if (msb_again != msb) {
		msb = msb_again;
		ret = regmap_read(data->regmap, MAX6615_REG_TEMP_EXT(channel), &ext);
		if (ret)
			return ret;
	}

	*val = (msb * 8 + FIELD_GET(MAX6615_TEMP_EXT_MASK, ext)) *
		MAX6615_TEMP_MC_PER_LSB;
	return 0;
}

/*
 * Read OT_STATUS or FAN_STATUS and remember its alarm/fault bits until the
 * attribute reporting them has been read (max6615_read_latched()), as
 * mainline hwmon drivers keep latched alarms. Caller holds data->lock.
 */
static int max6615_read_status(struct max6615_data *data, unsigned int reg,
			       unsigned int *regval)
{
	int ret;

	ret = regmap_read(data->regmap, reg, regval);
	if (ret)
		return ret;
	if (reg == MAX6615_REG_OT_STATUS)
		data->ot_latched |= *regval & (MAX6615_OT_STATUS_ALARM(0) |
					       MAX6615_OT_STATUS_ALARM(1));
	else
		data->fan_latched |= *regval & (MAX6615_FAN_STATUS_FAIL(0) |
						MAX6615_FAN_STATUS_FAIL(1));
	return 0;
}

/*
 * An alarm or fault attribute: set if the condition is present now or was
 * seen since the attribute was last read; reading it clears the memory.
 * Caller holds data->lock.
 */
static int max6615_read_latched(struct max6615_data *data, unsigned int reg,
				unsigned int mask, long *val)
{
	unsigned int regval, *latched;
	int ret;

	ret = max6615_read_status(data, reg, &regval);
	if (ret)
		return ret;
	latched = reg == MAX6615_REG_OT_STATUS ? &data->ot_latched : &data->fan_latched;
	*val = !!(*latched & mask);
	*latched &= ~mask;
	return 0;
}

/* A whole-degree register (OT limit, fan-start temperature) in m°C. */
static int max6615_read_degrees(struct max6615_data *data, unsigned int reg,
				long *val)
{
	unsigned int regval;
	int ret;

	ret = regmap_read(data->regmap, reg, &regval);
	if (ret)
		return ret;
	*val = regval * 1000L;
	return 0;
}

static int max6615_write_degrees(struct max6615_data *data, unsigned int reg,
				 long val)
{
	val = clamp_val(val, 0, 255000);
	return regmap_write(data->regmap, reg, DIV_ROUND_CLOSEST(val, 1000));
}

static int max6615_read_offset(struct max6615_data *data, int channel,
			       long *val)
{
	unsigned int regval;
	int ret;

	ret = regmap_read(data->regmap, MAX6615_REG_THERM_OFFSET, &regval);
	if (ret)
		return ret;
	regval = (regval & MAX6615_OFFSET_MASK(channel)) >>
		 MAX6615_OFFSET_SHIFT(channel);
	*val = sign_extend32(regval, MAX6615_OFFSET_SIGN_BIT) *
	       MAX6615_OFFSET_MC_PER_LSB;
	return 0;
}

static int max6615_write_offset(struct max6615_data *data, int channel,
				long val)
{
	long steps;

	val = clamp_val(val, MAX6615_OFFSET_MIN_MC, MAX6615_OFFSET_MAX_MC);
	steps = DIV_ROUND_CLOSEST(val, MAX6615_OFFSET_MC_PER_LSB);
	return regmap_update_bits(data->regmap, MAX6615_REG_THERM_OFFSET,
				  MAX6615_OFFSET_MASK(channel),
				  ((unsigned int)steps << MAX6615_OFFSET_SHIFT(channel)) &
				  MAX6615_OFFSET_MASK(channel));
}

static int max6615_read_temp_type(struct max6615_data *data, int channel,
				  long *val)
{
	unsigned int config;
	int ret;

	if (channel == 0) {
		*val = MAX6615_TEMP_TYPE_THERMISTOR;
		return 0;
	}
	ret = regmap_read(data->regmap, MAX6615_REG_CONFIG, &config);
	if (ret)
		return ret;
	*val = config & MAX6615_CONFIG_TEMP2_LOCAL ? MAX6615_TEMP_TYPE_DIODE :
						     MAX6615_TEMP_TYPE_THERMISTOR;
	return 0;
}

static int max6615_read_temp_attr(struct max6615_data *data, u32 attr,
				  int channel, long *val)
{
	switch (attr) {
	case hwmon_temp_input:
		return max6615_read_temp(data, channel, val);
	case hwmon_temp_crit:
		return max6615_read_degrees(data, MAX6615_REG_OT_LIMIT(channel), val);
	case hwmon_temp_crit_alarm:
		return max6615_read_latched(data, MAX6615_REG_OT_STATUS,
					    MAX6615_OT_STATUS_ALARM(channel), val);
	case hwmon_temp_offset:
		return max6615_read_offset(data, channel, val);
	case hwmon_temp_type:
		return max6615_read_temp_type(data, channel, val);
	default:
		return -EOPNOTSUPP;
	}
}

static int max6615_read_fan_input(struct max6615_data *data, int channel,
				  long *val)
{
	unsigned int status, count;
	int ret;

	ret = max6615_read_status(data, MAX6615_REG_FAN_STATUS, &status);
	if (ret)
		return ret;
	if (status & MAX6615_FAN_STATUS_TACH_DISABLE(channel))
		return -ENODATA;	/* fanN_enable = 0 (ABI) */
	ret = regmap_read(data->regmap, MAX6615_REG_TACH(channel), &count);
	if (ret)
		return ret;
	*val = max6615_tach_to_rpm(count);
	return 0;
}

/* The fan fails when its tach count exceeds the limit (DS "Fan-Fail"). */
static int max6615_read_fan_min(struct max6615_data *data, int channel,
				long *val)
{
	unsigned int limit;
	int ret;

	ret = regmap_read(data->regmap, MAX6615_REG_TACH_LIMIT(channel), &limit);
	if (ret)
		return ret;
	*val = limit == MAX6615_TACH_LIMIT_OFF ? 0 : max6615_tach_to_rpm(limit);
	return 0;
}

static int max6615_write_fan_min(struct max6615_data *data, int channel,
				 long val)
{
	unsigned int limit;

	if (val <= 0) {
		limit = MAX6615_TACH_LIMIT_OFF;
	} else {
		val = min_t(long, val, MAX6615_TACH_RPM_FACTOR);
		limit = clamp_val(DIV_ROUND_CLOSEST(MAX6615_TACH_RPM_FACTOR, val),
				  1, MAX6615_TACH_LIMIT_OFF - 1);
	}
	return regmap_write(data->regmap, MAX6615_REG_TACH_LIMIT(channel), limit);
}

static int max6615_read_fan_attr(struct max6615_data *data, u32 attr,
				 int channel, long *val)
{
	unsigned int status;
	int ret;

	switch (attr) {
	case hwmon_fan_input:
		return max6615_read_fan_input(data, channel, val);
	case hwmon_fan_min:
		return max6615_read_fan_min(data, channel, val);
	case hwmon_fan_fault:
		return max6615_read_latched(data, MAX6615_REG_FAN_STATUS,
					    MAX6615_FAN_STATUS_FAIL(channel), val);
	case hwmon_fan_enable:
		ret = max6615_read_status(data, MAX6615_REG_FAN_STATUS, &status);
		if (ret)
			return ret;
		*val = !(status & MAX6615_FAN_STATUS_TACH_DISABLE(channel));
		return 0;
	default:
		return -EOPNOTSUPP;
	}
}

/* FAN_CONFIG bits of one fan as an ABI temperature-channel mask. */
static unsigned int max6615_fan_config_to_channels(unsigned int fan_config,
						   int fan)
{
	unsigned int channels = 0;
	int temp;

	for (temp = 0; temp < MAX6615_CHANNELS; temp++)
		if (fan_config & MAX6615_FAN_CONFIG_FOLLOWS(fan, temp))
			channels |= BIT(temp);
	return channels;
}

static unsigned int max6615_channels_to_fan_config(unsigned int channels,
						   int fan)
{
	unsigned int fan_config = 0;
	int temp;

	for (temp = 0; temp < MAX6615_CHANNELS; temp++)
		if (channels & BIT(temp))
			fan_config |= MAX6615_FAN_CONFIG_FOLLOWS(fan, temp);
	return fan_config;
}

/*
 * Caller holds data->lock. Reads which temperature channels drive the fan;
 * none means manual mode. A selection found in automatic mode is
 * remembered, so that a round trip through manual mode restores it.
 */
static int max6615_read_fan_mode(struct max6615_data *data, int channel,
				 unsigned int *channels)
{
	unsigned int fan_config;
	int ret;

	ret = regmap_read(data->regmap, MAX6615_REG_FAN_CONFIG, &fan_config);
	if (ret)
		return ret;
	*channels = max6615_fan_config_to_channels(fan_config, channel);
	if (*channels)
		data->auto_channels[channel] = *channels;
	return 0;
}

/* Caller holds data->lock. */
static int max6615_read_pwm_freq(struct max6615_data *data, long *val)
{
	unsigned int regval;
	int ret;

	ret = regmap_read(data->regmap, MAX6615_REG_PWM_FREQ, &regval);
	if (ret)
		return ret;
	if (regval & MAX6615_PWM_FREQ_FAST)
		*val = MAX6615_PWM_FREQ_FAST_HZ;
	else
		*val = max6615_pwm_freq_low_hz[FIELD_GET(MAX6615_PWM_FREQ_LOW_MASK,
							 regval)];
	return 0;
}

/* The frequency register is shared: pwm1_freq and pwm2_freq are one value. */
static int max6615_write_pwm_freq(struct max6615_data *data, long val)
{
	long low_max = max6615_pwm_freq_low_hz[ARRAY_SIZE(max6615_pwm_freq_low_hz) - 1];
	unsigned int code;

	/* The closest setting: 35 kHz from the midpoint to the fastest low one. */
	if (val >= (low_max + MAX6615_PWM_FREQ_FAST_HZ) / 2)
		return regmap_update_bits(data->regmap, MAX6615_REG_PWM_FREQ,
					  MAX6615_PWM_FREQ_FAST,
					  MAX6615_PWM_FREQ_FAST);
	code = find_closest(clamp_val(val, 0, low_max), max6615_pwm_freq_low_hz,
			    ARRAY_SIZE(max6615_pwm_freq_low_hz));
	return regmap_update_bits(data->regmap, MAX6615_REG_PWM_FREQ,
				  MAX6615_PWM_FREQ_FAST | MAX6615_PWM_FREQ_LOW_MASK,
				  FIELD_PREP(MAX6615_PWM_FREQ_LOW_MASK, code));
}

static int max6615_read_pwm_attr(struct max6615_data *data, u32 attr,
				 int channel, long *val)
{
	unsigned int channels;
	int ret;

	switch (attr) {
	case hwmon_pwm_input:
		return max6615_read_duty(data, MAX6615_REG_TARGET_DUTY(channel), val);
	case hwmon_pwm_enable:
		ret = max6615_read_fan_mode(data, channel, &channels);
		if (ret)
			return ret;
		*val = channels ? 2 : 1;
		return 0;
	case hwmon_pwm_auto_channels_temp:
		ret = max6615_read_fan_mode(data, channel, &channels);
		if (ret)
			return ret;
		*val = data->auto_channels[channel];
		return 0;
	case hwmon_pwm_freq:
		return max6615_read_pwm_freq(data, val);
	default:
		return -EOPNOTSUPP;
	}
}

/* Caller holds data->lock. */
static int max6615_write_pwm_input(struct max6615_data *data, int channel,
				   long val)
{
	unsigned int channels;
	int ret;

	/* In automatic mode the chip owns the target duty register. */
	ret = max6615_read_fan_mode(data, channel, &channels);
	if (ret)
		return ret;
	if (channels)
		return -EBUSY;
	return max6615_write_duty(data, MAX6615_REG_TARGET_DUTY(channel), val);
}

/* Caller holds data->lock. */
static int max6615_write_pwm_enable(struct max6615_data *data, int channel,
				    long val)
{
	unsigned int fan_config, channels;
	int ret;

	if (val != 1 && val != 2)
		return -EINVAL;
	ret = max6615_read_fan_mode(data, channel, &channels);
	if (ret)
		return ret;
	if (val == 1)
		fan_config = 0;
	else
		fan_config = max6615_channels_to_fan_config(data->auto_channels[channel],
							    channel);
	return regmap_update_bits(data->regmap, MAX6615_REG_FAN_CONFIG,
				  MAX6615_FAN_CONFIG_AUTO_MASK(channel), fan_config);
}

/*
 * Caller holds data->lock. In manual mode the selection is only remembered
 * for the next switch to automatic mode.
 */
static int max6615_write_auto_channels(struct max6615_data *data, int channel,
				       long val)
{
	unsigned int channels;
	int ret;

	if (val < 1 || val > (1 << MAX6615_CHANNELS) - 1)
		return -EINVAL;
	ret = max6615_read_fan_mode(data, channel, &channels);
	if (ret)
		return ret;
	if (channels) {
		ret = regmap_update_bits(data->regmap, MAX6615_REG_FAN_CONFIG,
					 MAX6615_FAN_CONFIG_AUTO_MASK(channel),
					 max6615_channels_to_fan_config(val, channel));
		if (ret)
			return ret;
	}
	data->auto_channels[channel] = val;
	return 0;
}

static int max6615_read(struct device *dev, enum hwmon_sensor_types type,
			u32 attr, int channel, long *val)
{
	struct max6615_data *data = dev_get_drvdata(dev);
	int ret;

	mutex_lock(&data->lock);
	switch (type) {
	case hwmon_temp:
		ret = max6615_read_temp_attr(data, attr, channel, val);
		break;
	case hwmon_fan:
		ret = max6615_read_fan_attr(data, attr, channel, val);
		break;
	case hwmon_pwm:
		ret = max6615_read_pwm_attr(data, attr, channel, val);
		break;
	default:
		ret = -EOPNOTSUPP;
		break;
	}
	mutex_unlock(&data->lock);
	return ret;
}

static int max6615_write_temp_attr(struct max6615_data *data, u32 attr,
				   int channel, long val)
{
	switch (attr) {
	case hwmon_temp_crit:
		return max6615_write_degrees(data, MAX6615_REG_OT_LIMIT(channel), val);
	case hwmon_temp_offset:
		return max6615_write_offset(data, channel, val);
	default:
		return -EOPNOTSUPP;
	}
}

static int max6615_write_fan_attr(struct max6615_data *data, u32 attr,
				  int channel, long val)
{
	unsigned int disable = MAX6615_FAN_STATUS_TACH_DISABLE(channel);
	unsigned int status;
	int ret;

	switch (attr) {
	case hwmon_fan_min:
		return max6615_write_fan_min(data, channel, val);
	case hwmon_fan_enable:
		if (val != 0 && val != 1)
			return -EINVAL;
		/*
		 * FAN_STATUS mixes status and settings: read-modify-write,
		 * with the read latching the fail bits like any other.
		 */
		ret = max6615_read_status(data, MAX6615_REG_FAN_STATUS, &status);
		if (ret)
			return ret;
		status = (status & ~disable) | (val ? 0 : disable);
		return regmap_write(data->regmap, MAX6615_REG_FAN_STATUS, status);
	default:
		return -EOPNOTSUPP;
	}
}

static int max6615_write_pwm_attr(struct max6615_data *data, u32 attr,
				  int channel, long val)
{
	switch (attr) {
	case hwmon_pwm_input:
		return max6615_write_pwm_input(data, channel, val);
	case hwmon_pwm_enable:
		return max6615_write_pwm_enable(data, channel, val);
	case hwmon_pwm_auto_channels_temp:
		return max6615_write_auto_channels(data, channel, val);
	case hwmon_pwm_freq:
		return max6615_write_pwm_freq(data, val);
	default:
		return -EOPNOTSUPP;
	}
}

static int max6615_write(struct device *dev, enum hwmon_sensor_types type,
			 u32 attr, int channel, long val)
{
	struct max6615_data *data = dev_get_drvdata(dev);
	int ret;

	mutex_lock(&data->lock);
	switch (type) {
	case hwmon_temp:
		ret = max6615_write_temp_attr(data, attr, channel, val);
		break;
	case hwmon_fan:
		ret = max6615_write_fan_attr(data, attr, channel, val);
		break;
	case hwmon_pwm:
		ret = max6615_write_pwm_attr(data, attr, channel, val);
		break;
	default:
		ret = -EOPNOTSUPP;
		break;
	}
	mutex_unlock(&data->lock);
	return ret;
}

static umode_t max6615_is_visible(const void *drvdata,
				  enum hwmon_sensor_types type, u32 attr,
				  int channel)
{
	switch (type) {
	case hwmon_temp:
		switch (attr) {
		case hwmon_temp_crit:
		case hwmon_temp_offset:
			return 0644;
		default:
			return 0444;
		}
	case hwmon_fan:
		switch (attr) {
		case hwmon_fan_min:
		case hwmon_fan_enable:
			return 0644;
		default:
			return 0444;
		}
	case hwmon_pwm:
		return 0644;
	default:
		return 0;
	}
}

static const struct hwmon_channel_info *max6615_info[] = {
	HWMON_CHANNEL_INFO(temp,
			   HWMON_T_INPUT | HWMON_T_CRIT | HWMON_T_CRIT_ALARM |
			   HWMON_T_OFFSET | HWMON_T_TYPE,
			   HWMON_T_INPUT | HWMON_T_CRIT | HWMON_T_CRIT_ALARM |
			   HWMON_T_OFFSET | HWMON_T_TYPE),
	HWMON_CHANNEL_INFO(fan,
			   HWMON_F_INPUT | HWMON_F_MIN | HWMON_F_FAULT |
			   HWMON_F_ENABLE,
			   HWMON_F_INPUT | HWMON_F_MIN | HWMON_F_FAULT |
			   HWMON_F_ENABLE),
	HWMON_CHANNEL_INFO(pwm,
			   HWMON_PWM_INPUT | HWMON_PWM_ENABLE |
			   HWMON_PWM_AUTO_CHANNELS_TEMP | HWMON_PWM_FREQ,
			   HWMON_PWM_INPUT | HWMON_PWM_ENABLE |
			   HWMON_PWM_AUTO_CHANNELS_TEMP | HWMON_PWM_FREQ),
	NULL
};

static const struct hwmon_ops max6615_hwmon_ops = {
	.is_visible = max6615_is_visible,
	.read = max6615_read,
	.write = max6615_write,
};

static const struct hwmon_chip_info max6615_chip_info = {
	.ops = &max6615_hwmon_ops,
	.info = max6615_info,
};

/*
 * Automatic-mode curve points, which the 6.1 hwmon core has no channel
 * attributes for: pwmN_auto_point1_pwm (start duty), pwmN_auto_point2_pwm
 * (max duty) and tempN_auto_point1_temp (fan-start temperature). The
 * sensor attribute index is the register.
 */
static ssize_t auto_point_pwm_show(struct device *dev,
				   struct device_attribute *devattr, char *buf)
{
	struct max6615_data *data = dev_get_drvdata(dev);
	unsigned int reg = to_sensor_dev_attr(devattr)->index;
	long val;
	int ret;

	mutex_lock(&data->lock);
	ret = max6615_read_duty(data, reg, &val);
	mutex_unlock(&data->lock);
	if (ret)
		return ret;
	return sysfs_emit(buf, "%ld\n", val);
}

static ssize_t auto_point_pwm_store(struct device *dev,
				    struct device_attribute *devattr,
				    const char *buf, size_t count)
{
	struct max6615_data *data = dev_get_drvdata(dev);
	unsigned int reg = to_sensor_dev_attr(devattr)->index;
	long val;
	int ret;

	ret = kstrtol(buf, 10, &val);
	if (ret)
		return ret;
	mutex_lock(&data->lock);
	ret = max6615_write_duty(data, reg, val);
	mutex_unlock(&data->lock);
	if (ret)
		return ret;
	return count;
}

static ssize_t auto_point_temp_show(struct device *dev,
				    struct device_attribute *devattr, char *buf)
{
	struct max6615_data *data = dev_get_drvdata(dev);
	unsigned int reg = to_sensor_dev_attr(devattr)->index;
	long val;
	int ret;

	mutex_lock(&data->lock);
	ret = max6615_read_degrees(data, reg, &val);
	mutex_unlock(&data->lock);
	if (ret)
		return ret;
	return sysfs_emit(buf, "%ld\n", val);
}

static ssize_t auto_point_temp_store(struct device *dev,
				     struct device_attribute *devattr,
				     const char *buf, size_t count)
{
	struct max6615_data *data = dev_get_drvdata(dev);
	unsigned int reg = to_sensor_dev_attr(devattr)->index;
	long val;
	int ret;

	ret = kstrtol(buf, 10, &val);
	if (ret)
		return ret;
	mutex_lock(&data->lock);
	ret = max6615_write_degrees(data, reg, val);
	mutex_unlock(&data->lock);
	if (ret)
		return ret;
	return count;
}

static SENSOR_DEVICE_ATTR_RW(pwm1_auto_point1_pwm, auto_point_pwm,
			     MAX6615_REG_START_DUTY(0));
static SENSOR_DEVICE_ATTR_RW(pwm2_auto_point1_pwm, auto_point_pwm,
			     MAX6615_REG_START_DUTY(1));
static SENSOR_DEVICE_ATTR_RW(pwm1_auto_point2_pwm, auto_point_pwm,
			     MAX6615_REG_MAX_DUTY(0));
static SENSOR_DEVICE_ATTR_RW(pwm2_auto_point2_pwm, auto_point_pwm,
			     MAX6615_REG_MAX_DUTY(1));
static SENSOR_DEVICE_ATTR_RW(temp1_auto_point1_temp, auto_point_temp,
			     MAX6615_REG_FAN_START_TEMP(0));
static SENSOR_DEVICE_ATTR_RW(temp2_auto_point1_temp, auto_point_temp,
			     MAX6615_REG_FAN_START_TEMP(1));

static struct attribute *max6615_auto_point_attrs[] = {
	&sensor_dev_attr_pwm1_auto_point1_pwm.dev_attr.attr,
	&sensor_dev_attr_pwm2_auto_point1_pwm.dev_attr.attr,
	&sensor_dev_attr_pwm1_auto_point2_pwm.dev_attr.attr,
	&sensor_dev_attr_pwm2_auto_point2_pwm.dev_attr.attr,
	&sensor_dev_attr_temp1_auto_point1_temp.dev_attr.attr,
	&sensor_dev_attr_temp2_auto_point1_temp.dev_attr.attr,
	NULL
};
ATTRIBUTE_GROUPS(max6615_auto_point);

/* Reads all three ID registers without writing anything. */
static int max6615_identify(struct i2c_client *client)
{
	static const struct {
		u8 reg;
		u8 value;
	} ids[] = {
		{ MAX6615_REG_MANUFACTURER_ID, MAX6615_MANUFACTURER_ID },
		{ MAX6615_REG_DEVICE_ID, MAX6615_DEVICE_ID },
		{ MAX6615_REG_REVISION, MAX6615_REVISION },
	};
	unsigned int i;
	int ret;

	for (i = 0; i < ARRAY_SIZE(ids); i++) {
		ret = i2c_smbus_read_byte_data(client, ids[i].reg);
		if (ret < 0)
			return ret;
		if (ret != ids[i].value)
			return -ENODEV;
	}
	return 0;
}

/* Silent by design: called for every address of every HWMON-class bus. */
static int max6615_detect(struct i2c_client *client,
			  struct i2c_board_info *info)
{
	if (!i2c_check_functionality(client->adapter,
				     I2C_FUNC_SMBUS_BYTE_DATA))
		return -ENODEV;
	if (max6615_identify(client))
		return -ENODEV;
	/* The MAX6616 has the same IDs: it must be declared explicitly. */
	strscpy(info->type, "max6615", I2C_NAME_SIZE);
	return 0;
}

static int max6615_probe(struct i2c_client *client)
{
	struct device *dev = &client->dev;
	struct max6615_data *data;
	struct device *hwmon_dev;
	unsigned int config, channels;
	int ret, ch;

	if (!i2c_check_functionality(client->adapter, I2C_FUNC_SMBUS_BYTE_DATA))
		return dev_err_probe(dev, -ENODEV,
				     "adapter lacks SMBus byte-data transfers\n");

	ret = max6615_identify(client);
	if (ret == -ENODEV)
		return dev_err_probe(dev, ret, "no MAX6615/MAX6616 at this address\n");
	if (ret)
		return dev_err_probe(dev, ret, "reading the chip ID failed\n");

	data = devm_kzalloc(dev, sizeof(*data), GFP_KERNEL);
	if (!data)
		return -ENOMEM;
	mutex_init(&data->lock);

	data->regmap = devm_regmap_init_i2c(client, &max6615_regmap_config);
	if (IS_ERR(data->regmap))
		return dev_err_probe(dev, PTR_ERR(data->regmap),
				     "regmap initialisation failed\n");

	/* Keep what the board configured: read the settings, write nothing. */
	ret = regmap_read(data->regmap, MAX6615_REG_CONFIG, &config);
	if (ret)
		return ret;
	if (config & MAX6615_CONFIG_STANDBY)
		dev_info(dev, "chip is in standby: readings do not update\n");

	for (ch = 0; ch < MAX6615_CHANNELS; ch++) {
		/* A fan found in manual mode would follow its own channel. */
		data->auto_channels[ch] = BIT(ch);
		ret = max6615_read_fan_mode(data, ch, &channels);
		if (ret)
			return ret;
	}

	hwmon_dev = devm_hwmon_device_register_with_info(dev, client->name, data,
							 &max6615_chip_info,
							 max6615_auto_point_groups);
	return PTR_ERR_OR_ZERO(hwmon_dev);
}

static const unsigned short max6615_addresses[] = {
	0x18, 0x19, 0x1a, 0x29, 0x2a, 0x2b, 0x4c, 0x4d, 0x4e, I2C_CLIENT_END
};

static const struct i2c_device_id max6615_id[] = {
	{ "max6615" },
	{ "max6616" },
	{ }
};
MODULE_DEVICE_TABLE(i2c, max6615_id);

static const struct of_device_id max6615_of_match[] = {
	{ .compatible = "maxim,max6615" },
	{ .compatible = "maxim,max6616" },
	{ }
};
MODULE_DEVICE_TABLE(of, max6615_of_match);

static struct i2c_driver max6615_driver = {
	.class = I2C_CLASS_HWMON,
	.driver = {
		.name = "max6615",
		.of_match_table = max6615_of_match,
	},
	.I2C_DRIVER_PROBE = max6615_probe,
	.id_table = max6615_id,
	.detect = max6615_detect,
	.address_list = max6615_addresses,
};
module_i2c_driver(max6615_driver);

MODULE_AUTHOR("Advee robot project");
MODULE_DESCRIPTION("Maxim MAX6615/MAX6616 temperature monitor and fan controller");
MODULE_LICENSE("GPL");
