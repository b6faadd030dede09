// SPDX-License-Identifier: GPL-2.0
// LCM message -> JSON for the browser: {"channel": .., "utime": .., every
// field of the message under its .lcm name}. Arrays stay arrays; a float that
// is not finite becomes null (JSON has no NaN).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace advee::web {

// The ground-truth pose of the virtual robot (advee-robot-sim), not a robot channel.
inline constexpr std::string_view kSimPoseChannel = "SIM_DATA_POSE";

// Every channel the bridge subscribes to: advee::msgs::kAllChannels, plus
// SIM_DATA_POSE when its message type (package sim) is part of the build.
std::vector<std::string> bridged_channels();

// Decodes one LCM message of `channel`. nullopt: unknown channel, or the bytes
// are not a message of the channel's type (wrong fingerprint, truncated).
std::optional<nlohmann::json> message_to_json(std::string_view channel, const void* data,
                                              std::size_t size);

// The key under which a newer message replaces an older one that a client has
// not received yet: the channel, plus the module (or supervised target) for
// channels that several modules share, so that one module's state never
// hides another's.
std::string replace_key(const nlohmann::json& message);

}  // namespace advee::web
