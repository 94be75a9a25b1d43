#include "damper/physical/command_auth.h"

#include <sodium.h>

#include <cstring>
#include <stdexcept>

namespace damper::physical {

namespace {

void put_be(std::vector<uint8_t>& out, uint64_t v, int bytes) {
  for (int i = bytes - 1; i >= 0; --i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

void put_double(std::vector<uint8_t>& out, double d) {
  uint64_t bits;
  std::memcpy(&bits, &d, sizeof bits);
  put_be(out, bits, 8);
}

}  // namespace

void command_mac_input(const hybrid_lcm::actuator_command_t& cmd, std::vector<uint8_t>& out) {
  out.clear();
  put_be(out, static_cast<uint64_t>(cmd.utime), 8);
  put_be(out, static_cast<uint32_t>(cmd.run_id.size() + 1), 4);  // LCM string: length incl. NUL
  out.insert(out.end(), cmd.run_id.begin(), cmd.run_id.end());
  out.push_back(0);
  put_be(out, static_cast<uint64_t>(cmd.sequence), 8);
  put_double(out, cmd.drum_displacement_in);
  put_double(out, cmd.actuator1_position_in);
  put_double(out, cmd.actuator2_position_in);
  out.push_back(static_cast<uint8_t>(cmd.mode));
}

CommandSigner::CommandSigner(const RunKey& key) : key_(key) {
  static_assert(crypto_auth_hmacsha256_KEYBYTES == 32, "run key is 32 bytes");
  if (sodium_init() < 0) throw std::runtime_error("libsodium: sodium_init() failed");
  buffer_.reserve(512);
}

void CommandSigner::sign(hybrid_lcm::actuator_command_t& cmd) {
  command_mac_input(cmd, buffer_);
  cmd.hmac_length = crypto_auth_hmacsha256_BYTES;
  cmd.hmac.resize(crypto_auth_hmacsha256_BYTES);
  crypto_auth_hmacsha256(cmd.hmac.data(), buffer_.data(), buffer_.size(), key_.data());
}

bool CommandSigner::verify(const hybrid_lcm::actuator_command_t& cmd) {
  if (cmd.hmac_length != crypto_auth_hmacsha256_BYTES || cmd.hmac.size() != crypto_auth_hmacsha256_BYTES)
    return false;
  command_mac_input(cmd, buffer_);
  return crypto_auth_hmacsha256_verify(cmd.hmac.data(), buffer_.data(), buffer_.size(), key_.data()) == 0;
}

CommandGate::CommandGate(const RunKey& key, const GateSettings& settings) : signer_(key), settings_(settings) {}

CommandGate::Verdict CommandGate::check(const hybrid_lcm::actuator_command_t& cmd, int64_t now_utime,
                                        std::string& why) {
  if (!signer_.verify(cmd)) {
    why = "forged: HMAC does not verify under the run key (sequence " + std::to_string(cmd.sequence) + ")";
    return Verdict::forged;
  }
  if (!settings_.run_id.empty() && cmd.run_id != settings_.run_id) {
    why = "foreign run: run_id '" + cmd.run_id + "' is not '" + settings_.run_id + "'";
    return Verdict::foreign_run;
  }
  if (any_accepted_ && cmd.sequence <= last_sequence_) {
    why = "replayed: sequence " + std::to_string(cmd.sequence) + " <= last accepted " + std::to_string(last_sequence_);
    return Verdict::replayed;
  }
  const double age_s = 1e-6 * static_cast<double>(now_utime - cmd.utime);
  if (age_s > settings_.max_age_s || -age_s > settings_.max_future_s) {
    why = "stale: command sequence " + std::to_string(cmd.sequence) + " is " + std::to_string(age_s * 1e3) +
          " ms old (allowed " + std::to_string(-settings_.max_future_s * 1e3) + " to " +
          std::to_string(settings_.max_age_s * 1e3) + " ms)";
    return Verdict::stale;
  }
  if (settings_.run_id.empty()) settings_.run_id = cmd.run_id;
  last_sequence_ = cmd.sequence;
  any_accepted_ = true;
  why.clear();
  return Verdict::accepted;
}

const char* to_string(CommandGate::Verdict v) {
  switch (v) {
    case CommandGate::Verdict::accepted: return "accepted";
    case CommandGate::Verdict::forged: return "forged";
    case CommandGate::Verdict::foreign_run: return "foreign_run";
    case CommandGate::Verdict::replayed: return "replayed";
    case CommandGate::Verdict::stale: return "stale";
  }
  return "?";
}

}  // namespace damper::physical
