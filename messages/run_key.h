#pragma once
/// @file run_key.h
/// The per-run HMAC key of every LCM message of a run (docs/physical.md, "Message
/// authentication"): 32 random bytes, stored as 64 lowercase hex characters and a newline in
/// a file with permissions 0600. `hybridsim run` writes a fresh one to <results>/run.key for
/// every LCM run and hands its path to brfd-substructure and brfd-rig (--key-file: the path,
/// never the key, is on their command line); a lab gives its own with `rig.key_file`, an
/// external substructure with `transport.key_file`. The key comes from the kernel's CSPRNG
/// (getrandom); signing and verifying are in message_auth.h.

#include <fcntl.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

namespace messages {

using RunKey = std::array<uint8_t, 32>;

/// A key file is missing, unreadable, malformed or readable by others.
class KeyFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// 32 bytes from the kernel CSPRNG. Throws KeyFileError if getrandom fails.
inline RunKey generate_run_key() {
  RunKey key{};
  std::size_t got = 0;
  while (got < key.size()) {
    const ssize_t n = getrandom(key.data() + got, key.size() - got, 0);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw KeyFileError(std::string("getrandom failed: ") + std::strerror(errno));
    }
    got += static_cast<std::size_t>(n);
  }
  return key;
}

inline std::string key_to_hex(const RunKey& key) {
  static const char* digits = "0123456789abcdef";
  std::string s;
  for (uint8_t b : key) {
    s.push_back(digits[b >> 4]);
    s.push_back(digits[b & 15]);
  }
  return s;
}

/// Writes `key` as hex to `path`, replacing any old file, with permissions exactly 0600.
inline void write_key_file(const std::string& path, const RunKey& key) {
  ::unlink(path.c_str());
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) throw KeyFileError("cannot create key file '" + path + "': " + std::strerror(errno));
  const std::string text = key_to_hex(key) + "\n";
  const bool ok = ::fchmod(fd, 0600) == 0 && ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  const int e = errno;
  ::close(fd);
  if (!ok) throw KeyFileError("cannot write key file '" + path + "': " + std::strerror(e));
}

/// Reads a key file: 64 hex characters (surrounding whitespace ignored). Refuses a file that
/// group or others may read (chmod 600 it). Throws KeyFileError naming the file.
inline RunKey read_key_file(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw KeyFileError("cannot read HMAC key file '" + path + "': " + std::strerror(errno));
  if ((st.st_mode & 077) != 0)
    throw KeyFileError("HMAC key file '" + path + "' is accessible to group or others (mode " +
                       std::to_string(st.st_mode & 0777) + " octal " + [&] {
                         char b[8];
                         std::snprintf(b, sizeof b, "%03o", static_cast<unsigned>(st.st_mode & 0777));
                         return std::string(b);
                       }() + "): chmod 600 it");
  std::ifstream f(path);
  std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const auto first = text.find_first_not_of(" \t\r\n");
  const auto last = text.find_last_not_of(" \t\r\n");
  text = first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
  if (text.size() != 64)
    throw KeyFileError("HMAC key file '" + path + "' must hold 64 hex characters (32 bytes), found " +
                       std::to_string(text.size()) + " characters");
  RunKey key{};
  for (std::size_t i = 0; i < 32; ++i) {
    auto nibble = [&](char c) -> int {
      if (c >= '0' && c <= '9') return c - '0';
      if (c >= 'a' && c <= 'f') return c - 'a' + 10;
      if (c >= 'A' && c <= 'F') return c - 'A' + 10;
      throw KeyFileError("HMAC key file '" + path + "' has a non-hex character '" + std::string(1, c) + "'");
    };
    key[i] = static_cast<uint8_t>(nibble(text[2 * i]) << 4 | nibble(text[2 * i + 1]));
  }
  return key;
}

}  // namespace messages
