// SPDX-License-Identifier: GPL-2.0
/*
 * fuzz - random characters with random 9th bits, in bursts of 500, each
 * burst followed by a valid event frame: every valid frame after the noise
 * reaches read() byte-exact and in order, the discipline counts the garbage,
 * and a transaction works afterwards. 10^5 characters (200 frames) in make
 * check, 10^6 (2000 frames) with VMTEST_FUZZ_SCALE=full (make fuzz).
 */
#include "rs485-lib.h"

#define PORT		0
#define BURST_CHARS	500

int main(void)
{
	const unsigned long noise_chars = fuzz_size(100000, 1000000);
	const int bursts = noise_chars / BURST_CHARS;
	static uint16_t w[BURST_CHARS * 2 + 16];
	struct n_rs485_stats st;
	struct n_rs485_xfer x;
	struct event_reader rd;
	struct slave s;
	uint32_t rng = 0x2545f491;
	int fd, wfd, b, ret;
	size_t i, n;
	uint8_t f[8];
	double t0, limit;
	const char *slow = getenv("VMTEST_SLOWDOWN");

	tap_plan(4);
	if (sim_load())
		tap_bail("cannot load ts_uart + ts7800_sim");
	fd = bus_open(PORT);
	wfd = wire_open(PORT, O_NONBLOCK);
	if (fd < 0 || wfd < 0)
		tap_bail("attach n_rs485, wire");
	/* quiet: the noise makes frames of its own */
	if (event_reader_start(&rd, fd, bursts, 0))
		tap_bail("reader thread");

	t0 = now_s();
	for (b = 0; b < bursts; b++) {
		n = BURST_CHARS;
		for (i = 0; i < n; i++) {
			rng ^= rng << 13;
			rng ^= rng >> 17;
			rng ^= rng << 5;
			w[i] = rng & TS7800_SIM_WORD_CHAR;
		}
		n += frame_words(f, event_frame(b, f), 0, w + n);
		if (wire_write_all(wfd, w, n))
			tap_bail("wire write");
	}
	/*
	 * The wire needs ~10 s per 10^5 characters at 115200 Bd; the deadline
	 * (60 s per 10^5, times the lane's slowdown) is reached only on failure.
	 */
	limit = 60.0 * noise_chars / 100000 * (slow ? atoi(slow) : 1);
	while ((int)rd.next < bursts && now_s() - t0 < limit)
		usleep(100000);
	usleep(200000);
	event_reader_stop(&rd);
	close(wfd);

	get_stats(fd, &st);
	tap_diag("%lu noise characters, %d valid frames: %u lost", noise_chars, bursts,
		 rd.got < (unsigned int)bursts ? bursts - rd.got : 0);
	tap_diag("%.1f s; stats: rx %llu chars, %llu frames, crc %llu, truncated %llu, noise %llu, overruns %llu, events %llu, dropped %llu; %u frames made by the noise",
		 now_s() - t0, (unsigned long long)st.rx_bytes, (unsigned long long)st.rx_frames,
		 (unsigned long long)st.rx_crc_errors, (unsigned long long)st.rx_truncated,
		 (unsigned long long)st.rx_noise, (unsigned long long)st.rx_overruns,
		 (unsigned long long)st.events, (unsigned long long)st.events_dropped, rd.other + rd.non_event);
	/*
	 * Only a reported UART overrun (an emulated CPU that did not serve the
	 * FIFO in time, e.g. on the debug kernel) may cost a valid frame: the
	 * one whose characters it lost.
	 */
	tap_ok(rd.got + 2 * st.rx_overruns >= (unsigned int)bursts,
	       "every valid frame after noise reached read() in order: %u of %d (%llu overruns)",
	       rd.got, bursts, (unsigned long long)st.rx_overruns);
	tap_ok(st.rx_bytes >= noise_chars || st.rx_overruns,
	       "the discipline saw all %lu noise characters, or overruns were reported (%llu)",
	       noise_chars, (unsigned long long)st.rx_bytes);
	tap_ok(st.rx_crc_errors + st.rx_truncated + st.rx_noise > noise_chars / 100,
	       "garbage is counted (CRC errors, truncated frames, stray characters)");
	if (slave_start(&s, PORT))
		tap_bail("slave");
	ret = xfer(fd, &x, SLAVE_ADDR, I_ECHO, 0, f, 8, 300000, 2);
	tap_ok(ret == 0 && x.status == N_RS485_OK && !memcmp(x.resp.data, f, 8),
	       "a transaction works after the fuzzing");
	slave_stop(&s);
	close(fd);
	sim_unload();
	return tap_finish();
}
