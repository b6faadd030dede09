/* SPDX-License-Identifier: GPL-2.0 */
/*
 * TS-7800 FPGA: register map shared by the FPGA core (tsuart-fix/), its child
 * drivers and the register-level simulator (tests/sim/).
 *
 * Offsets are relative to the FPGA window (0xE8000000 on the board). The
 * parent exposes the window as a regmap with 16-bit values and a stride of 2;
 * 32-bit registers appear as two halves, low half first (the board is
 * little-endian). Facts and their confidence: docs/tsuart.md and
 * ../shared/specs/ts7800-notes.md.
 */
#ifndef _LINUX_TS7800_FPGA_H
#define _LINUX_TS7800_FPGA_H

#include <linux/bits.h>
#include <linux/regmap.h>
#include <linux/types.h>

struct device;
struct irq_domain;
struct resource;

/* Name of the parent's regmap of the window (dev_get_regmap()). */
#define TS7800_FPGA_REGMAP_NAME		"fpga"

/* ID word at offset 0: bits 31..8 magic, bits 7..0 FPGA revision. */
#define TS7800_FPGA_ID_LO		0x000
#define TS7800_FPGA_ID_HI		0x002
#define TS7800_FPGA_ID_MAGIC		0x00b480
#define TS7800_FPGA_WINDOW_SIZE		0x1000

/* PC/104 pin function registers of rows A..D (0x30, 0x34, 0x38, 0x3C). */
#define TS7800_FPGA_PC104_FUNC_FIRST	0x030
#define TS7800_FPGA_PC104_FUNC_LAST	0x03e

/* PC/104 row C pin function register; bits 14..19 = pins C14..C19. */
#define TS7800_FPGA_PC104_ROWC_LO	0x038
#define TS7800_FPGA_PC104_ROWC_HI	0x03a
#define TS7800_FPGA_ROWC_UART89_PINS	GENMASK(19, 14)
#define TS7800_FPGA_ROWC_KEEP		GENMASK(13, 0)

/* FPGA interrupt (MSI) enable mask, bit k = FPGA source k. */
#define TS7800_FPGA_IRQ_MASK_LO		0x204
#define TS7800_FPGA_IRQ_MASK_HI		0x206
#define TS7800_FPGA_NR_IRQS		32
#define TS7800_FPGA_HWIRQ_UART(n)	(16 + (n))

/* Child platform device name of a TS-UART (id = port number). */
#define TS7800_UART_DEV_NAME		"ts7800-uart"

/* TS-UART port n: STAT at 0xC0 + 4n, DATA two bytes above. */
#define TS7800_UART_BASE(n)		(0x0c0 + 4 * (n))
#define TS7800_UART_REGS_SIZE		4
#define TS7800_UART_STAT		0
#define TS7800_UART_DATA		2
#define TS7800_UART_MAX_PORTS		10
#define TS7800_UART_ALWAYS_PORTS	8

/* Board-wide divisor table: slot c (baud code c) at 0xE8 + 2c. */
#define TS7800_UART_DIVISOR(code)	(0x0e8 + 2 * (code))
#define TS7800_UART_NR_CODES		7
#define TS7800_UART_CODE_OFF		7
/* One divisor unit is one period of the 12.5 MHz bit clock. */
#define TS7800_UART_BITCLK_HZ		12500000U
#define TS7800_UART_BITCLK_NS		80U

/* STAT bits: status (read-only, writes ignored) */
#define TS7800_STAT_TBRE		BIT(0)	/* DATA can take a character */
#define TS7800_STAT_DR			BIT(1)	/* received character ready */
#define TS7800_STAT_OERR		BIT(2)	/* receive overrun */
#define TS7800_STAT_CTS			BIT(3)	/* CTS input level */
#define TS7800_STAT_RXBRK		BIT(9)	/* break received */
#define TS7800_STAT_TRE			BIT(12)	/* transmitter completely idle */
/* STAT bits: control (read back what was written) */
#define TS7800_STAT_RTS			BIT(4)
#define TS7800_STAT_BAUD		GENMASK(7, 5)
#define TS7800_STAT_MODE9		BIT(8)
#define TS7800_STAT_TXBRK		BIT(10)
#define TS7800_STAT_DIV8		BIT(13)
#define TS7800_STAT_HWCTS		BIT(14)
#define TS7800_STAT_CTRL_MASK		(TS7800_STAT_RTS | TS7800_STAT_BAUD | \
					 TS7800_STAT_MODE9 | TS7800_STAT_TXBRK | \
					 TS7800_STAT_DIV8 | TS7800_STAT_HWCTS)

#define TS7800_DATA_MASK8		0x0ff
#define TS7800_DATA_MASK9		0x1ff

/*
 * DIO header (ts7800-notes 3.4): input levels at 0x04, output latch at 0x08,
 * bit n-1 = header pin n. An output bit of 0 pulls the pin low, 1 releases it
 * to its pull-up (thesis 7.2.1), so every pin is open-drain and reads back
 * through the input register. Pins 2 and 16 are power, 6/10/12/14 the SPI
 * lines (FRAME, MISO, MOSI, CLK): never handed out as GPIOs.
 */
#define TS7800_DIO_IN			0x004
#define TS7800_DIO_OUT			0x008
#define TS7800_DIO_NR_PINS		16
#define TS7800_DIO_BIT(pin)		BIT((pin) - 1)
#define TS7800_DIO_POWER_PINS		(TS7800_DIO_BIT(2) | TS7800_DIO_BIT(16))
#define TS7800_DIO_SPI_PINS		(TS7800_DIO_BIT(6) | TS7800_DIO_BIT(10) | \
					 TS7800_DIO_BIT(12) | TS7800_DIO_BIT(14))
#define TS7800_DIO_RESERVED		(TS7800_DIO_POWER_PINS | TS7800_DIO_SPI_PINS)
/* Child platform device name of the DIO header (one per FPGA). */
#define TS7800_DIO_DEV_NAME		"ts7800-dio"
/* Its child: the bit-banged I2C bus on two of its pins (BR-FAN1 board). */
#define TS7800_DIO_I2C_DEV_NAME		"ts7800-dio-i2c"

/* Nominal rate and the divisor the TS loader writes, per baud code. */
struct ts7800_uart_rate {
	unsigned int baud;
	u16 divisor;
};

extern const struct ts7800_uart_rate ts7800_uart_rates[TS7800_UART_NR_CODES];
extern const struct regmap_config ts7800_fpga_regmap_config;

int ts7800_fpga_identify(struct regmap *map, u8 *revision);
int ts7800_fpga_write_divisors(struct regmap *map);
int ts7800_fpga_add_uarts(struct device *parent, struct regmap *map,
			  struct irq_domain *domain);
int ts7800_fpga_add_dio(struct device *parent);
int ts7800_fpga_add_pc104(struct device *parent, struct irq_domain *domain,
			  const struct resource *io);

#endif /* _LINUX_TS7800_FPGA_H */
