/* SPDX-License-Identifier: GPL-2.0 */
/*
 * tap.h - minimal TAP 13 producer for the project's VM test programs.
 *
 * Output follows the kselftest conventions (plan, "ok N desc", "not ok N",
 * "# SKIP", "# " diagnostics), so the harness and any TAP consumer read it.
 * Exit codes: 0 all passed, 1 something failed, 4 everything skipped.
 * Single header, no state outside this file: include it in one .c only.
 */
#ifndef VMTEST_TAP_H
#define VMTEST_TAP_H

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <errno.h>

static unsigned int tap_n, tap_failed, tap_skipped, tap_planned;

static inline void tap_plan(unsigned int n)
{
	setvbuf(stdout, NULL, _IOLBF, 0);
	printf("TAP version 13\n1..%u\n", n);
	tap_planned = n;
}

static inline void tap_vresult(int ok, const char *directive, const char *fmt, va_list ap)
{
	printf("%sok %u ", ok ? "" : "not ", ++tap_n);
	vprintf(fmt, ap);
	if (directive)
		printf(" # %s", directive);
	putchar('\n');
	fflush(stdout);
}

/* Report one test point; returns cond so that callers can chain on it. */
static inline int tap_ok(int cond, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	tap_vresult(cond, NULL, fmt, ap);
	va_end(ap);
	if (!cond)
		tap_failed++;
	return cond;
}

/*
 * A point that checks a known, not yet fixed defect (TAP "# TODO"): it is
 * reported, and when it fails it fails as "not ok ... # TODO reason", which
 * the harness counts as an expected failure; the row then needs an entry in
 * tests/expected-skips like any skip. Returns cond.
 */
static inline int tap_ok_todo(int cond, const char *reason, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	tap_vresult(cond, cond ? NULL : reason, fmt, ap);
	va_end(ap);
	if (!cond)
		tap_skipped++;
	return cond;
}

static inline void tap_skip(const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	tap_vresult(1, "SKIP", fmt, ap);
	va_end(ap);
	tap_skipped++;
}

static inline void tap_diag(const char *fmt, ...)
{
	va_list ap;

	fputs("# ", stdout);
	va_start(ap, fmt);
	vprintf(fmt, ap);
	va_end(ap);
	putchar('\n');
}

/* Abort the whole program: remaining planned points count as failed. */
static inline void __attribute__((noreturn)) tap_bail(const char *fmt, ...)
{
	va_list ap;

	fputs("Bail out! ", stdout);
	va_start(ap, fmt);
	vprintf(fmt, ap);
	va_end(ap);
	printf(" (errno %d: %s)\n", errno, strerror(errno));
	exit(1);
}

static inline int tap_finish(void)
{
	if (tap_planned && tap_n != tap_planned) {
		tap_diag("planned %u tests but ran %u", tap_planned, tap_n);
		return 1;
	}
	if (tap_failed)
		return 1;
	return tap_n && tap_skipped == tap_n ? 4 : 0;
}

#endif /* VMTEST_TAP_H */
