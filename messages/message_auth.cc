#include "messages/message_auth.h"

#include <sodium.h>

#include <stdexcept>

namespace messages {

MessageAuth::MessageAuth(const RunKey& key) : key_(key) {
  static_assert(crypto_auth_hmacsha256_KEYBYTES == 32, "run key is 32 bytes");
  static_assert(crypto_auth_hmacsha256_BYTES == kMacBytes, "HMAC-SHA256 is 32 bytes");
  if (sodium_init() < 0) throw std::runtime_error("libsodium: sodium_init() failed");
}

void MessageAuth::mac(const uint8_t* data, std::size_t size, uint8_t* out) const {
  crypto_auth_hmacsha256(out, data, size, key_.data());
}

bool MessageAuth::verify(const uint8_t* data, std::size_t size) const {
  const std::size_t tail = 4 + kMacBytes;
  if (data == nullptr || size < kFingerprintBytes + tail) return false;
  const uint8_t* len = data + size - tail;
  const uint32_t hmac_length = static_cast<uint32_t>(len[0]) << 24 | static_cast<uint32_t>(len[1]) << 16 |
                               static_cast<uint32_t>(len[2]) << 8 | static_cast<uint32_t>(len[3]);
  if (hmac_length != static_cast<uint32_t>(kMacBytes)) return false;
  return crypto_auth_hmacsha256_verify(data + size - kMacBytes, data + kFingerprintBytes,
                                       size - tail - kFingerprintBytes, key_.data()) == 0;
}

const char* to_string(Received r) {
  switch (r) {
    case Received::ok: return "ok";
    case Received::malformed: return "malformed";
    case Received::foreign_run: return "foreign_run";
    case Received::bad_mac: return "bad_mac";
  }
  return "?";
}

bool peek_run_id(const uint8_t* data, std::size_t size, std::string& run_id) {
  constexpr std::size_t at = kFingerprintBytes + 8;  // fingerprint, utime
  if (data == nullptr || size < at + 4) return false;
  const uint32_t n = static_cast<uint32_t>(data[at]) << 24 | static_cast<uint32_t>(data[at + 1]) << 16 |
                     static_cast<uint32_t>(data[at + 2]) << 8 | static_cast<uint32_t>(data[at + 3]);
  if (n < 1 || n > size - at - 4 || data[at + 4 + n - 1] != 0) return false;
  run_id.assign(reinterpret_cast<const char*>(data + at + 4), n - 1);
  return true;
}

}  // namespace messages
