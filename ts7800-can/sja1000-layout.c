// SPDX-License-Identifier: GPL-2.0
/*
 * Build-time check that ts-can1's copy of struct sja1000_priv
 * (sja1000-core.h) has exactly the layout of the kernel's own, in
 * drivers/net/can/sja1000/sja1000.h of the kernel being built for. The SJA1000
 * core writes the members through its own definition, so any difference
 * would be silent memory corruption: here it fails the build instead.
 *
 * ts7800-can/Kbuild compiles this file with SJA1000_KERNEL_HEADER naming that
 * header: the kernel's own tree when it has one (the debug kernel), else
 * Debian's linux-source-6.1 extracted for the gates (scripts/build-kmod.sh
 * passes it). It generates no code.
 */
#include <linux/build_bug.h>
#include <linux/stddef.h>

/* Our copy, under another name so that both definitions can be compared. */
#define sja1000_priv ts_can1_sja1000_priv_copy
#include "sja1000-core.h"
#undef sja1000_priv

#include SJA1000_KERNEL_HEADER

/* Same offset and size of every member, and the same size of the whole. */
#define KERNEL	struct sja1000_priv
#define COPY	struct ts_can1_sja1000_priv_copy
static_assert(offsetof(KERNEL, can) == offsetof(COPY, can) &&
	      sizeof_field(KERNEL, can) == sizeof_field(COPY, can),
	      "sja1000-core.h: member can differs from struct sja1000_priv of this kernel");
static_assert(offsetof(KERNEL, echo_skb) == offsetof(COPY, echo_skb) &&
	      sizeof_field(KERNEL, echo_skb) == sizeof_field(COPY, echo_skb),
	      "sja1000-core.h: member echo_skb differs from struct sja1000_priv of this kernel");
static_assert(offsetof(KERNEL, read_reg) == offsetof(COPY, read_reg) &&
	      sizeof_field(KERNEL, read_reg) == sizeof_field(COPY, read_reg),
	      "sja1000-core.h: member read_reg differs from struct sja1000_priv of this kernel");
static_assert(offsetof(KERNEL, write_reg) == offsetof(COPY, write_reg) &&
	      sizeof_field(KERNEL, write_reg) == sizeof_field(COPY, write_reg),
	      "sja1000-core.h: member write_reg differs from struct sja1000_priv of this kernel");
static_assert(offsetof(KERNEL, pre_irq) == offsetof(COPY, pre_irq) &&
	      sizeof_field(KERNEL, pre_irq) == sizeof_field(COPY, pre_irq),
	      "sja1000-core.h: member pre_irq differs from struct sja1000_priv of this kernel");
static_assert(offsetof(KERNEL, post_irq) == offsetof(COPY, post_irq) &&
	      sizeof_field(KERNEL, post_irq) == sizeof_field(COPY, post_irq),
	      "sja1000-core.h: member post_irq differs from struct sja1000_priv of this kernel");
static_assert(offsetof(KERNEL, priv) == offsetof(COPY, priv) &&
	      sizeof_field(KERNEL, priv) == sizeof_field(COPY, priv),
	      "sja1000-core.h: member priv differs from struct sja1000_priv of this kernel");
static_assert(offsetof(KERNEL, dev) == offsetof(COPY, dev) &&
	      sizeof_field(KERNEL, dev) == sizeof_field(COPY, dev),
	      "sja1000-core.h: member dev differs from struct sja1000_priv of this kernel");
static_assert(offsetof(KERNEL, reg_base) == offsetof(COPY, reg_base) &&
	      sizeof_field(KERNEL, reg_base) == sizeof_field(COPY, reg_base),
	      "sja1000-core.h: member reg_base differs from struct sja1000_priv of this kernel");
static_assert(offsetof(KERNEL, irq_flags) == offsetof(COPY, irq_flags) &&
	      sizeof_field(KERNEL, irq_flags) == sizeof_field(COPY, irq_flags),
	      "sja1000-core.h: member irq_flags differs from struct sja1000_priv of this kernel");
static_assert(offsetof(KERNEL, cmdreg_lock) == offsetof(COPY, cmdreg_lock) &&
	      sizeof_field(KERNEL, cmdreg_lock) == sizeof_field(COPY, cmdreg_lock),
	      "sja1000-core.h: member cmdreg_lock differs from struct sja1000_priv of this kernel");
static_assert(offsetof(KERNEL, flags) == offsetof(COPY, flags) &&
	      sizeof_field(KERNEL, flags) == sizeof_field(COPY, flags),
	      "sja1000-core.h: member flags differs from struct sja1000_priv of this kernel");
static_assert(offsetof(KERNEL, ocr) == offsetof(COPY, ocr) &&
	      sizeof_field(KERNEL, ocr) == sizeof_field(COPY, ocr),
	      "sja1000-core.h: member ocr differs from struct sja1000_priv of this kernel");
static_assert(offsetof(KERNEL, cdr) == offsetof(COPY, cdr) &&
	      sizeof_field(KERNEL, cdr) == sizeof_field(COPY, cdr),
	      "sja1000-core.h: member cdr differs from struct sja1000_priv of this kernel");
static_assert(sizeof(KERNEL) == sizeof(COPY),
	      "sja1000-core.h: struct sja1000_priv has another size in this kernel");
