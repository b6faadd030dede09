// SPDX-License-Identifier: GPL-2.0
/*
 * echo - a 2-wire half-duplex bus whose transceiver keeps its receiver on:
 * the simulated UART hears every character it sends (TS7800_SIM_SET_ECHO).
 * Without N_RS485_CFG_ECHO the echo is taken for the response; with it the
 * discipline discards the echo and every outcome is as on a quiet bus. A
 * frame that the bus does not carry as sent (simulated by corrupting what
 * the UART transmits, which the node and the echo both see) is a collision:
 * counted, retried as a plain repeat, N_RS485_COLLISION when every attempt
 * collides. A missing echo is one as well, also when the UART lost echo
 * characters in an overrun (the discipline cannot tell): an emulated CPU
 * under host load can miss 16 character times, so on the quiet line a
 * collision is accepted only where the simulated UART counted an overrun,
 * and the transfer is retried then.
 */
#include "rs485-lib.h"

#define PORT	0

static int set_echo_flag(int fd, int on)
{
	struct n_rs485_config cfg;

	memset(&cfg, 0, sizeof(cfg));
	if (ioctl(fd, N_RS485_IOC_GET_CONFIG, &cfg))
		return -1;
	cfg.flags = on ? N_RS485_CFG_ECHO : 0;
	return ioctl(fd, N_RS485_IOC_SET_CONFIG, &cfg);
}

int main(void)
{
	struct n_rs485_stats st0, st;
	struct ts7800_sim_wire_stats ws0, ws;
	unsigned long long overruns;
	struct n_rs485_config cfg;
	uint8_t data[N_RS485_MAX_DATA], buf[N_RS485_MAX_FRAME];
	struct n_rs485_xfer x;
	struct slave s;
	unsigned int exec0;
	int fd, ret, i;

	tap_plan(12);
	if (sim_load())
		tap_bail("cannot load ts_uart + ts7800_sim");
	fd = bus_open(PORT);
	if (fd < 0 || slave_start(&s, PORT))
		tap_bail("attach n_rs485, slave");
	if (wire_set_echo(s.wfd, 1))
		tap_bail("TS7800_SIM_SET_ECHO: %s", strerror(errno));
	for (i = 0; i < N_RS485_MAX_DATA; i++)
		data[i] = i * 7 + 3;

	/* The problem: the echo has the request's ADDR and INSTR. */
	ret = xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, data, 4, 300000, 0);
	tap_ok(ret == 0 && x.status == N_RS485_ERROR && x.resp.flags == 0,
	       "without N_RS485_CFG_ECHO the echo is taken for the response (status %u, flags %#x)",
	       x.status, x.resp.flags);
	/* the node's real response went to read() */
	usleep(50000);
	while (poll(&(struct pollfd){ .fd = fd, .events = POLLIN }, 1, 0) > 0 &&
	       read(fd, buf, sizeof(buf)) > 0)
		;

	memset(&cfg, 0, sizeof(cfg));
	cfg.baud = 115200;
	cfg.timeout_us = 10000;
	cfg.retries = 2;
	cfg.gap_chars = 2;
	cfg.flags = 0x2;
	errno = 0;
	tap_ok(ioctl(fd, N_RS485_IOC_SET_CONFIG, &cfg) && errno == EINVAL,
	       "unknown configuration flags: EINVAL");
	ret = set_echo_flag(fd, 1);
	memset(&cfg, 0, sizeof(cfg));
	ioctl(fd, N_RS485_IOC_GET_CONFIG, &cfg);
	tap_ok(ret == 0 && cfg.flags == N_RS485_CFG_ECHO, "N_RS485_CFG_ECHO set and read back");

	get_stats(fd, &st0);
	wire_stats(s.wfd, &ws0);
	ret = xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, data, 255, 300000, 2);
	wire_stats(s.wfd, &ws);
	overruns = ws.rx_overruns - ws0.rx_overruns;
	tap_ok(ret == 0 && x.status == N_RS485_OK && (x.attempts == 1 || overruns) &&
	       x.resp.len == 255 && !memcmp(x.resp.data, data, 255),
	       "with it, 255 bytes echoed by the node come back byte-exact (status %u, attempts %u; more than one only after an overrun: %llu)",
	       x.status, x.attempts, overruns);
	ret = xfer(fd, &x, SLAVE_ADDR, I_SILENT, 0, NULL, 0, 20000, 2);
	tap_ok(ret == 0 && x.status == N_RS485_TIMEOUT && x.attempts == 3,
	       "a silent node: TIMEOUT after 3 attempts (status %u, attempts %u)",
	       x.status, x.attempts);
	exec0 = s.executions[I_CORRUPT_ONCE];
	ret = xfer(fd, &x, SLAVE_ADDR, I_CORRUPT_ONCE, 0, NULL, 0, 300000, 2);
	tap_ok(ret == 0 && x.status == N_RS485_OK && x.attempts == 2 && x.resp.data[0] == 0x5a &&
	       s.executions[I_CORRUPT_ONCE] == exec0 + 1,
	       "a corrupted response: RESEND, the node executed once (status %u, attempts %u)",
	       x.status, x.attempts);
	ret = xfer(fd, &x, N_RS485_ADDR_BROADCAST, I_ECHO, 0, data, 3, N_RS485_DEFAULT, N_RS485_DEFAULT);
	tap_ok(ret == 0 && x.status == N_RS485_OK, "broadcast: OK once its echo is back");
	get_stats(fd, &st);
	wire_stats(s.wfd, &ws);
	overruns = ws.rx_overruns - ws0.rx_overruns;
	tap_ok(st.collisions - st0.collisions <= overruns && st.unexpected == st0.unexpected,
	       "no collision but after an overrun, and no echo delivered as a frame (collisions +%llu, overruns +%llu, unexpected +%llu)",
	       (unsigned long long)(st.collisions - st0.collisions), overruns,
	       (unsigned long long)(st.unexpected - st0.unexpected));

	/* One character of the request is changed on the line: a collision. */
	get_stats(fd, &st0);
	exec0 = s.executions[I_COUNT];
	debugfs_write(PORT, "tx_corrupt", 1);
	ret = xfer(fd, &x, SLAVE_ADDR, I_COUNT, 0, NULL, 0, 300000, 2);
	get_stats(fd, &st);
	tap_ok(ret == 0 && x.status == N_RS485_OK && x.attempts == 2 &&
	       st.collisions == st0.collisions + 1 && s.executions[I_COUNT] == exec0 + 1,
	       "a collision is counted and the request repeated: OK on attempt %u, collisions +%llu, executed %u time(s)",
	       x.attempts, (unsigned long long)(st.collisions - st0.collisions),
	       s.executions[I_COUNT] - exec0);

	/* Every attempt collides. */
	get_stats(fd, &st0);
	debugfs_write(PORT, "tx_corrupt", 1000);
	ret = xfer(fd, &x, SLAVE_ADDR, I_COUNT, 0, NULL, 0, 300000, 2);
	debugfs_write(PORT, "tx_corrupt", 0);
	get_stats(fd, &st);
	tap_ok(ret == 0 && x.status == N_RS485_COLLISION && x.attempts == 3 &&
	       st.collisions == st0.collisions + 3 && st.xfers_failed == st0.xfers_failed + 1 &&
	       s.executions[I_COUNT] == exec0 + 1,
	       "every attempt collides: N_RS485_COLLISION after 3 attempts (status %u, collisions +%llu), the node executed nothing",
	       x.status, (unsigned long long)(st.collisions - st0.collisions));

	/* The flag on a bus that does not echo: the echo is missing. */
	wire_set_echo(s.wfd, 0);
	ret = xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, data, 2, 300000, 0);
	tap_ok(ret == 0 && x.status == N_RS485_COLLISION,
	       "no echo although N_RS485_CFG_ECHO: N_RS485_COLLISION (status %u)", x.status);
	set_echo_flag(fd, 0);
	ret = xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, data, 2, 300000, 0);
	get_stats(fd, &st);
	tap_ok(ret == 0 && x.status == N_RS485_OK && st.xfers == st.xfers_ok + st.xfers_failed,
	       "flag off again on a quiet bus: OK; xfers %llu = ok %llu + failed %llu",
	       (unsigned long long)st.xfers, (unsigned long long)st.xfers_ok,
	       (unsigned long long)st.xfers_failed);

	slave_stop(&s);
	close(fd);
	sim_unload();
	return tap_finish();
}
