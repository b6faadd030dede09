// SPDX-License-Identifier: GPL-2.0
/*
 * The kernel's own SJA1000 core (drivers/net/can/sja1000/sja1000.c of the
 * kernel being built for), compiled as a test-only module for kernels that
 * are configured without it: the debug-kernel lane, so that ts-can1 and the
 * tscan1 suite run under KASAN, lockdep and kmemleak there too. Built only
 * when CONFIG_CAN_SJA1000 is off and the kernel's source tree is at hand
 * (tests/sim/Kbuild); Debian's kernels ship sja1000.ko themselves.
 */
#include "sja1000.c"

MODULE_INFO(test, "Y");
