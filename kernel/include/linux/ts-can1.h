/* SPDX-License-Identifier: GPL-2.0 */
/*
 * TS-CAN1 PC/104 CAN card: register map of its PLD and the contract between
 * the ts-can1 driver (ts7800-can/) and whatever provides the PC/104 bus
 * below it (the TS-7800 board glue or the test-only simulator, tests/sim/).
 *
 * Addresses are ISA I/O port numbers. On the TS-7800 port A is the byte at
 * PC/104 8-bit I/O window + A (ts7800-notes 3.3). Facts and their confidence:
 * ../shared/specs/ts7800-notes.md section 4, docs/ts7800.md.
 */
#ifndef _LINUX_TS_CAN1_H
#define _LINUX_TS_CAN1_H

#include <linux/bits.h>
#include <linux/types.h>

struct device;

/* Platform device the driver binds to (one per PC/104 bus). */
#define TS_CAN1_DEV_NAME		"ts-can1"
/*
 * Register access: either the device's first memory resource is the PC/104
 * 8-bit I/O window (the driver maps it), or its parent owns a regmap of this
 * name with 8-bit values whose register number is the ISA port.
 */
#define TS_CAN1_IO_REGMAP		"pc104-io"
/* ISA ports 0..0x3ff: the size of the window the driver uses. */
#define TS_CAN1_IO_SIZE			0x400
/* Interrupts: one named resource per PC/104 line, "irq5", "irq6", "irq7". */
#define TS_CAN1_IRQ_NAME_FMT		"irq%u"

/* PLD: 8 byte registers at 0x150 + 8 * id, id 0..3 set by JP1/JP2. */
#define TS_CAN1_PLD_BASE(id)		(0x150 + 8 * (id))
#define TS_CAN1_PLD_SIZE		8
#define TS_CAN1_MAX_CARDS		4
#define TS_CAN1_PLD_ID1			0
#define TS_CAN1_PLD_ID2			1
#define TS_CAN1_PLD_VERSION		2
#define TS_CAN1_PLD_LED			3
#define TS_CAN1_PLD_PAGE		4
#define TS_CAN1_PLD_MODE		5
#define TS_CAN1_PLD_JUMPERS		6

#define TS_CAN1_ID1_VALUE		0xf6
#define TS_CAN1_ID2_VALUE		0xb9

/* MODE: SJA1000 window enable, and the index of its base (table below). */
#define TS_CAN1_MODE_ENABLE		BIT(6)
#define TS_CAN1_MODE_WINDOW		GENMASK(2, 0)

/* JUMPERS: JP4/JP5 select the PC/104 interrupt line. */
#define TS_CAN1_JP4			BIT(4)
#define TS_CAN1_JP5			BIT(5)

/*
 * The PC/104 interrupt line the jumpers select, 0 if none: one definition
 * for the driver and the simulated card.
 */
static inline unsigned int ts_can1_jumper_line(u8 jumpers)
{
	switch (jumpers & (TS_CAN1_JP4 | TS_CAN1_JP5)) {
	case TS_CAN1_JP4:
		return 6;
	case TS_CAN1_JP5:
		return 7;
	case TS_CAN1_JP4 | TS_CAN1_JP5:
		return 5;
	default:
		return 0;
	}
}

/* SJA1000 (PeliCAN) register window: 32 byte registers. */
#define TS_CAN1_SJA1000_SIZE		32
#define TS_CAN1_NR_WINDOWS		8
/* ISA base of the SJA1000 for MODE window index 0..7. */
#define TS_CAN1_WINDOW_BASES \
	{ 0x100, 0x120, 0x180, 0x1a0, 0x200, 0x240, 0x280, 0x320 }

/* SJA1000 (PeliCAN) registers that clear when read: IR, ALC, ECC. */
#define TS_CAN1_SJA1000_IR		3
#define TS_CAN1_SJA1000_ALC		11
#define TS_CAN1_SJA1000_ECC		12

/*
 * The SJA1000 window index of ISA port @port, or -1 (outside all eight);
 * @reg gets the register number inside the window.
 */
static inline int ts_can1_io_window(unsigned int port, unsigned int *reg)
{
	static const u16 bases[TS_CAN1_NR_WINDOWS] = TS_CAN1_WINDOW_BASES;
	int i;

	for (i = 0; i < TS_CAN1_NR_WINDOWS; i++) {
		if (port >= bases[i] && port < bases[i] + TS_CAN1_SJA1000_SIZE) {
			*reg = port - bases[i];
			return i;
		}
	}
	return -1;
}

/*
 * Regmap rules of the PC/104 I/O space (for every provider of the bus):
 * only the addresses a TS-CAN1 can decode are readable - the four PLD blocks
 * and the eight SJA1000 windows; every other port may be another card's.
 */
static inline bool ts_can1_io_readable(struct device *dev, unsigned int port)
{
	unsigned int reg;

	return (port >= TS_CAN1_PLD_BASE(0) &&
		port < TS_CAN1_PLD_BASE(TS_CAN1_MAX_CARDS)) ||
	       ts_can1_io_window(port, &reg) >= 0;
}

/* Reads with a side effect: a regmap debugfs dump must leave them alone. */
static inline bool ts_can1_io_precious(struct device *dev, unsigned int port)
{
	unsigned int reg;

	if (ts_can1_io_window(port, &reg) < 0)
		return false;
	return reg == TS_CAN1_SJA1000_IR || reg == TS_CAN1_SJA1000_ALC ||
	       reg == TS_CAN1_SJA1000_ECC;
}

/* 16 MHz crystal; the SJA1000 runs its CAN clock at half of it. */
#define TS_CAN1_XTAL_HZ			16000000

/*
 * TS-7800 FPGA: PC/104 pin function of rows A and B (ts7800-notes 3.3).
 * Two bits per pin pair, 01 = bus; an 8-bit card needs only these rows.
 * Offsets into the parent's 16-bit "fpga" regmap, low half first.
 */
#define TS7800_FPGA_PC104_ROWA_LO	0x030
#define TS7800_FPGA_PC104_ROWB_LO	0x034
#define TS7800_FPGA_PC104_FUNC_BUS	0x5555

#endif /* _LINUX_TS_CAN1_H */
