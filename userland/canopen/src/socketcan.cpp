// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/socketcan.hpp"

#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/socket.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "advee/throw_errno.hpp"

namespace advee::canopen {

std::string_view to_string(CanControllerState s) {
  switch (s) {
    case CanControllerState::kErrorActive: return "error-active";
    case CanControllerState::kErrorWarning: return "error-warning";
    case CanControllerState::kErrorPassive: return "error-passive";
    case CanControllerState::kBusOff: return "bus-off";
  }
  return "?";
}

CanErrorInfo decode_error_frame(const ::can_frame& f) {
  CanErrorInfo e;
  const canid_t id = f.can_id;
  e.tx_timeout = id & CAN_ERR_TX_TIMEOUT;
  e.lost_arbitration = id & CAN_ERR_LOSTARB;
  e.protocol_violation = id & CAN_ERR_PROT;
  e.no_ack = id & CAN_ERR_ACK;
  e.bus_error = id & CAN_ERR_BUSERROR;
  e.restarted = id & CAN_ERR_RESTARTED;
  if (id & CAN_ERR_CRTL) {
    const std::uint8_t c = f.data[1];
    e.rx_overflow = c & CAN_ERR_CRTL_RX_OVERFLOW;
    e.tx_overflow = c & CAN_ERR_CRTL_TX_OVERFLOW;
    if (c & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE))
      e.state = CanControllerState::kErrorPassive;
    else if (c & (CAN_ERR_CRTL_RX_WARNING | CAN_ERR_CRTL_TX_WARNING))
      e.state = CanControllerState::kErrorWarning;
    else if (c & CAN_ERR_CRTL_ACTIVE)
      e.state = CanControllerState::kErrorActive;
  }
  if (id & CAN_ERR_BUSOFF) e.state = CanControllerState::kBusOff;
  if (e.restarted) e.state = CanControllerState::kErrorActive;
  if (id & CAN_ERR_CNT) {
    e.tx_errors = f.data[6];
    e.rx_errors = f.data[7];
  }
  return e;
}

CanSocket CanSocket::open(const std::string& ifname) {
  UniqueFd fd(::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW));
  if (!fd) throw_errno("socket(PF_CAN)");
  const unsigned idx = ::if_nametoindex(ifname.c_str());
  if (idx == 0) throw_errno(("if_nametoindex " + ifname).c_str());
  const can_err_mask_t err_mask = CAN_ERR_MASK;
  if (::setsockopt(fd.get(), SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof err_mask) < 0)
    throw_errno("CAN_RAW_ERR_FILTER");
  const int one = 1;
  if (::setsockopt(fd.get(), SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof one) < 0) throw_errno("SO_RXQ_OVFL");
  // A bigger receive buffer absorbs bursts while the loop is not scheduled: a
  // CAN skb costs ~1 KiB, so the default (rmem_default, ~200 KiB) holds only a
  // few hundred frames. FORCE needs CAP_NET_ADMIN; otherwise rmem_max caps it.
  const int rcvbuf = 8 << 20;
  if (::setsockopt(fd.get(), SOL_SOCKET, SO_RCVBUFFORCE, &rcvbuf, sizeof rcvbuf) < 0)
    (void)::setsockopt(fd.get(), SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf);
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = static_cast<int>(idx);
  if (::bind(fd.get(), reinterpret_cast<sockaddr*>(&addr), sizeof addr) < 0) throw_errno("bind(CAN)");
  return CanSocket(std::move(fd), ifname);
}

CanSocket::SendStatus CanSocket::send(const CanFrame& f) {
  ::can_frame k{};
  k.can_id = f.id & CAN_SFF_MASK;
  if (f.rtr) k.can_id |= CAN_RTR_FLAG;
  k.len = f.len;
  std::memcpy(k.data, f.data.data(), 8);
  const ssize_t n = ::write(fd_.get(), &k, sizeof k);
  if (n == static_cast<ssize_t>(sizeof k)) return SendStatus::kSent;
  if (n < 0 && (errno == ENOBUFS || errno == EAGAIN)) return SendStatus::kRetryLater;
  return SendStatus::kFailed;
}

namespace {
std::optional<CanSocket::Received> convert(const ::can_frame& k, ssize_t n) {
  if (n != static_cast<ssize_t>(sizeof k)) return std::nullopt;  // not a classic frame
  if (k.can_id & CAN_ERR_FLAG) return CanSocket::Error{decode_error_frame(k)};
  CanFrame f;
  f.id = k.can_id & (k.can_id & CAN_EFF_FLAG ? CAN_EFF_MASK : CAN_SFF_MASK);
  f.rtr = k.can_id & CAN_RTR_FLAG;
  f.len = k.len > 8 ? 8 : k.len;
  std::memcpy(f.data.data(), k.data, 8);
  if (k.can_id & CAN_EFF_FLAG) f.id |= 0x80000000u;  // 29-bit: never matches a CANopen COB-ID
  return f;
}
}  // namespace

std::size_t CanSocket::receive_batch(std::vector<Received>& out, std::size_t max) {
  constexpr std::size_t kBatch = 64;
  if (max > kBatch) max = kBatch;
  ::can_frame frames[kBatch];
  iovec iov[kBatch];
  mmsghdr msgs[kBatch];
  alignas(cmsghdr) char control[kBatch][CMSG_SPACE(sizeof(std::uint32_t))];
  for (std::size_t i = 0; i < max; ++i) {
    iov[i] = {&frames[i], sizeof frames[i]};
    msgs[i] = {};
    msgs[i].msg_hdr.msg_iov = &iov[i];
    msgs[i].msg_hdr.msg_iovlen = 1;
    msgs[i].msg_hdr.msg_control = control[i];
    msgs[i].msg_hdr.msg_controllen = sizeof control[i];
  }
  const int n = ::recvmmsg(fd_.get(), msgs, static_cast<unsigned>(max), MSG_DONTWAIT, nullptr);
  if (n < 0) {
    if (errno == EAGAIN || errno == EINTR) return 0;
    throw_errno("recvmmsg(CAN)");
  }
  for (int i = 0; i < n; ++i) {
    for (cmsghdr* c = CMSG_FIRSTHDR(&msgs[i].msg_hdr); c; c = CMSG_NXTHDR(&msgs[i].msg_hdr, c))
      if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_RXQ_OVFL) std::memcpy(&dropped_, CMSG_DATA(c), sizeof dropped_);
    if (auto r = convert(frames[i], static_cast<ssize_t>(msgs[i].msg_len))) out.push_back(std::move(*r));
  }
  return static_cast<std::size_t>(n);
}

std::optional<CanSocket::Received> CanSocket::receive() {
  ::can_frame k{};
  iovec iov{&k, sizeof k};
  alignas(cmsghdr) char control[CMSG_SPACE(sizeof(std::uint32_t))];
  msghdr msg{};
  msg.msg_iov = &iov;
  msg.msg_iovlen = 1;
  msg.msg_control = control;
  msg.msg_controllen = sizeof control;
  const ssize_t n = ::recvmsg(fd_.get(), &msg, 0);
  if (n < 0) {
    if (errno == EAGAIN || errno == EINTR) return std::nullopt;
    throw_errno("recvmsg(CAN)");
  }
  for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c; c = CMSG_NXTHDR(&msg, c))
    if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_RXQ_OVFL)
      std::memcpy(&dropped_, CMSG_DATA(c), sizeof dropped_);
  return convert(k, n);
}

}  // namespace advee::canopen
