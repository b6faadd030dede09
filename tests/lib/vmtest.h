/* SPDX-License-Identifier: GPL-2.0 */
/*
 * vmtest.h - small helpers shared by the C programs of the VM suites.
 * Header-only, like tap.h; include it after tap.h.
 */
#ifndef VMTEST_VMTEST_H
#define VMTEST_VMTEST_H

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

/* Run a shell command built like printf; returns its exit status (-1: not run). */
static inline int sh(const char *fmt, ...)
{
	char cmd[512];
	va_list ap;
	int st;

	va_start(ap, fmt);
	vsnprintf(cmd, sizeof(cmd), fmt, ap);
	va_end(ap);
	st = system(cmd);
	return st == -1 ? -1 : WEXITSTATUS(st);
}

/* CLOCK_MONOTONIC in seconds. */
static inline double now_s(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec + ts.tv_nsec / 1e9;
}

/* Wait up to 3 s for a path: devtmpfs nodes appear asynchronously after registration. */
static inline int wait_for_path(const char *path)
{
	struct stat sb;
	int i;

	for (i = 0; i < 300; i++) {
		if (!stat(path, &sb))
			return 0;
		usleep(10000);
	}
	return -1;
}

/*
 * fuzz_size(CI, FULL): the size of a fuzz program, from VMTEST_FUZZ_SCALE
 * (the host's ADVEE_FUZZ_SCALE, docs/testing.md): CI in make check (unset or
 * "ci"), FULL with "full" (make fuzz: the goal's sizes of issue 26). Any other
 * value bails out: a typo must not quietly run the small size.
 */
static inline unsigned long fuzz_size(unsigned long ci, unsigned long full)
{
	const char *s = getenv("VMTEST_FUZZ_SCALE");

	if (!s || !*s || !strcmp(s, "ci"))
		return ci;
	if (!strcmp(s, "full"))
		return full;
	tap_bail("VMTEST_FUZZ_SCALE=%s: ci or full", s);
}

#endif /* VMTEST_VMTEST_H */
