#pragma once
/// @file message_auth.h
/// Per-run message authentication of every LCM message of a run (docs/physical.md, "Message
/// authentication"): drift commands, force feedback, run control and heartbeats between
/// hybridsim and brfd-substructure, actuator commands and sensor frames between
/// brfd-substructure and the lab controller (or brfd-rig).
///
/// Every message type ends with the two fields `int32_t hmac_length; byte hmac[hmac_length];`.
/// The HMAC is HMAC-SHA256 (libsodium crypto_auth_hmacsha256, RFC 2104 / FIPS 198-1) under the
/// 32-byte run key (run_key.h) of exactly these bytes of the message's LCM encoding:
///
///     encoding[8 .. size - 4 - 32)
///
/// i.e. every field before hmac_length, each as LCM encodes it (big-endian; int64 8 bytes,
/// double IEEE-754 8 bytes, int8 1 byte, int32 4 bytes, string = int32 length counting a
/// terminating NUL, the bytes, the NUL; arrays element by element), without the 8-byte type
/// fingerprint and without hmac_length and hmac. A receiver verifies on the bytes it received
/// (constant-time compare), so no re-encoding can hide a difference.
///
/// Freshness is not the MAC's job: every type carries a sequence that the receiver requires
/// to increase (replays), and replies echo the sequence of the command they answer.
///
/// Receiving (check_and_decode): nothing unauthenticated is decoded. The type fingerprint is
/// compared and the run id read in place (every type starts with utime, run_id, so run_id is
/// the LCM string at byte 16); a message of another run is "foreign_run", one of ours whose
/// HMAC fails is "bad_mac", and only an authentic message is decoded (strictly). A forged
/// array length (e.g. num_dampers = 2^31 - 1) therefore never reaches LCM's decoder, which
/// would allocate it.

#include "messages/run_key.h"
#include "messages/transport.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace messages {

/// Bytes of the HMAC (HMAC-SHA256).
constexpr int kMacBytes = 32;
/// Bytes of an LCM type fingerprint (not authenticated).
constexpr int kFingerprintBytes = 8;

/// Signs and verifies messages under one run key. Allocation-free once `buffer`s have their
/// capacity.
class MessageAuth {
 public:
  /// Initialises libsodium; throws std::runtime_error if it cannot.
  explicit MessageAuth(const RunKey& key);

  /// HMAC-SHA256 of `size` bytes into out[0..32).
  void mac(const uint8_t* data, std::size_t size, uint8_t* out) const;

  /// True when `data` (a whole received message, fingerprint first) ends in hmac_length = 32
  /// and an HMAC of the bytes before hmac_length that verifies.
  bool verify(const uint8_t* data, std::size_t size) const;
  bool verify(const RawMessage& m) const { return verify(m.data, m.size); }

  /// Sets msg.hmac_length = 32 and msg.hmac to the HMAC of the other fields; `buffer` holds
  /// the signed encoding afterwards. Throws EncodeError (as publish_message does).
  template <class T>
  void sign(T& msg, std::vector<uint8_t>& buffer) const {
    msg.hmac_length = kMacBytes;
    msg.hmac.assign(kMacBytes, 0);
    encode_message(msg, buffer);
    const std::size_t covered = buffer.size() - 4 - kMacBytes;
    mac(buffer.data() + kFingerprintBytes, covered - kFingerprintBytes, buffer.data() + covered + 4);
    std::copy(buffer.end() - kMacBytes, buffer.end(), msg.hmac.begin());
  }

  /// Signs `msg` and publishes it on `channel` (errors as publish_message).
  template <class T>
  void publish(LcmInterface& lcm, const std::string& channel, T& msg, std::vector<uint8_t>& buffer) const {
    sign(msg, buffer);
    lcm.publish(channel, buffer.data(), buffer.size());
  }

  /// The bytes the HMAC of `msg` covers (its encoding without fingerprint and hmac fields).
  template <class T>
  static void mac_input(const T& msg, std::vector<uint8_t>& out) {
    T copy = msg;
    copy.hmac_length = 0;  // whatever it carries: the HMAC covers the fields before it
    copy.hmac.clear();
    std::vector<uint8_t> encoded;
    encode_message(copy, encoded);
    out.assign(encoded.begin() + kFingerprintBytes, encoded.end() - 4);
  }

 private:
  template <class T>
  static void encode_message(const T& msg, std::vector<uint8_t>& buffer) {
    const int size = msg.getEncodedSize();
    if (size < kFingerprintBytes + 4) throw EncodeError(std::string("cannot size a ") + T::getTypeName());
    buffer.resize(static_cast<std::size_t>(size));
    if (msg.encode(buffer.data(), 0, size) != size) throw EncodeError(std::string("cannot encode a ") + T::getTypeName());
  }

  RunKey key_;
};

/// What a receiver makes of one raw message (check_and_decode).
enum class Received { ok, malformed, foreign_run, bad_mac };

/// "malformed", "foreign_run", "bad_mac" ("ok" for ok): the reason part of a bad-message kind.
const char* to_string(Received r);

/// The run id of a raw message of our types (the LCM string at byte 16), read without
/// decoding. False when the bytes cannot hold one (too short, length out of range, no NUL).
bool peek_run_id(const uint8_t* data, std::size_t size, std::string& run_id);

/// The receive rule of every authenticated channel (see the file comment): fingerprint of T,
/// run id (is_ours(run_id) decides), HMAC, then strict decode into `msg`. `detail` says why a
/// message is not ok.
template <class T, class IsOurs>
Received check_and_decode(const RawMessage& m, const MessageAuth& auth, IsOurs&& is_ours, T& msg,
                          std::string& detail) {
  if (m.size < static_cast<std::size_t>(kFingerprintBytes)) {
    detail = std::to_string(m.size) + " bytes: too short for a " + T::getTypeName();
    return Received::malformed;
  }
  uint64_t fingerprint = 0;
  for (int i = 0; i < kFingerprintBytes; ++i) fingerprint = fingerprint << 8 | m.data[i];
  if (fingerprint != static_cast<uint64_t>(T::getHash())) {
    detail = "not a " + std::string(T::getTypeName()) + " (type fingerprint differs; " + std::to_string(m.size) +
             " bytes): are both processes built from the same messages/*.lcm?";
    return Received::malformed;
  }
  std::string run_id;
  if (!peek_run_id(m.data, m.size, run_id)) {
    detail = std::string("a ") + T::getTypeName() + " whose run_id field cannot be read (" + std::to_string(m.size) +
             " bytes)";
    return Received::malformed;
  }
  if (!is_ours(run_id)) {
    detail = "run id '" + run_id + "'";
    return Received::foreign_run;
  }
  if (!auth.verify(m)) {
    detail = "HMAC does not verify under the run key (" + std::to_string(m.size) + " bytes)";
    return Received::bad_mac;
  }
  try {
    decode_message(m, msg);
  } catch (const std::exception& e) {  // authentic but undecodable: a sender's bug
    detail = e.what();
    return Received::malformed;
  }
  return Received::ok;
}

}  // namespace messages
