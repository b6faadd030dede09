// SPDX-License-Identifier: GPL-2.0
/*
 * ioctlfuzz - random ioctl numbers of the discipline's range with random
 * directions, sizes, pointers (NULL, kernel addresses, unmapped, straddling
 * a page end) and random contents, also the real commands with random
 * contents: only clean errors (EINVAL, EFAULT, ENOTTY) or success, and the
 * bus works afterwards. Also checks at compile time that the UAPI layout is
 * the one documented (same on 32-bit user space), and that the ioctl codes
 * are our own: the discipline's and the simulator's old numbers (magic 0xB5,
 * rpmsg's, and 0xB4, gpio's, in ioctl-number.rst) are refused.
 */
#include <sys/mman.h>
#include <stddef.h>

#include "rs485-lib.h"

#define PORT	0
#define ROUNDS	20000

_Static_assert(sizeof(struct n_rs485_frame) == 260, "n_rs485_frame layout");
_Static_assert(sizeof(struct n_rs485_xfer) == 536, "n_rs485_xfer layout");
_Static_assert(offsetof(struct n_rs485_xfer, timeout_us) == 520, "n_rs485_xfer layout");
_Static_assert(offsetof(struct n_rs485_xfer, attempts) == 532, "n_rs485_xfer layout");
_Static_assert(sizeof(struct n_rs485_config) == 32, "n_rs485_config layout");
_Static_assert(offsetof(struct n_rs485_config, flags) == 16, "n_rs485_config layout");
_Static_assert(sizeof(struct n_rs485_stats) == 22 * 8, "n_rs485_stats layout");
_Static_assert(offsetof(struct n_rs485_stats, tx_path) == 18 * 8, "n_rs485_stats layout");
_Static_assert(offsetof(struct n_rs485_stats, collisions) == 17 * 8, "n_rs485_stats layout");
_Static_assert(sizeof(struct n_rs485_node) == 8, "n_rs485_node layout");

static const unsigned int real_cmds[] = {
	N_RS485_IOC_XFER, N_RS485_IOC_GET_CONFIG, N_RS485_IOC_SET_CONFIG, N_RS485_IOC_GET_STATS,
	N_RS485_IOC_GET_NODE, N_RS485_IOC_RESET_NODE, FIONREAD,
};

static uint32_t rng = 0x9e3779b9;

static uint32_t rnd(void)
{
	rng ^= rng << 13;
	rng ^= rng >> 17;
	rng ^= rng << 5;
	return rng;
}

int main(void)
{
	struct n_rs485_config defcfg;
	unsigned int ok = 0, clean = 0, bad = 0, i;
	struct n_rs485_xfer x;
	struct slave s;
	uint8_t *page;
	int fd, ret;

	tap_plan(4);
	if (sim_load())
		tap_bail("cannot load ts_uart + ts7800_sim");
	fd = bus_open(PORT);
	if (fd < 0 || slave_start(&s, PORT))
		tap_bail("attach n_rs485, slave");
	memset(&defcfg, 0, sizeof(defcfg));
	ioctl(fd, N_RS485_IOC_GET_CONFIG, &defcfg);
	/* two pages, the second inaccessible: arguments that straddle it fault */
	page = mmap(NULL, 8192, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
	if (page == MAP_FAILED || mprotect(page + 4096, 4096, PROT_NONE))
		tap_bail("mmap");

	for (i = 0; i < ROUNDS; i++) {
		unsigned int cmd, size = rnd() % 700, off;
		void *arg;

		if (rnd() % 2)
			cmd = real_cmds[rnd() % (sizeof(real_cmds) / sizeof(real_cmds[0]))];
		else
			cmd = _IOC(rnd() % 4, N_RS485_IOC_MAGIC, rnd() % 16, size);
		for (off = 0; off < 4096; off += 4)
			*(uint32_t *)(page + off) = rnd();
		switch (rnd() % 6) {
		case 0:
			arg = NULL;
			break;
		case 1:
			arg = (void *)(uintptr_t)(0xffffffff81000000ull + rnd());
			break;
		case 2:
			arg = page + 4096 - (rnd() % 64);	/* straddles the end */
			break;
		case 3:
			arg = page + 4096 + rnd() % 4096;	/* unmapped */
			break;
		default:
			arg = page + rnd() % 8;			/* valid, maybe unaligned */
			break;
		}
		if (cmd == N_RS485_IOC_XFER && (uint8_t *)arg >= page &&
		    (uint8_t *)arg < page + 3000) {
			struct n_rs485_xfer *px = arg;

			/* keep valid transactions short */
			px->timeout_us = 100 + rnd() % 2000;
			px->retries = rnd() % 2;
		}
		errno = 0;
		ret = ioctl(fd, cmd, arg);
		if (!ret) {
			ok++;
			if (cmd == N_RS485_IOC_SET_CONFIG)
				ioctl(fd, N_RS485_IOC_SET_CONFIG, &defcfg);
		} else if (errno == EINVAL || errno == EFAULT || errno == ENOTTY) {
			clean++;
		} else {
			bad++;
			if (bad < 10)
				tap_diag("cmd %#x arg %p: %s", cmd, arg, strerror(errno));
		}
	}
	tap_diag("%u rounds: %u succeeded, %u clean errors, %u other", ROUNDS, ok, clean, bad);
	tap_ok(bad == 0, "only clean errors (EINVAL, EFAULT, ENOTTY) or success");
	tap_ok(ok > 0 && clean > 0, "both successes and errors were exercised");
	ret = xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, "abc", 3, 300000, 2);
	tap_ok(ret == 0 && x.status == N_RS485_OK && !memcmp(x.resp.data, "abc", 3),
	       "the bus works after the fuzzing");
	{
		struct n_rs485_stats st;
		struct ts7800_sim_wire_stats ws;
		int r1, e1, r2, e2;

		r1 = ioctl(fd, _IOR(0xb5, 4, struct n_rs485_stats), &st);
		e1 = errno;
		r2 = ioctl(s.wfd, _IOR(0xb4, 1, struct ts7800_sim_wire_stats), &ws);
		e2 = errno;
		tap_ok(N_RS485_IOC_MAGIC != 0xb5 && TS7800_SIM_IOC_MAGIC != 0xb4 &&
		       r1 == -1 && e1 == ENOTTY && r2 == -1 && e2 == ENOTTY,
		       "the old codes (0xB5 statistics, 0xB4 wire statistics) are refused: %s, %s",
		       r1 ? strerror(e1) : "served", r2 ? strerror(e2) : "served");
	}
	slave_stop(&s);
	munmap(page, 8192);
	close(fd);
	sim_unload();
	return tap_finish();
}
