// SPDX-License-Identifier: GPL-2.0
/*
 * echo - the VM lanes' own smoke test: load the vmtest_echo module, check that
 * its device returns what was written (byte-exact, including a full FIFO and
 * O_NONBLOCK behaviour), and unload it again.
 */
#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tap.h"
#include "vmtest.h"

#define DEV "/dev/vmtest-echo"
#define FIFO_SIZE 4096

int main(void)
{
	unsigned char out[FIFO_SIZE + 16], in[FIFO_SIZE + 16];
	struct pollfd pfd;
	ssize_t n;
	size_t i;
	int fd;

	tap_plan(7);

	if (!tap_ok(sh("modprobe vmtest_echo") == 0 && wait_for_path(DEV) == 0,
		    "modprobe vmtest_echo creates " DEV))
		tap_bail("cannot continue without the device");

	fd = open(DEV, O_RDWR | O_NONBLOCK);
	if (fd < 0)
		tap_bail("open " DEV);

	for (i = 0; i < sizeof(out); i++)
		out[i] = (unsigned char)(i * 7 + 3);

	n = write(fd, "advee", 5);
	tap_ok(n == 5 && read(fd, in, sizeof(in)) == 5 && !memcmp(in, "advee", 5),
	       "short write is read back byte-exact");

	n = write(fd, out, sizeof(out));
	tap_ok(n == FIFO_SIZE, "write larger than the FIFO is cut to %d (got %zd)", FIFO_SIZE, n);

	tap_ok(write(fd, out, 1) == -1 && errno == EAGAIN, "full FIFO refuses with EAGAIN");

	memset(in, 0, sizeof(in));
	n = read(fd, in, sizeof(in));
	tap_ok(n == FIFO_SIZE && !memcmp(in, out, FIFO_SIZE), "full FIFO is read back byte-exact");

	pfd.fd = fd;
	pfd.events = POLLIN;
	tap_ok(poll(&pfd, 1, 0) == 0 && read(fd, in, 1) == -1 && errno == EAGAIN,
	       "empty device: poll shows no input, read says EAGAIN");
	close(fd);

	tap_ok(sh("modprobe -r vmtest_echo") == 0 && access(DEV, F_OK) != 0,
	       "modprobe -r vmtest_echo removes the device");

	return tap_finish();
}
