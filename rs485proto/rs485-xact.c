// SPDX-License-Identifier: GPL-2.0
/*
 * rs485-xact.c - transactions: the FIFO of requests, the bus worker that
 * sends them and waits for the response, retries, outcomes and the per-node
 * error counters.
 *
 * Callers (N_RS485_IOC_XFER, write()) queue a request and sleep; the worker
 * runs the requests one at a time in arrival order, so several processes
 * share the bus fairly. A caller that is interrupted leaves its request to
 * the worker: the frame on the wire is always finished and a late response
 * is still awaited (without retries), so it cannot be taken for the answer
 * of the next request.
 */
#include <linux/slab.h>

#include "n_rs485.h"

/* A response that started before the timeout may take this long to finish. */
#define RS485_RESP_SLACK_NS	(2 * NSEC_PER_MSEC)

struct rs485_req *rs485_req_alloc(void)
{
	struct rs485_req *req = kzalloc(sizeof(*req), GFP_KERNEL);

	if (req) {
		INIT_LIST_HEAD(&req->node);
		kref_init(&req->ref);
	}
	return req;
}

static void rs485_req_release(struct kref *ref)
{
	kfree(container_of(ref, struct rs485_req, ref));
}

void rs485_req_put(struct rs485_req *req)
{
	kref_put(&req->ref, rs485_req_release);
}

/* Queue @req for the worker; the bus takes its own reference. */
int rs485_req_submit(struct rs485_bus *bus, struct rs485_req *req)
{
	unsigned long flags;
	int ret = 0;

	spin_lock_irqsave(&bus->lock, flags);
	if (bus->dead) {
		ret = -EIO;
	} else if (!req->is_xfer && bus->queued >= RS485_REQ_QUEUE_MAX) {
		ret = -EAGAIN;
	} else {
		kref_get(&req->ref);
		list_add_tail(&req->node, &bus->queue);
		bus->queued++;
		if (req->is_xfer)
			bus->stats.xfers++;
	}
	spin_unlock_irqrestore(&bus->lock, flags);
	if (!ret)
		queue_work(bus->wq, &bus->work);
	return ret;
}

/*
 * Sleep until the worker completed @req. Returns 0 (result in @req), -EIO
 * when the discipline goes away (the tty core sets TTY_LDISC_CHANGING and
 * wakes sleepers before it detaches the discipline or hangs up, and cannot
 * proceed while they stay inside it), and on a signal:
 *   -ERESTARTSYS while the request is still queued: it is withdrawn, nothing
 *   went out, so the call may be restarted (SA_RESTART, a stop signal, ptrace
 *   attach, the freezer) without a second execution;
 *   -EINTR once the worker has taken it: it is on the bus, is left to the
 *   worker (which finishes the frame and consumes a late response, see the
 *   top of this file), and must never be sent again by a restarted call.
 */
int rs485_req_wait(struct rs485_bus *bus, struct rs485_req *req)
{
	struct tty_struct *tty = bus->tty;
	bool withdrawn = false;
	unsigned long flags;
	int ret;

	ret = wait_event_interruptible(tty->write_wait, READ_ONCE(req->done) ||
				       test_bit(TTY_LDISC_CHANGING, &tty->flags));
	spin_lock_irqsave(&bus->lock, flags);
	if (req->done) {
		ret = bus->dead && req->status == N_RS485_ERROR ? -EIO : 0;
	} else {
		if (!ret)
			ret = -EIO;	/* the discipline is being detached */
		if (bus->cur == req) {
			req->abandoned = true;
			if (ret == -ERESTARTSYS)
				ret = -EINTR;
		} else {
			list_del_init(&req->node);
			bus->queued--;
			withdrawn = true;
		}
		if (req->is_xfer)
			bus->stats.xfers_failed++;
	}
	spin_unlock_irqrestore(&bus->lock, flags);
	if (withdrawn)
		rs485_req_put(req);	/* the bus's reference */
	return ret;
}

/* CAN-like error counter of a node: +8 per failed exchange, -1 per good one. */
static void rs485_node_account(struct rs485_bus *bus, struct rs485_req *req)
{
	u8 addr = req->frame.addr;
	u16 *err = &bus->node_err[addr];

	if (!req->expect_resp)
		return;
	switch (req->status) {
	case N_RS485_TIMEOUT:
	case N_RS485_BADCRC:
		*err = min(*err + RS485_ERR_FAIL, RS485_ERR_OFF);
		break;
	case N_RS485_OK:
	case N_RS485_UNKINSTR:
	case N_RS485_DEVERR:
		/* The node answers: an "off" node is back, else count down. */
		if (*err >= RS485_ERR_OFF)
			*err = 0;
		else if (*err)
			(*err)--;
		break;
	default:
		break;		/* local failures say nothing about the node */
	}
}

static u32 rs485_resp_status(const struct n_rs485_frame *resp)
{
	if (resp->flags & N_RS485_RESP_UNKINSTR)
		return N_RS485_UNKINSTR;
	if (resp->flags & N_RS485_RESP_DEVERR)
		return N_RS485_DEVERR;
	if (resp->flags & N_RS485_RESP_ACK)
		return N_RS485_OK;
	return N_RS485_ERROR;	/* a response that claims nothing */
}

static bool rs485_resp_final(struct rs485_bus *bus)
{
	unsigned long flags;
	bool final;

	spin_lock_irqsave(&bus->lock, flags);
	final = bus->dead || bus->resp_state == RS485_RESP_GOOD ||
		bus->resp_state == RS485_RESP_CORRUPT;
	spin_unlock_irqrestore(&bus->lock, flags);
	return final;
}

/*
 * Wait for the response to the request just sent; returns the final state.
 * The state stays as it is: until the next attempt goes out, the response
 * may still come whole (rs485_run()).
 */
static enum rs485_resp_state rs485_await(struct rs485_bus *bus, struct rs485_req *req)
{
	ktime_t tmo = ns_to_ktime((u64)req->timeout_us * NSEC_PER_USEC);
	enum rs485_resp_state state;
	bool extended = false;
	unsigned long flags;

	for (;;) {
		wait_event_hrtimeout(bus->resp_wait, rs485_resp_final(bus), tmo);
		spin_lock_irqsave(&bus->lock, flags);
		state = bus->resp_state;
		if (state == RS485_RESP_STARTED && !extended && !bus->dead) {
			/* The node began in time: give its frame time to finish. */
			spin_unlock_irqrestore(&bus->lock, flags);
			tmo = ns_to_ktime(RS485_WIRE_MAX * rs485_char_ns(bus) +
					  RS485_RESP_SLACK_NS);
			extended = true;
			continue;
		}
		spin_unlock_irqrestore(&bus->lock, flags);
		return state;
	}
}

static size_t rs485_req_encode(const struct rs485_req *req, bool resend, u8 *buf)
{
	size_t len = N_RS485_HEADER_LEN + req->frame.len;

	memcpy(buf, &req->frame, len);
	if (resend)
		buf[2] |= N_RS485_REQ_RESEND;
	buf[len] = rs485_crc(buf, len);
	return len + 1;
}

void rs485_count(struct rs485_bus *bus, u64 *counter)
{
	unsigned long flags;

	spin_lock_irqsave(&bus->lock, flags);
	(*counter)++;
	spin_unlock_irqrestore(&bus->lock, flags);
}

/* Send @req with its retries; sets req->status. */
static void rs485_run(struct rs485_bus *bus, struct rs485_req *req, u8 *buf)
{
	bool resend = false;
	unsigned long flags;
	u32 attempt;
	int ret;

	req->status = N_RS485_ERROR;
	for (attempt = 0; attempt <= req->retries; attempt++) {
		enum rs485_resp_state state;
		size_t len;

		if (attempt && (READ_ONCE(req->abandoned) || READ_ONCE(bus->dead))) {
			req->status = N_RS485_ERROR;
			return;
		}
		rs485_line_wait(bus);

		/*
		 * Until this request goes out, the last attempt still owns
		 * what arrives (rs485_rx_frame_for_xact()): its response may
		 * have come whole after all, after the cut frame of the node
		 * that made it "corrupt" (an event hit by an overrun) or after
		 * the timeout. Then it is the answer, and a retry would only
		 * bring a second one, for read() or the next transaction. If
		 * it has started since, the node has executed: RESEND. A frame
		 * that begins from here on belongs to the new attempt.
		 */
		spin_lock_irqsave(&bus->lock, flags);
		if (bus->resp_state == RS485_RESP_GOOD) {
			spin_unlock_irqrestore(&bus->lock, flags);
			req->status = rs485_resp_status(&req->resp);
			return;
		}
		if (bus->resp_state == RS485_RESP_STARTED || bus->resp_state == RS485_RESP_CORRUPT)
			resend = true;
		bus->resp_state = req->expect_resp ? RS485_RESP_WAIT : RS485_RESP_NONE;
		bus->attempt++;
		if (attempt)
			bus->stats.retries++;
		spin_unlock_irqrestore(&bus->lock, flags);

		len = rs485_req_encode(req, resend, buf);
		req->attempts++;
		ret = rs485_tx_frame(bus, buf, len);
		if (ret) {
			spin_lock_irqsave(&bus->lock, flags);
			bus->resp_state = RS485_RESP_NONE;
			if (ret == -ECOMM)
				bus->stats.collisions++;
			spin_unlock_irqrestore(&bus->lock, flags);
			if (ret == -ECOMM && !READ_ONCE(bus->dead)) {
				/*
				 * The node got a garbled frame (or none): no
				 * response to wait for. Repeat the request (after
				 * the gap, like every request).
				 */
				req->status = N_RS485_COLLISION;
				continue;
			}
			req->status = N_RS485_ERROR;
			return;
		}
		if (!req->expect_resp) {
			req->status = N_RS485_OK;
			return;
		}
		state = rs485_await(bus, req);
		if (READ_ONCE(bus->dead)) {
			req->status = N_RS485_ERROR;
			return;
		}
		switch (state) {
		case RS485_RESP_GOOD:
			req->status = rs485_resp_status(&req->resp);
			return;
		case RS485_RESP_CORRUPT:
		case RS485_RESP_STARTED:
			/*
			 * The node's address character arrived, so it executed:
			 * its response failed the CRC, was cut short (address
			 * character, overrun, framing error, break) or stopped.
			 * Ask for the answer again, in this and every later
			 * retry of the request (set there).
			 */
			req->status = N_RS485_BADCRC;
			break;
		default:
			/*
			 * Nothing of a response: the request is repeated as it
			 * was, unless an earlier attempt set RESEND (sticky).
			 */
			rs485_count(bus, &bus->stats.timeouts);
			req->status = N_RS485_TIMEOUT;
			break;
		}
	}
}

void rs485_xact_work(struct work_struct *work)
{
	struct rs485_bus *bus = container_of(work, struct rs485_bus, work);
	u8 buf[RS485_WIRE_MAX];
	struct rs485_req *req;
	unsigned long flags;

	for (;;) {
		spin_lock_irqsave(&bus->lock, flags);
		if (bus->dead || list_empty(&bus->queue)) {
			spin_unlock_irqrestore(&bus->lock, flags);
			return;
		}
		req = list_first_entry(&bus->queue, struct rs485_req, node);
		list_del_init(&req->node);
		bus->queued--;
		bus->cur = req;
		spin_unlock_irqrestore(&bus->lock, flags);

		mutex_lock(&bus->line_mutex);
		rs485_run(bus, req, buf);
		mutex_unlock(&bus->line_mutex);

		spin_lock_irqsave(&bus->lock, flags);
		bus->cur = NULL;
		bus->resp_state = RS485_RESP_NONE;
		if (!req->abandoned && req->is_xfer) {
			if (req->status == N_RS485_OK)
				bus->stats.xfers_ok++;
			else
				bus->stats.xfers_failed++;
		}
		if (req->is_xfer)
			rs485_node_account(bus, req);
		WRITE_ONCE(req->done, true);
		spin_unlock_irqrestore(&bus->lock, flags);
		wake_up_interruptible_all(&bus->tty->write_wait);
		rs485_req_put(req);
	}
}

/* Detach or hangup: fail everything queued, stop the worker's wait. */
void rs485_xact_kill(struct rs485_bus *bus)
{
	struct rs485_req *req, *tmp;
	unsigned long flags;
	LIST_HEAD(failed);

	spin_lock_irqsave(&bus->lock, flags);
	bus->dead = true;
	list_for_each_entry_safe(req, tmp, &bus->queue, node) {
		list_move_tail(&req->node, &failed);
		bus->queued--;
		req->status = N_RS485_ERROR;
		if (req->is_xfer)
			bus->stats.xfers_failed++;
		WRITE_ONCE(req->done, true);
	}
	spin_unlock_irqrestore(&bus->lock, flags);
	wake_up_all(&bus->resp_wait);
	wake_up_interruptible_all(&bus->tty->write_wait);
	list_for_each_entry_safe(req, tmp, &failed, node) {
		list_del_init(&req->node);
		rs485_req_put(req);
	}
}

/* Does the waiting request take this valid frame? Called by the RX machine. */
bool rs485_rx_frame_for_xact(struct rs485_bus *bus, const u8 *frame, unsigned int len,
			     u32 attempt)
{
	bool taken = false, wake = false;
	struct rs485_req *req;
	unsigned long flags;

	spin_lock_irqsave(&bus->lock, flags);
	bus->stats.rx_frames++;
	req = bus->cur;
	/* Also between attempts (CORRUPT, or WAIT after a timeout): rs485_run(). */
	if (req && bus->resp_state != RS485_RESP_NONE && bus->resp_state != RS485_RESP_GOOD &&
	    !(frame[2] & N_RS485_RESP_EVENT) &&
	    frame[0] == req->frame.addr && frame[1] == req->frame.instr) {
		memcpy(&req->resp, frame, len);
		bus->resp_state = RS485_RESP_GOOD;
		/* A write() request's response goes to read(). */
		taken = req->is_xfer;
		wake = true;
	} else if (req && bus->resp_state == RS485_RESP_STARTED && attempt == bus->attempt &&
		   frame[0] == req->frame.addr) {
		/*
		 * The address character that made the response "started" was
		 * a whole frame of the node that is not the response (an event,
		 * a late answer): nothing of the response has arrived yet.
		 */
		bus->resp_state = RS485_RESP_WAIT;
	}
	spin_unlock_irqrestore(&bus->lock, flags);
	if (wake)
		wake_up_all(&bus->resp_wait);
	return taken;
}

/*
 * A frame from @addr that began during @attempt ended without being valid
 * (bad CRC, cut short): if it is the response being waited for, retry now.
 */
void rs485_rx_corrupt_from(struct rs485_bus *bus, u8 addr, u32 attempt)
{
	unsigned long flags;
	bool wake = false;

	spin_lock_irqsave(&bus->lock, flags);
	if (bus->cur && bus->cur->frame.addr == addr && attempt == bus->attempt &&
	    (bus->resp_state == RS485_RESP_WAIT || bus->resp_state == RS485_RESP_STARTED)) {
		bus->resp_state = RS485_RESP_CORRUPT;
		wake = true;
	}
	spin_unlock_irqrestore(&bus->lock, flags);
	if (wake)
		wake_up_all(&bus->resp_wait);
}

/*
 * Address character seen: if it is the awaited node's, it has started to
 * answer. Returns the attempt the frame that begins here belongs to.
 */
u32 rs485_rx_addr_seen(struct rs485_bus *bus, u8 addr)
{
	unsigned long flags;
	u32 attempt;

	spin_lock_irqsave(&bus->lock, flags);
	if (bus->cur && bus->cur->frame.addr == addr && bus->resp_state == RS485_RESP_WAIT)
		bus->resp_state = RS485_RESP_STARTED;
	attempt = bus->attempt;
	spin_unlock_irqrestore(&bus->lock, flags);
	return attempt;
}
