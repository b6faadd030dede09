/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Interface of the kernel's SJA1000 core module (sja1000.ko) as far as a bus
 * glue needs it.
 *
 * The kernel keeps this interface in drivers/net/can/sja1000/sja1000.h, which
 * no linux-headers package ships, so an out-of-tree glue has to declare it.
 * The layout of struct sja1000_priv below must match that header of the
 * kernel the module is built for; it is the same from 5.x through 6.1 (the
 * Debian 12 kernels: amd64, armmp, marvell). A later kernel that changes the
 * struct needs this file updated (docs/ts7800.md, "Gaps").
 */
#ifndef TS_CAN1_SJA1000_CORE_H
#define TS_CAN1_SJA1000_CORE_H

#include <linux/can/dev.h>
#include <linux/can/platform/sja1000.h>
#include <linux/interrupt.h>
#include <linux/netdevice.h>
#include <linux/spinlock.h>

/* SJA1000 PeliCAN mode register; reads 0xff where no chip answers. */
#define TS_CAN1_SJA1000_MOD		0x00
#define TS_CAN1_SJA1000_ABSENT		0xff

struct sja1000_priv {
	struct can_priv can;	/* first member: the CAN core casts to it */
	struct sk_buff *echo_skb;

	/* the bus glue does its own locking */
	u8 (*read_reg)(const struct sja1000_priv *priv, int reg);
	void (*write_reg)(const struct sja1000_priv *priv, int reg, u8 val);
	void (*pre_irq)(const struct sja1000_priv *priv);
	void (*post_irq)(const struct sja1000_priv *priv);

	void *priv;		/* bus glue data, after this struct */
	struct net_device *dev;

	void __iomem *reg_base;	/* only read as "probe the chip" flag */
	unsigned long irq_flags;
	spinlock_t cmdreg_lock;	/* the core serialises CMR writes with it */

	u16 flags;
	u8 ocr;
	u8 cdr;
};

struct net_device *alloc_sja1000dev(int sizeof_priv);
void free_sja1000dev(struct net_device *dev);
int register_sja1000dev(struct net_device *dev);
void unregister_sja1000dev(struct net_device *dev);
irqreturn_t sja1000_interrupt(int irq, void *dev_id);

#endif /* TS_CAN1_SJA1000_CORE_H */
