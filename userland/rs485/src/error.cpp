// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485/error.hpp"

#include <string>

namespace advee::rs485 {
namespace {

class Rs485Category final : public std::error_category {
 public:
  const char* name() const noexcept override { return "rs485"; }
  std::string message(int value) const override {
    switch (static_cast<Outcome>(value)) {
      case Outcome::ok: return "OK";
      case Outcome::timeout: return "TIMEOUT: no valid response after all retries";
      case Outcome::bad_crc: return "BADCRC: the response had a bad CRC after all retries";
      case Outcome::unknown_instruction: return "UNKINSTR: the device does not know the instruction";
      case Outcome::device_error: return "DEVERR: the device failed executing the instruction";
      case Outcome::error: return "ERROR: local bus failure or a response without ACK";
      case Outcome::bad_response: return "BADRESP: the response data does not have the instruction's layout";
    }
    return "unknown rs485 outcome " + std::to_string(value);
  }
};

}  // namespace

const std::error_category& rs485_category() noexcept {
  static const Rs485Category category;
  return category;
}

std::error_code make_error_code(Outcome o) noexcept { return {static_cast<int>(o), rs485_category()}; }

std::string_view outcome_name(Outcome o) noexcept {
  switch (o) {
    case Outcome::ok: return "OK";
    case Outcome::timeout: return "TIMEOUT";
    case Outcome::bad_crc: return "BADCRC";
    case Outcome::unknown_instruction: return "UNKINSTR";
    case Outcome::device_error: return "DEVERR";
    case Outcome::error: return "ERROR";
    case Outcome::bad_response: return "BADRESP";
  }
  return "?";
}

bool is_protocol_outcome(const std::error_code& ec) noexcept {
  return ec && ec.category() == rs485_category();
}

}  // namespace advee::rs485
