// SPDX-License-Identifier: GPL-2.0
/*
 * regmap - the FPGA regmap's debugfs dump (/sys/kernel/debug/regmap/) must
 * have no side effects and show only the registers the drivers own: a dump
 * that reads a TS-UART's DATA register pops its receive FIFO (a character
 * lost), one that reads STAT clears its overrun flag, and reads outside the
 * blocks we own (NAND, RTC, random number generator) may disturb the
 * devices of other drivers in the same window.
 */
#include <dirent.h>

#include "tsuart-lib.h"

#define REGMAP_DIR "/sys/kernel/debug/regmap"
/* TS-UART n: STAT at 0xC0 + 4n, DATA 2 above (docs/tsuart.md). */
#define UART_STAT(n)	(0x0c0 + 4 * (n))

/* Read the whole dump of the FPGA regmap into buf; returns its length or -1. */
static ssize_t dump_fpga(char *buf, size_t size)
{
	char path[512];
	struct dirent *e;
	ssize_t len = -1, r;
	DIR *d = opendir(REGMAP_DIR);
	int fd;

	if (!d)
		return -1;
	while ((e = readdir(d))) {
		if (!strstr(e->d_name, "ts7800-sim-fpga"))
			continue;
		snprintf(path, sizeof(path), REGMAP_DIR "/%s/registers", e->d_name);
		fd = open(path, O_RDONLY);
		if (fd < 0)
			break;
		len = 0;
		while (len < (ssize_t)size - 1 && (r = read(fd, buf + len, size - 1 - len)) > 0)
			len += r;
		buf[len] = 0;
		close(fd);
		break;
	}
	closedir(d);
	return len;
}

/* The dump starts at dump[1]; dump[0] is a newline, so every line is "\nREG:". */
static int listed(const char *dump, unsigned int reg)
{
	char key[16];

	snprintf(key, sizeof(key), "\n%03x:", reg);
	return strstr(dump, key) != NULL;
}

int main(void)
{
	static char dump[64 * 1024];
	struct ts7800_sim_wire_stats st;
	uint16_t ch = 'A';
	uint8_t got = 0;
	unsigned int n, bad;
	ssize_t len;
	double end;
	int fd, wfd;

	tap_plan(7);
	if (!tap_ok(sim_load("") == 0, "load ts_uart and ts7800_sim"))
		tap_bail("cannot continue without the simulator");
	fd = tty_open(6, B115200, 0, 0);
	wfd = wire_open(6, 0);

	/* A character waits in the RX FIFO while interrupts are held. */
	debugfs_write(-1, "irq_hold", 1);
	wire_write_all(wfd, &ch, 1);
	for (end = now_s() + 2; now_s() < end; usleep(1000))
		if (!wire_stats(wfd, &st) && st.from_wire == 1)
			break;
	dump[0] = '\n';
	len = dump_fpga(dump + 1, sizeof(dump) - 1);
	tap_ok(len > 0, "the regmap dump of the simulated FPGA can be read (%zd bytes)", len);
	debugfs_write(-1, "irq_hold", 0);
	tap_ok(tty_read_n(fd, &got, 1, 2) == 1 && got == 'A',
	       "a character in the RX FIFO survives the dump (got 0x%02x)", got);

	for (bad = 0, n = 0; n < NPORTS; n++)
		bad += listed(dump, UART_STAT(n) + 2);
	tap_ok(len > 0 && !bad, "no DATA register is in the dump (%u listed)", bad);
	for (bad = 0, n = 0; n < NPORTS; n++)
		bad += listed(dump, UART_STAT(n));
	tap_ok(len > 0 && !bad, "no STAT register (reading clears OERR) is in the dump (%u listed)",
	       bad);
	for (bad = 0, n = 0x208; n < 0x1000; n += 2)
		bad += listed(dump, n);
	bad += listed(dump, 0x044) + listed(dump, 0x046) + listed(dump, 0x0c);
	tap_ok(len > 0 && !bad && listed(dump, 0x000) && listed(dump, 0x204),
	       "only owned blocks are listed: ID and IRQ mask yes, RNG/NAND/RTC no (%u others)",
	       bad);
	close(fd);
	close(wfd);
	tap_ok(sim_unload() == 0, "unload");
	return tap_finish();
}
