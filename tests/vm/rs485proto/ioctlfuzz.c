// SPDX-License-Identifier: GPL-2.0
/*
 * ioctlfuzz - random ioctl numbers of the discipline's range with random
 * directions, sizes, pointers (NULL, kernel addresses, unmapped, straddling
 * a page end) and random contents, also the real commands with random
 * contents: only clean errors (EINVAL, EFAULT, ENOTTY) or success, and the
 * bus works afterwards. The same on the simulator's wire devices of both
 * ports (their range, their real commands; TS7800_SIM_READ_LOG also with a
 * user pointer into the test's pages and a random count), CTS, echo and the
 * line log put back before the bus is used again. Rounds: 20,000 on the
 * discipline and 10,000 on the wires in make check, 100,000 each with
 * VMTEST_FUZZ_SCALE=full (make fuzz). Also checks at compile time that the UAPI layout is
 * the one documented (same on 32-bit user space), and that the ioctl codes
 * are our own: the discipline's and the simulator's old numbers (magic 0xB5,
 * rpmsg's, and 0xB4, gpio's, in ioctl-number.rst) are refused.
 */
#include <sys/mman.h>
#include <stddef.h>

#include "rs485-lib.h"

#define PORT	0

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

static const unsigned int wire_cmds[] = {
	TS7800_SIM_GET_STATS, TS7800_SIM_RESET_STATS, TS7800_SIM_SET_CTS, TS7800_SIM_SET_ECHO,
	TS7800_SIM_SET_LOG, TS7800_SIM_READ_LOG, TS7800_SIM_GET_GAPS,
};

static uint32_t rng = 0x9e3779b9;

static uint32_t rnd(void)
{
	rng ^= rng << 13;
	rng ^= rng >> 17;
	rng ^= rng << 5;
	return rng;
}

/* random_arg PAGE: NULL, a kernel address, straddling, unmapped or valid */
static void *random_arg(uint8_t *page)
{
	unsigned int off;

	for (off = 0; off < 4096; off += 4)
		*(uint32_t *)(page + off) = rnd();
	switch (rnd() % 6) {
	case 0:
		return NULL;
	case 1:
		return (void *)(uintptr_t)(0xffffffff81000000ull + rnd());
	case 2:
		return page + 4096 - (rnd() % 64);	/* straddles the end */
	case 3:
		return page + 4096 + rnd() % 4096;	/* unmapped */
	default:
		return page + rnd() % 8;		/* valid, maybe unaligned */
	}
}

/*
 * wire_fuzz WFD[2] ROUNDS PAGE &OK &CLEAN: random ioctls on the two wires;
 * returns the count of other errors.
 */
static unsigned int wire_fuzz(const int *wfd, unsigned long rounds, uint8_t *page,
			      unsigned int *ok, unsigned int *clean)
{
	unsigned int bad = 0, cmd, size;
	unsigned long i;
	void *arg;
	int ret;

	for (i = 0; i < rounds; i++) {
		size = rnd() % 300;
		if (rnd() % 2)
			cmd = wire_cmds[rnd() % (sizeof(wire_cmds) / sizeof(wire_cmds[0]))];
		else
			cmd = _IOC(rnd() % 4, TS7800_SIM_IOC_MAGIC, rnd() % 12, size);
		arg = random_arg(page);
		if (cmd == TS7800_SIM_READ_LOG && (uint8_t *)arg >= page &&
		    (uint8_t *)arg < page + 4096 - sizeof(struct ts7800_sim_log_read) && rnd() % 2) {
			struct ts7800_sim_log_read *rd = arg;

			/* into the pages, maybe across the unmapped one */
			rd->events = (uintptr_t)(page + 2048 + rnd() % 2048);
			rd->max = rnd() % 2 ? rnd() % 256 : rnd();
		}
		errno = 0;
		ret = ioctl(wfd[rnd() % 2], cmd, arg);
		if (!ret) {
			(*ok)++;
		} else if (errno == EINVAL || errno == EFAULT || errno == ENOTTY) {
			(*clean)++;
		} else {
			bad++;
			if (bad < 10)
				tap_diag("wire cmd %#x arg %p: %s", cmd, arg, strerror(errno));
		}
	}
	return bad;
}

int main(void)
{
	const unsigned long rounds = fuzz_size(20000, 100000);
	const unsigned long wire_rounds = fuzz_size(10000, 100000);
	unsigned int ok = 0, clean = 0, bad = 0, wok = 0, wclean = 0, wbad, i;
	struct n_rs485_config defcfg;
	uint32_t one = 1, zero = 0;
	int wfd[2];
	double t0;
	struct n_rs485_xfer x;
	struct slave s;
	uint8_t *page;
	int fd, ret;

	tap_plan(5);
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

	t0 = now_s();
	for (i = 0; i < rounds; i++) {
		unsigned int cmd, size = rnd() % 700;
		void *arg;

		if (rnd() % 2)
			cmd = real_cmds[rnd() % (sizeof(real_cmds) / sizeof(real_cmds[0]))];
		else
			cmd = _IOC(rnd() % 4, N_RS485_IOC_MAGIC, rnd() % 16, size);
		arg = random_arg(page);
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
	tap_diag("discipline: %lu rounds in %.1f s: %u succeeded, %u clean errors, %u other",
		 rounds, now_s() - t0, ok, clean, bad);
	tap_ok(bad == 0, "only clean errors (EINVAL, EFAULT, ENOTTY) or success");
	tap_ok(ok > 0 && clean > 0, "both successes and errors were exercised");

	wfd[0] = s.wfd;
	wfd[1] = wire_open(1, O_NONBLOCK);
	if (wfd[1] < 0)
		tap_bail("wire of port 1");
	t0 = now_s();
	wbad = wire_fuzz(wfd, wire_rounds, page, &wok, &wclean);
	tap_diag("wires: %lu rounds in %.1f s: %u succeeded, %u clean errors, %u other",
		 wire_rounds, now_s() - t0, wok, wclean, wbad);
	tap_ok(wbad == 0 && wok > 0 && wclean > 0,
	       "wire devices: only clean errors (EINVAL, EFAULT, ENOTTY) or success, both seen");
	for (i = 0; i < 2; i++) {
		ioctl(wfd[i], TS7800_SIM_SET_CTS, &one);
		ioctl(wfd[i], TS7800_SIM_SET_ECHO, &zero);
		ioctl(wfd[i], TS7800_SIM_SET_LOG, &zero);
	}
	close(wfd[1]);
	ret = xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, "abc", 3, 300000, 2);
	tap_ok(ret == 0 && x.status == N_RS485_OK && !memcmp(x.resp.data, "abc", 3),
	       "the bus works after the fuzzing (CTS, echo, line log put back)");
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
