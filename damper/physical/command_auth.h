#pragma once
/// @file command_auth.h
/// Authentication of actuator commands (docs/physical.md, "Command authentication"):
/// every actuator_command_t carries a sequence number and an HMAC-SHA256 (libsodium
/// crypto_auth_hmacsha256) under the per-run key of messages/run_key.h, computed as for every
/// message of the run (messages/message_auth.h, one implementation).
///
/// The HMAC covers the command's fields utime, run_id, sequence, drum_displacement_in,
/// actuator1_position_in, actuator2_position_in, mode in this order, each encoded as LCM
/// encodes it (big-endian; int64 8 bytes, double IEEE-754 8 bytes, int8 1 byte, string as an
/// int32 length that counts a terminating NUL, the bytes, then the NUL). The 8-byte LCM type
/// fingerprint and the hmac fields themselves are not covered.
///
/// The receiving side (lab bridge, brfd-rig) accepts a command only if (CommandGate):
///   1. its HMAC verifies under the run key (else "forged"),
///   2. its run_id is the run's (else "foreign run"),
///   3. its sequence is greater than the last accepted one (else "replayed"),
///   4. its utime is no older than max_age_s and no further ahead than max_future_s of the
///      receiver's clock (else "stale").

#include "messages/message_auth.h"
#include "messages/run_key.h"
#include "hybrid_lcm/actuator_command_t.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace damper::physical {

// The run key lives with the messages it authenticates (messages/run_key.h).
using messages::generate_run_key;
using messages::KeyFileError;
using messages::read_key_file;
using messages::RunKey;
using messages::write_key_file;

/// Bytes the HMAC covers (see the file comment). `out` is resized; allocation-free once it
/// has the capacity.
void command_mac_input(const hybrid_lcm::actuator_command_t& cmd, std::vector<uint8_t>& out);

/// Signs and verifies commands under one key.
class CommandSigner {
 public:
  /// Initialises libsodium; throws std::runtime_error if it cannot.
  explicit CommandSigner(const RunKey& key);
  /// Sets cmd.hmac_length = 32 and cmd.hmac to the HMAC of the other fields.
  void sign(hybrid_lcm::actuator_command_t& cmd);
  /// True when cmd carries a 32-byte HMAC that verifies (constant-time compare).
  bool verify(const hybrid_lcm::actuator_command_t& cmd);

 private:
  messages::MessageAuth auth_;
  std::vector<uint8_t> buffer_;
};

/// Acceptance rules of the receiving side (points 1-4 of the file comment).
struct GateSettings {
  std::string run_id;            ///< "" = adopt the run id of the first authentic command
  double max_age_s = 0.05;       ///< older commands are stale
  double max_future_s = 0.01;    ///< commands stamped further ahead than this are stale
};

class CommandGate {
 public:
  enum class Verdict { accepted, forged, foreign_run, replayed, stale };

  CommandGate(const RunKey& key, const GateSettings& settings);
  /// Checks one received command at receiver time now_utime (µs since the epoch). On
  /// acceptance the sequence becomes the last accepted one. `why` is filled for rejections
  /// with a sentence naming the rule, e.g. "replayed: sequence 12 <= last accepted 40".
  Verdict check(const hybrid_lcm::actuator_command_t& cmd, int64_t now_utime, std::string& why);

  int64_t last_accepted_sequence() const { return last_sequence_; }
  const std::string& run_id() const { return settings_.run_id; }

 private:
  CommandSigner signer_;
  GateSettings settings_;
  int64_t last_sequence_ = -1;
  bool any_accepted_ = false;
};

const char* to_string(CommandGate::Verdict v);

}  // namespace damper::physical
