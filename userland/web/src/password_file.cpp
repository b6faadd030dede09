// SPDX-License-Identifier: GPL-2.0
#include "advee/web/password_file.hpp"

#include <sodium.h>
#include <sys/stat.h>

#include <fstream>
#include <stdexcept>
#include <system_error>

namespace advee::web {

void init_crypto() {
  if (sodium_init() < 0) throw std::runtime_error("libsodium cannot start");
}

bool valid_operator_name(const std::string& name) {
  if (name.empty() || name.size() > 32) return false;
  for (const char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
          c == '.' || c == '-'))
      return false;
  return true;
}

// Argon2id with 2 passes over 19 MiB (OWASP's minimum for Argon2id): libsodium's
// INTERACTIVE 64 MiB would take half the TS-7800's 128 MiB for every login.
// The parameters are part of each stored hash: a change applies to new ones.
constexpr unsigned long long kOpsLimit = crypto_pwhash_OPSLIMIT_INTERACTIVE;
constexpr std::size_t kMemLimit = 19u << 20;

std::string hash_password(const std::string& password) {
  char out[crypto_pwhash_STRBYTES];
  if (crypto_pwhash_str(out, password.data(), password.size(), kOpsLimit, kMemLimit) != 0)
    throw std::runtime_error("crypto_pwhash_str: out of memory");
  return out;
}

bool verify_password(const std::string& hash, const std::string& password) {
  return crypto_pwhash_str_verify(hash.c_str(), password.data(), password.size()) == 0;
}

std::string random_password() {
  static constexpr char kAlphabet[] = "abcdefghijkmnopqrstuvwxyzABCDEFGHJKLMNPQRSTUVWXYZ23456789";
  std::string s(16, ' ');
  for (auto& c : s) c = kAlphabet[randombytes_uniform(sizeof kAlphabet - 1)];
  return s;
}

PasswordFile PasswordFile::load(const std::filesystem::path& path) {
  PasswordFile f;
  std::ifstream in(path);
  if (!in) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec) && !ec) return f;
    throw std::runtime_error(path.string() + ": cannot read (it must be readable by the service)");
  }
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty() || line[0] == '#') continue;
    const auto colon = line.find(':');
    const std::string name = line.substr(0, colon);
    if (colon == std::string::npos || !valid_operator_name(name) ||
        line.compare(colon + 1, 7, "$argon2") != 0)
      throw std::runtime_error(path.string() + ":" + std::to_string(n) +
                               ": expected NAME:HASH (set it with advee-web passwd)");
    f.hashes_[name] = line.substr(colon + 1);
  }
  return f;
}

void PasswordFile::save(const std::filesystem::path& path) const {
  const auto tmp = path.string() + ".new";
  // Created 0640 before anything is written: never readable by others.
  const mode_t old = ::umask(027);
  {
    std::ofstream out(tmp, std::ios::trunc);
    ::umask(old);
    if (!out) throw std::runtime_error(tmp + ": cannot write");
    out << "# advee-web operators: NAME:crypto_pwhash_str (advee-web passwd NAME)\n";
    for (const auto& [name, hash] : hashes_) out << name << ':' << hash << '\n';
    out.flush();
    if (!out) throw std::runtime_error(tmp + ": write failed");
  }
  if (::chmod(tmp.c_str(), 0640) != 0 || std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error(path.string() + ": cannot replace");
  }
}

void PasswordFile::set(const std::string& name, const std::string& password) {
  if (!valid_operator_name(name))
    throw std::invalid_argument("operator name: 1 to 32 of A-Z a-z 0-9 _ . -");
  hashes_[name] = hash_password(password);
}

bool PasswordFile::remove(const std::string& name) { return hashes_.erase(name) > 0; }

bool PasswordFile::check(const std::string& name, const std::string& password) const {
  const auto it = hashes_.find(name);
  if (it == hashes_.end()) {
    // The same cost for an unknown name.
    static const std::string dummy = hash_password("advee-web: no such operator");
    verify_password(dummy, password);
    return false;
  }
  return verify_password(it->second, password);
}

}  // namespace advee::web
