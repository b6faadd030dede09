// SPDX-License-Identifier: GPL-2.0
/*
 * ioctlfuzz - random ioctl numbers of the discipline's range with random
 * directions, sizes, pointers (NULL, kernel addresses, unmapped, straddling
 * a page end) and random contents, also the real commands with random
 * contents: only clean errors (EINVAL, EFAULT, ENOTTY) or success, and the
 * bus works afterwards. Also checks at compile time that the UAPI layout is
 * the one documented (same on 32-bit user space), and that a program built
 * with the first, 136-byte struct rs485_stats still gets its statistics.
 */
#include <sys/mman.h>
#include <stddef.h>

#include "rs485-lib.h"

#define PORT	0
#define ROUNDS	20000

_Static_assert(sizeof(struct rs485_frame) == 260, "rs485_frame layout");
_Static_assert(sizeof(struct rs485_xfer) == 536, "rs485_xfer layout");
_Static_assert(offsetof(struct rs485_xfer, timeout_us) == 520, "rs485_xfer layout");
_Static_assert(offsetof(struct rs485_xfer, attempts) == 532, "rs485_xfer layout");
_Static_assert(sizeof(struct rs485_config) == 32, "rs485_config layout");
_Static_assert(offsetof(struct rs485_config, flags) == 16, "rs485_config layout");
_Static_assert(sizeof(struct rs485_stats) == 18 * 8, "rs485_stats layout");
_Static_assert(offsetof(struct rs485_stats, collisions) == 17 * 8, "rs485_stats layout");
_Static_assert(sizeof(struct rs485_node) == 8, "rs485_node layout");

static const unsigned int real_cmds[] = {
	RS485_IOC_XFER, RS485_IOC_GET_CONFIG, RS485_IOC_SET_CONFIG, RS485_IOC_GET_STATS,
	RS485_IOC_GET_NODE, RS485_IOC_RESET_NODE, FIONREAD,
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
	struct rs485_config defcfg;
	unsigned int ok = 0, clean = 0, bad = 0, i;
	struct rs485_xfer x;
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
	ioctl(fd, RS485_IOC_GET_CONFIG, &defcfg);
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
			cmd = _IOC(rnd() % 4, RS485_IOC_MAGIC, rnd() % 16, size);
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
		if (cmd == RS485_IOC_XFER && (uint8_t *)arg >= page &&
		    (uint8_t *)arg < page + 3000) {
			struct rs485_xfer *px = arg;

			/* keep valid transactions short */
			px->timeout_us = 100 + rnd() % 2000;
			px->retries = rnd() % 2;
		}
		errno = 0;
		ret = ioctl(fd, cmd, arg);
		if (!ret) {
			ok++;
			if (cmd == RS485_IOC_SET_CONFIG)
				ioctl(fd, RS485_IOC_SET_CONFIG, &defcfg);
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
	tap_ok(ret == 0 && x.status == RS485_OK && !memcmp(x.resp.data, "abc", 3),
	       "the bus works after the fuzzing");
	{
		/* RS485_IOC_GET_STATS as compiled before collisions was added */
		unsigned int old_cmd = _IOC(_IOC_READ, RS485_IOC_MAGIC, 4, 136);
		uint64_t old[18];
		struct rs485_stats st;

		memset(old, 0xa5, sizeof(old));
		get_stats(fd, &st);
		ret = ioctl(fd, old_cmd, old);
		tap_ok(ret == 0 && old[9] == st.xfers && old[0] >= st.tx_frames &&
		       old[17] == 0xa5a5a5a5a5a5a5a5ull,
		       "the 136-byte RS485_IOC_GET_STATS of older programs still works (xfers %llu), nothing written past it",
		       (unsigned long long)old[9]);
	}
	slave_stop(&s);
	munmap(page, 8192);
	close(fd);
	sim_unload();
	return tap_finish();
}
