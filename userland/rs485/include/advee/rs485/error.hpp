// SPDX-License-Identifier: GPL-2.0
// Outcomes of a transaction as std::error_code values of the "rs485"
// category, and Expected<T> for calls that return a value or an error.
//
// Errors a caller can get:
//  - rs485_category(): the outcomes of the spec (TIMEOUT, BADCRC, UNKINSTR,
//    DEVERR, ERROR) and bad_response (the response arrived with ACK but its
//    data does not have the layout of the instruction: a library-level check);
//  - std::system_category(): the call itself failed (EINTR: a signal, the
//    request may have executed; EIO: the discipline was detached or the tty
//    hung up; EBADF after Bus was closed, ...).
#pragma once

#include <cstdint>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>
#include <variant>

namespace advee::rs485 {

// Values 0..5 are enum n_rs485_status of the UAPI (n_rs485_xfer.status).
enum class Outcome : int {
  ok = 0,
  timeout = 1,              // TIMEOUT: no valid response after all retries
  bad_crc = 2,              // BADCRC: the last attempt's response had a bad CRC
  unknown_instruction = 3,  // UNKINSTR: the device does not know the instruction
  device_error = 4,         // DEVERR: the device failed executing it
  error = 5,                // ERROR: local failure (UART stuck), response without ACK
  bad_response = 16,        // library: response data not in the instruction's layout
};

const std::error_category& rs485_category() noexcept;
std::error_code make_error_code(Outcome o) noexcept;
// "OK", "TIMEOUT", "BADCRC", "UNKINSTR", "DEVERR", "ERROR", "BADRESP" (the spec's names).
std::string_view outcome_name(Outcome o) noexcept;
// True if `ec` is an rs485 outcome (the bus worked, the node's answer was not OK),
// false for system errors (the call did not get that far) and for success.
bool is_protocol_outcome(const std::error_code& ec) noexcept;

// A value or an error_code (std::expected is C++23). value() throws
// std::system_error when there is no value; operator* requires one.
template <typename T>
class Expected {
 public:
  Expected(T value) : v_(std::in_place_index<0>, std::move(value)) {}  // NOLINT: implicit by design
  Expected(std::error_code error) : v_(std::in_place_index<1>, error) {}  // NOLINT
  Expected(Outcome o) : v_(std::in_place_index<1>, make_error_code(o)) {}  // NOLINT

  bool has_value() const noexcept { return v_.index() == 0; }
  explicit operator bool() const noexcept { return has_value(); }
  std::error_code error() const noexcept { return has_value() ? std::error_code{} : std::get<1>(v_); }

  const T& value() const& {
    if (!has_value()) throw std::system_error(std::get<1>(v_));
    return std::get<0>(v_);
  }
  T& value() & {
    if (!has_value()) throw std::system_error(std::get<1>(v_));
    return std::get<0>(v_);
  }
  T&& value() && {
    if (!has_value()) throw std::system_error(std::get<1>(v_));
    return std::get<0>(std::move(v_));
  }
  const T& operator*() const& { return std::get<0>(v_); }
  T& operator*() & { return std::get<0>(v_); }
  const T* operator->() const { return &std::get<0>(v_); }
  T* operator->() { return &std::get<0>(v_); }

 private:
  std::variant<T, std::error_code> v_;
};

}  // namespace advee::rs485

template <>
struct std::is_error_code_enum<advee::rs485::Outcome> : std::true_type {};
