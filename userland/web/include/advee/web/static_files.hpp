// SPDX-License-Identifier: GPL-2.0
// The page's files, served from one directory (--root): request path to file,
// never outside the root, and the Content-Type of each file kind.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace advee::web {

// The file under `root` that the request target (path, maybe with a ?query)
// names; "/" is index.html. nullopt: a path that leaves the root ("..", a
// backslash or NUL), or no regular file there.
std::optional<std::filesystem::path> resolve_static(const std::filesystem::path& root,
                                                    std::string_view target);

// Content-Type by extension; application/octet-stream for unknown ones.
std::string_view content_type(const std::filesystem::path& file);

// The whole file, or nullopt when it cannot be read.
std::optional<std::string> read_file(const std::filesystem::path& file);

}  // namespace advee::web
