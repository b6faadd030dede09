// SPDX-License-Identifier: GPL-2.0
/*
 * Simulated TS-7800 PC/104 bus with a TS-CAN1 card on it (test only, never
 * loaded on the robot).
 *
 * Registers a parent device that looks to the ts-can1 driver like the
 * TS-7800 board glue: the FPGA's PC/104 pin function registers as the
 * parent's "fpga" regmap, the 8-bit PC/104 I/O window as its "pc104-io"
 * regmap, and PC/104 IRQ5/6/7 as the named interrupts of a "ts-can1" child.
 * Behind the window sit the card's PLD (include/linux/ts-can1.h) and a
 * register model of its SJA1000 in PeliCAN mode: reset/operating mode, the
 * configuration registers, the TX buffer, a receive FIFO, self reception and
 * the interrupt register. The bus is ideal: every transmitted frame is
 * acknowledged at once by a (virtual) second node; acceptance filtering, bus
 * errors and bit timing on the wire are not modelled.
 *
 * Everything the driver wrote that a user cannot see through SocketCAN is in
 * debugfs (ts-can1-sim/state), so tests can check the programming of the card;
 * ts-can1-sim/inject delivers frames from the second node.
 */
#include <linux/bitfield.h>
#include <linux/debugfs.h>
#include <linux/fs.h>
#include <linux/kernel.h>
#include <linux/irq.h>
#include <linux/irq_work.h>
#include <linux/irqdomain.h>
#include <linux/module.h>
#include <linux/platform_device.h>
#include <linux/regmap.h>
#include <linux/seq_file.h>
#include <linux/spinlock.h>
#include <linux/string.h>
#include <linux/ts-can1.h>
#include <linux/ts7800-fpga.h>
#include <linux/uaccess.h>

#define SIM_DRV_NAME		"ts-can1-sim"
#define SIM_FIRST_LINE		5
#define SIM_NR_LINES		3
#define SIM_PLD_VERSION		3	/* MODEL: any version; the driver only reports it */

/* SJA1000 PeliCAN registers (NXP SJA1000 data sheet, PeliCAN mode). */
#define SJA_MOD			0x00
#define SJA_CMR			0x01
#define SJA_SR			0x02
#define SJA_IR			0x03
#define SJA_IER			0x04
#define SJA_BTR0		0x06
#define SJA_BTR1		0x07
#define SJA_OCR			0x08
#define SJA_ALC			0x0b
#define SJA_ECC			0x0c
#define SJA_EWL			0x0d
#define SJA_RXERR		0x0e
#define SJA_TXERR		0x0f
#define SJA_FRAME		0x10	/* TX/RX buffer, or ACR0..3/AMR0..3 in reset */
#define SJA_FRAME_LEN		13
#define SJA_RMC			0x1d
#define SJA_CDR			0x1f

#define SJA_MOD_RM		BIT(0)
#define SJA_MOD_LOM		BIT(1)
#define SJA_MOD_STM		BIT(2)
#define SJA_MOD_MASK		GENMASK(4, 0)
#define SJA_CMR_TR		BIT(0)
#define SJA_CMR_AT		BIT(1)
#define SJA_CMR_RRB		BIT(2)
#define SJA_CMR_CDO		BIT(3)
#define SJA_CMR_SRR		BIT(4)
#define SJA_SR_RBS		BIT(0)
#define SJA_SR_DOS		BIT(1)
#define SJA_SR_TBS		BIT(2)
#define SJA_SR_TCS		BIT(3)
#define SJA_IR_RI		BIT(0)
#define SJA_IR_TI		BIT(1)
#define SJA_IR_DOI		BIT(3)
#define SJA_FI_FF		BIT(7)
#define SJA_FI_RTR		BIT(6)
#define SJA_FI_DLC		GENMASK(3, 0)

/* The chip's 64-byte RX FIFO holds at least four extended data frames. */
#define SIM_RX_FRAMES		4

static unsigned int sim_card_id;
module_param_named(card_id, sim_card_id, uint, 0444);
MODULE_PARM_DESC(card_id, "Card id 0..3 (JP1/JP2): PLD at 0x150 + 8 * id (default 0)");

static bool sim_present = true;
module_param_named(present, sim_present, bool, 0444);
MODULE_PARM_DESC(present, "A card is plugged in (default 1); without it the bus reads 0xff");

static ushort sim_id1 = TS_CAN1_ID1_VALUE;
module_param_named(id1, sim_id1, ushort, 0444);
MODULE_PARM_DESC(id1, "First PLD ID byte (default 0xf6)");

static ushort sim_id2 = TS_CAN1_ID2_VALUE;
module_param_named(id2, sim_id2, ushort, 0444);
MODULE_PARM_DESC(id2, "Second PLD ID byte (default 0xb9)");

static ushort sim_jumpers = TS_CAN1_JP4;
module_param_named(jumpers, sim_jumpers, ushort, 0444);
MODULE_PARM_DESC(jumpers, "PLD jumper register: 0x10 JP4 (IRQ6, default), 0x20 JP5 (IRQ7), 0x30 both (IRQ5), 0 none");

static bool sim_sja_absent;
module_param_named(sja_absent, sim_sja_absent, bool, 0444);
MODULE_PARM_DESC(sja_absent, "The SJA1000 does not answer in any window (default 0)");

struct sim_frame {
	u8 b[SJA_FRAME_LEN];	/* FI, identifier, data as in the buffer */
};

struct sim_sja {
	u8 mod, ier, ir, btr0, btr1, ocr, cdr, ewl, rxerr, txerr;
	bool dos;
	u8 accept[8];			/* ACR0..3, AMR0..3 */
	u8 tx[SJA_FRAME_LEN];		/* TX buffer as written */
	struct sim_frame rx[SIM_RX_FRAMES];
	unsigned int rx_head, rx_count;
	u32 tx_frames, rx_frames, self_rx, overruns;
};

struct ts_can1_sim {
	struct device *dev;
	spinlock_t lock;		/* the card, the pin rows and the line */
	u32 rows[2];			/* FPGA PC/104 pin function, rows A/B */
	u8 led, page, mode;		/* PLD registers as written */
	struct sim_sja sja;
	unsigned int line;		/* jumpered PC/104 line, 0 = none */
	bool level;			/* the card's interrupt output */

	raw_spinlock_t irq_lock;	/* irq_enable, irq_level */
	u32 irq_enable, irq_level;	/* per line, bit = line number */
	struct irq_work irq_work;
	struct irq_domain *domain;
	struct fwnode_handle *fwnode;
	struct dentry *debugfs;
};

static const u16 sim_windows[TS_CAN1_NR_WINDOWS] = TS_CAN1_WINDOW_BASES;

/* ---- interrupt lines ---------------------------------------------------- */

static void sim_irq_work(struct irq_work *work)
{
	struct ts_can1_sim *sim = container_of(work, struct ts_can1_sim, irq_work);
	unsigned long pending, flags;
	unsigned int line;

	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	pending = sim->irq_level & sim->irq_enable;
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
	for_each_set_bit(line, &pending, BITS_PER_LONG)
		generic_handle_domain_irq(sim->domain, line);
}

/* The card's output drives its jumpered line (sim->lock held). */
static void sim_update_line(struct ts_can1_sim *sim)
{
	struct sim_sja *s = &sim->sja;
	bool level = sim->line && (s->ir & s->ier);
	unsigned long flags;

	if (level == sim->level)
		return;
	sim->level = level;
	/*
	 * irqsave: under PREEMPT_RT sim->lock leaves interrupts on, and the
	 * hard irq_work queued here would interrupt us on this CPU and spin on
	 * irq_lock (a hung guest in tscan1/lifecycle on 6.12-rt).
	 */
	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	if (level)
		sim->irq_level |= BIT(sim->line);
	else
		sim->irq_level &= ~BIT(sim->line);
	if (level && (sim->irq_enable & BIT(sim->line)))
		irq_work_queue(&sim->irq_work);
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
}

static void sim_irq_mask(struct irq_data *d)
{
	struct ts_can1_sim *sim = irq_data_get_irq_chip_data(d);
	unsigned long flags;

	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	sim->irq_enable &= ~BIT(irqd_to_hwirq(d));
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
}

static void sim_irq_unmask(struct irq_data *d)
{
	struct ts_can1_sim *sim = irq_data_get_irq_chip_data(d);
	u32 bit = BIT(irqd_to_hwirq(d));
	unsigned long flags;

	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	sim->irq_enable |= bit;
	/* A level interrupt still asserted fires again. */
	if (sim->irq_level & bit)
		irq_work_queue(&sim->irq_work);
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
}

static struct irq_chip sim_irq_chip = {
	.name		= SIM_DRV_NAME,
	.irq_mask	= sim_irq_mask,
	.irq_unmask	= sim_irq_unmask,
};

static int sim_irq_map(struct irq_domain *d, unsigned int virq, irq_hw_number_t hwirq)
{
	irq_set_chip_data(virq, d->host_data);
	irq_set_chip_and_handler(virq, &sim_irq_chip, handle_level_irq);
	irq_set_noprobe(virq);
	return 0;
}

static const struct irq_domain_ops sim_irq_domain_ops = {
	.map	= sim_irq_map,
	.xlate	= irq_domain_xlate_onecell,
};

/* ---- SJA1000 ------------------------------------------------------------ */

static void sim_sja_reset(struct sim_sja *s)
{
	s->mod = SJA_MOD_RM;
	s->ier = 0;
	s->ir = 0;
	s->dos = false;
	s->rx_head = 0;
	s->rx_count = 0;
	s->txerr = 0;
	s->rxerr = 0;
	s->ewl = 96;
}

/* An interrupt flag is set only while its enable is (PeliCAN rule). */
static void sim_sja_flag(struct sim_sja *s, u8 bit)
{
	if (s->ier & bit)
		s->ir |= bit;
}

static void sim_sja_receive(struct sim_sja *s, const u8 *frame)
{
	if (s->rx_count == SIM_RX_FRAMES) {
		s->overruns++;
		s->dos = true;
		sim_sja_flag(s, SJA_IR_DOI);
		return;
	}
	memcpy(s->rx[(s->rx_head + s->rx_count) % SIM_RX_FRAMES].b, frame,
	       SJA_FRAME_LEN);
	s->rx_count++;
	s->rx_frames++;
	sim_sja_flag(s, SJA_IR_RI);
}

/*
 * A transmission request: the frame goes out and the virtual second node
 * acknowledges it at once; with self reception the chip also receives it.
 * Listen-only mode sends nothing.
 */
static void sim_sja_transmit(struct sim_sja *s, bool self)
{
	if (s->mod & (SJA_MOD_RM | SJA_MOD_LOM))
		return;
	s->tx_frames++;
	if (self) {
		s->self_rx++;
		sim_sja_receive(s, s->tx);
	}
	sim_sja_flag(s, SJA_IR_TI);
}

static void sim_sja_command(struct sim_sja *s, u8 cmd)
{
	if (cmd & SJA_CMR_RRB && s->rx_count) {
		s->rx_head = (s->rx_head + 1) % SIM_RX_FRAMES;
		s->rx_count--;
	}
	if (cmd & SJA_CMR_CDO)
		s->dos = false;
	if (cmd & (SJA_CMR_TR | SJA_CMR_SRR))
		sim_sja_transmit(s, cmd & SJA_CMR_SRR);
	/* RI follows the FIFO: set while a frame waits. */
	if (s->rx_count)
		sim_sja_flag(s, SJA_IR_RI);
	else
		s->ir &= ~SJA_IR_RI;
}

static u8 sim_sja_read(struct sim_sja *s, unsigned int reg)
{
	bool reset = s->mod & SJA_MOD_RM;
	u8 val;

	switch (reg) {
	case SJA_MOD:
		return s->mod;
	case SJA_CMR:
		return 0xff;	/* write-only */
	case SJA_SR:
		return (s->rx_count ? SJA_SR_RBS : 0) | (s->dos ? SJA_SR_DOS : 0) |
		       SJA_SR_TBS | SJA_SR_TCS;
	case SJA_IR:
		/* Reading clears every flag but RI, which follows the FIFO. */
		val = s->ir;
		s->ir &= SJA_IR_RI;
		return val;
	case SJA_IER:
		return s->ier;
	case SJA_BTR0:
		return s->btr0;
	case SJA_BTR1:
		return s->btr1;
	case SJA_OCR:
		return s->ocr;
	case SJA_ALC:
	case SJA_ECC:
		return 0;
	case SJA_EWL:
		return s->ewl;
	case SJA_RXERR:
		return s->rxerr;
	case SJA_TXERR:
		return s->txerr;
	case SJA_FRAME ... SJA_FRAME + SJA_FRAME_LEN - 1:
		if (reset)
			return reg < SJA_FRAME + 8 ? s->accept[reg - SJA_FRAME] : 0;
		return s->rx_count ? s->rx[s->rx_head].b[reg - SJA_FRAME] : 0;
	case SJA_RMC:
		return s->rx_count;
	case SJA_CDR:
		return s->cdr;
	default:
		return 0;
	}
}

static void sim_sja_write(struct sim_sja *s, unsigned int reg, u8 val)
{
	bool reset = s->mod & SJA_MOD_RM;

	switch (reg) {
	case SJA_MOD:
		if (val & SJA_MOD_RM) {
			sim_sja_reset(s);
			s->mod = val & SJA_MOD_MASK;
		} else {
			s->mod = val & SJA_MOD_MASK;
		}
		break;
	case SJA_CMR:
		sim_sja_command(s, val);
		break;
	case SJA_IER:
		s->ier = val;
		s->ir &= val;
		if (s->rx_count)
			sim_sja_flag(s, SJA_IR_RI);
		break;
	/* Configuration registers take writes only in reset mode. */
	case SJA_BTR0:
		if (reset)
			s->btr0 = val;
		break;
	case SJA_BTR1:
		if (reset)
			s->btr1 = val;
		break;
	case SJA_OCR:
		if (reset)
			s->ocr = val;
		break;
	case SJA_EWL:
		if (reset)
			s->ewl = val;
		break;
	case SJA_RXERR:
		if (reset)
			s->rxerr = val;
		break;
	case SJA_TXERR:
		if (reset)
			s->txerr = val;
		break;
	case SJA_FRAME ... SJA_FRAME + SJA_FRAME_LEN - 1:
		if (reset && reg < SJA_FRAME + 8)
			s->accept[reg - SJA_FRAME] = val;
		else if (!reset)
			s->tx[reg - SJA_FRAME] = val;
		break;
	case SJA_CDR:
		s->cdr = val;
		break;
	default:
		break;
	}
}

/* ---- PC/104 bus --------------------------------------------------------- */

/* The card decodes nothing until the FPGA drives rows A/B as the bus. */
static bool sim_bus_on(struct ts_can1_sim *sim)
{
	return sim->rows[0] == 0x55555555 && sim->rows[1] == 0x55555555;
}

/* SJA1000 register of an ISA port, or -1 if the window does not decode it. */
static int sim_sja_reg(struct ts_can1_sim *sim, unsigned int port)
{
	unsigned int base;

	if (!(sim->mode & TS_CAN1_MODE_ENABLE) || sim_sja_absent)
		return -1;
	base = sim_windows[FIELD_GET(TS_CAN1_MODE_WINDOW, sim->mode)];
	if (port < base || port >= base + TS_CAN1_SJA1000_SIZE)
		return -1;
	return port - base;
}

static int sim_io_read(void *context, unsigned int port, unsigned int *val)
{
	struct ts_can1_sim *sim = context;
	unsigned int pld = TS_CAN1_PLD_BASE(sim_card_id);
	unsigned long flags;
	int reg;

	*val = 0xff;	/* an undriven bus */
	spin_lock_irqsave(&sim->lock, flags);
	if (!sim_present || !sim_bus_on(sim))
		goto out;
	if (port >= pld && port < pld + TS_CAN1_PLD_SIZE) {
		switch (port - pld) {
		case TS_CAN1_PLD_ID1:
			*val = sim_id1;
			break;
		case TS_CAN1_PLD_ID2:
			*val = sim_id2;
			break;
		case TS_CAN1_PLD_VERSION:
			*val = SIM_PLD_VERSION;
			break;
		case TS_CAN1_PLD_LED:
			*val = sim->led;
			break;
		case TS_CAN1_PLD_PAGE:
			*val = sim->page;
			break;
		case TS_CAN1_PLD_MODE:
			*val = sim->mode;
			break;
		case TS_CAN1_PLD_JUMPERS:
			*val = sim_jumpers;
			break;
		}
		goto out;
	}
	reg = sim_sja_reg(sim, port);
	if (reg >= 0) {
		*val = sim_sja_read(&sim->sja, reg);
		sim_update_line(sim);
	}
out:
	spin_unlock_irqrestore(&sim->lock, flags);
	return 0;
}

static int sim_io_write(void *context, unsigned int port, unsigned int val)
{
	struct ts_can1_sim *sim = context;
	unsigned int pld = TS_CAN1_PLD_BASE(sim_card_id);
	unsigned long flags;
	int reg;

	spin_lock_irqsave(&sim->lock, flags);
	if (!sim_present || !sim_bus_on(sim))
		goto out;
	if (port >= pld && port < pld + TS_CAN1_PLD_SIZE) {
		switch (port - pld) {
		case TS_CAN1_PLD_LED:
			sim->led = val;
			break;
		case TS_CAN1_PLD_PAGE:
			sim->page = val;
			break;
		case TS_CAN1_PLD_MODE:
			sim->mode = val;
			break;
		}
		goto out;
	}
	reg = sim_sja_reg(sim, port);
	if (reg >= 0) {
		sim_sja_write(&sim->sja, reg, val);
		sim_update_line(sim);
	}
out:
	spin_unlock_irqrestore(&sim->lock, flags);
	return 0;
}

/* FPGA window: only the PC/104 pin function of rows A and B is modelled. */
static int sim_fpga_read(void *context, unsigned int reg, unsigned int *val)
{
	struct ts_can1_sim *sim = context;
	unsigned int row = (reg - TS7800_FPGA_PC104_ROWA_LO) / 4;
	unsigned long flags;

	*val = 0;
	if (reg < TS7800_FPGA_PC104_ROWA_LO || reg > TS7800_FPGA_PC104_ROWB_LO + 2)
		return 0;
	spin_lock_irqsave(&sim->lock, flags);
	*val = (reg & 2) ? sim->rows[row] >> 16 : sim->rows[row] & 0xffff;
	spin_unlock_irqrestore(&sim->lock, flags);
	return 0;
}

static int sim_fpga_write(void *context, unsigned int reg, unsigned int val)
{
	struct ts_can1_sim *sim = context;
	unsigned int row = (reg - TS7800_FPGA_PC104_ROWA_LO) / 4;
	unsigned long flags;
	u32 *r;

	if (reg < TS7800_FPGA_PC104_ROWA_LO || reg > TS7800_FPGA_PC104_ROWB_LO + 2)
		return 0;	/* MODEL: other registers ignore writes */
	spin_lock_irqsave(&sim->lock, flags);
	r = &sim->rows[row];
	if (reg & 2)
		*r = (*r & 0xffff) | (val << 16);
	else
		*r = (*r & 0xffff0000) | (val & 0xffff);
	spin_unlock_irqrestore(&sim->lock, flags);
	return 0;
}

static const struct regmap_config sim_io_regmap_config = {
	.name		= TS_CAN1_IO_REGMAP,
	.reg_bits	= 32,
	.val_bits	= 8,
	.max_register	= TS_CAN1_IO_SIZE - 1,
	/* the bus rules of every PC/104 provider (include/linux/ts-can1.h) */
	.readable_reg	= ts_can1_io_readable,
	.writeable_reg	= ts_can1_io_readable,
	.precious_reg	= ts_can1_io_precious,
	.cache_type	= REGCACHE_NONE,
	.fast_io	= true,		/* used from the interrupt handler */
	.reg_read	= sim_io_read,
	.reg_write	= sim_io_write,
};

/* The modelled part of the FPGA window: the row A/B pin function registers. */
static bool sim_fpga_readable(struct device *dev, unsigned int reg)
{
	return reg >= TS7800_FPGA_PC104_ROWA_LO && reg <= TS7800_FPGA_PC104_ROWB_LO + 2;
}

static const struct regmap_config sim_fpga_regmap_config = {
	.name		= "fpga",
	.reg_bits	= 32,
	.val_bits	= 16,
	.reg_stride	= 2,
	.max_register	= 0xffe,
	.readable_reg	= sim_fpga_readable,
	.writeable_reg	= sim_fpga_readable,
	.cache_type	= REGCACHE_NONE,
	.fast_io	= true,
	.reg_read	= sim_fpga_read,
	.reg_write	= sim_fpga_write,
};

/* ---- debugfs ------------------------------------------------------------ */

static int sim_state_show(struct seq_file *m, void *unused)
{
	struct ts_can1_sim *sim = m->private;
	struct sim_sja *s = &sim->sja;
	unsigned long flags;

	spin_lock_irqsave(&sim->lock, flags);
	seq_printf(m, "rows 0x%08x 0x%08x\n", sim->rows[0], sim->rows[1]);
	seq_printf(m, "pld 0x%03x mode 0x%02x led 0x%02x page 0x%02x line %u\n",
		   TS_CAN1_PLD_BASE(sim_card_id), sim->mode, sim->led, sim->page,
		   sim->line);
	seq_printf(m, "sja mod 0x%02x ier 0x%02x btr0 0x%02x btr1 0x%02x ocr 0x%02x cdr 0x%02x\n",
		   s->mod, s->ier, s->btr0, s->btr1, s->ocr, s->cdr);
	seq_printf(m, "frames tx %u rx %u self %u pending %u overruns %u\n",
		   s->tx_frames, s->rx_frames, s->self_rx, s->rx_count, s->overruns);
	spin_unlock_irqrestore(&sim->lock, flags);
	return 0;
}
DEFINE_SHOW_ATTRIBUTE(sim_state);

/* The buffer layout of a frame: frame information, identifier, data. */
static void sim_frame_build(u8 *b, u32 id, const u8 *data, unsigned int len)
{
	unsigned int d;

	memset(b, 0, SJA_FRAME_LEN);
	if (id > 0x7ff) {
		b[0] = SJA_FI_FF | len;
		b[1] = id >> 21;
		b[2] = id >> 13;
		b[3] = id >> 5;
		b[4] = (id & 0x1f) << 3;
		d = 5;
	} else {
		b[0] = len;
		b[1] = id >> 3;
		b[2] = (id & 0x7) << 5;
		d = 3;
	}
	memcpy(b + d, data, len);
}

/*
 * Frames from the second node: "ID DATA [COUNT]" (hex identifier, extended
 * above 0x7ff; hex data bytes, "-" for none; COUNT copies arrive back to
 * back, before the CPU can read any, so more than the FIFO holds overrun).
 * -ENETDOWN while the chip is in reset mode: it receives nothing then.
 */
static ssize_t sim_inject_write(struct file *file, const char __user *ubuf,
				size_t count, loff_t *ppos)
{
	struct ts_can1_sim *sim = file->private_data;
	char buf[64], hex[17];
	u8 data[8], frame[SJA_FRAME_LEN];
	unsigned int n = 1, len, i;
	unsigned long flags;
	int fields, ret;
	u32 id;

	if (count >= sizeof(buf))
		return -EINVAL;
	if (copy_from_user(buf, ubuf, count))
		return -EFAULT;
	buf[count] = '\0';
	fields = sscanf(buf, "%x %16s %u", &id, hex, &n);
	if (fields < 2 || id > 0x1fffffff || !n || n > 64)
		return -EINVAL;
	len = strcmp(hex, "-") ? strlen(hex) / 2 : 0;
	if (len > sizeof(data) || (len && strlen(hex) % 2) ||
	    (len && hex2bin(data, hex, len)))
		return -EINVAL;
	sim_frame_build(frame, id, data, len);

	spin_lock_irqsave(&sim->lock, flags);
	if (sim->sja.mod & SJA_MOD_RM) {
		ret = -ENETDOWN;
	} else {
		for (i = 0; i < n; i++)
			sim_sja_receive(&sim->sja, frame);
		sim_update_line(sim);
		ret = count;
	}
	spin_unlock_irqrestore(&sim->lock, flags);
	return ret;
}

static const struct file_operations sim_inject_fops = {
	.owner	= THIS_MODULE,
	.open	= simple_open,
	.write	= sim_inject_write,
	.llseek	= noop_llseek,
};

/* ---- device ------------------------------------------------------------- */

/* Runs last: the bus device (and its interrupt mappings) are gone by then. */
static void sim_remove_domain(void *data)
{
	struct ts_can1_sim *sim = data;

	irq_work_sync(&sim->irq_work);
	irq_domain_remove(sim->domain);
	irq_domain_free_fwnode(sim->fwnode);
}

static void sim_remove_debugfs(void *data)
{
	struct ts_can1_sim *sim = data;

	debugfs_remove_recursive(sim->debugfs);
}

static int sim_probe(struct platform_device *pdev)
{
	struct device *dev = &pdev->dev;
	struct ts_can1_sim *sim;
	struct regmap *map;
	int ret;

	sim = devm_kzalloc(dev, sizeof(*sim), GFP_KERNEL);
	if (!sim)
		return -ENOMEM;
	sim->dev = dev;
	spin_lock_init(&sim->lock);
	raw_spin_lock_init(&sim->irq_lock);
	sim->irq_work = IRQ_WORK_INIT_HARD(sim_irq_work);
	sim->line = ts_can1_jumper_line(sim_jumpers);
	sim_sja_reset(&sim->sja);

	map = devm_regmap_init(dev, NULL, sim, &sim_io_regmap_config);
	if (IS_ERR(map))
		return PTR_ERR(map);
	map = devm_regmap_init(dev, NULL, sim, &sim_fpga_regmap_config);
	if (IS_ERR(map))
		return PTR_ERR(map);

	sim->fwnode = irq_domain_alloc_named_fwnode(SIM_DRV_NAME);
	if (!sim->fwnode)
		return -ENOMEM;
	sim->domain = irq_domain_create_linear(sim->fwnode, SIM_FIRST_LINE + SIM_NR_LINES,
					       &sim_irq_domain_ops, sim);
	if (!sim->domain) {
		irq_domain_free_fwnode(sim->fwnode);
		return -ENOMEM;
	}
	ret = devm_add_action_or_reset(dev, sim_remove_domain, sim);
	if (ret)
		return ret;
	/* The bus device, created exactly as the FPGA core creates it. */
	ret = ts7800_fpga_add_pc104(dev, sim->domain, NULL);
	if (ret)
		return ret;
	sim->debugfs = debugfs_create_dir(SIM_DRV_NAME, NULL);
	debugfs_create_file("state", 0444, sim->debugfs, sim, &sim_state_fops);
	debugfs_create_file("inject", 0200, sim->debugfs, sim, &sim_inject_fops);
	ret = devm_add_action_or_reset(dev, sim_remove_debugfs, sim);
	if (ret)
		return ret;

	dev_info(dev, "simulated PC/104 bus: %s at 0x%x, jumpers 0x%02x (IRQ%u)\n",
		 sim_present ? "TS-CAN1" : "no card", TS_CAN1_PLD_BASE(sim_card_id),
		 sim_jumpers, sim->line);
	return 0;
}

static struct platform_driver sim_driver = {
	.probe	= sim_probe,
	.driver	= {
		.name = SIM_DRV_NAME,
		/*
		 * Bind attributes kept: tscan1/unbind-bus unbinds the bus
		 * provider as an FPGA core unbind would; everything the probe
		 * sets up is devres.
		 */
	},
};

static struct platform_device *sim_pdev;

static int __init sim_init(void)
{
	int ret;

	if (sim_card_id >= TS_CAN1_MAX_CARDS || sim_id1 > 0xff || sim_id2 > 0xff ||
	    sim_jumpers > 0xff)
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

MODULE_DESCRIPTION("Simulated TS-7800 PC/104 bus with a TS-CAN1 (SJA1000) card (test only)");
MODULE_LICENSE("GPL");
MODULE_INFO(test, "Y");
