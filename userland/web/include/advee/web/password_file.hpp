// SPDX-License-Identifier: GPL-2.0
// The operators' passwords: one line per operator, "NAME:HASH", where HASH is
// libsodium's crypto_pwhash_str() (Argon2id, salted, its parameters inside).
// No password is ever stored or logged in clear. The file is written 0640
// (root and the service's group: docs/web-dashboard.md "Security model").
// C++17: bridge_server.cpp includes it.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>

namespace advee::web {

// Call once before anything below (sodium_init(); safe to repeat). Throws
// std::runtime_error when libsodium cannot start.
void init_crypto();

// A name is 1..32 of [A-Za-z0-9_.-]: it appears in logs and on LCM.
bool valid_operator_name(const std::string& name);

// crypto_pwhash_str of `password` (Argon2id, slow on purpose: 19 MiB, 2 passes;
// about 30 ms on the build host, longer on the robot's ARM computers).
std::string hash_password(const std::string& password);
bool verify_password(const std::string& hash, const std::string& password);
// 16 random letters and digits (~95 bits): a first operator's password.
std::string random_password();

class PasswordFile {
 public:
  // Reads `path`; a missing file is an empty one. Throws std::runtime_error
  // naming the line of a malformed entry, or when the file cannot be read.
  static PasswordFile load(const std::filesystem::path& path);

  // Writes atomically (temporary file + rename), mode 0640. Throws on error.
  void save(const std::filesystem::path& path) const;

  // Replaces or adds NAME's password. Throws std::invalid_argument for a bad name.
  void set(const std::string& name, const std::string& password);
  bool remove(const std::string& name);

  // True when NAME exists and PASSWORD is its password. An unknown name
  // costs a hash as well, so that timing does not tell names apart.
  bool check(const std::string& name, const std::string& password) const;

  std::size_t size() const { return hashes_.size(); }
  bool contains(const std::string& name) const { return hashes_.count(name) > 0; }

 private:
  std::map<std::string, std::string> hashes_;
};

}  // namespace advee::web
