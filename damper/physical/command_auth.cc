#include "damper/physical/command_auth.h"


namespace damper::physical {

void command_mac_input(const hybrid_lcm::actuator_command_t& cmd, std::vector<uint8_t>& out) {
  messages::MessageAuth::mac_input(cmd, out);
}

CommandSigner::CommandSigner(const RunKey& key) : auth_(key) { buffer_.reserve(512); }

void CommandSigner::sign(hybrid_lcm::actuator_command_t& cmd) { auth_.sign(cmd, buffer_); }

bool CommandSigner::verify(const hybrid_lcm::actuator_command_t& cmd) {
  if (cmd.hmac_length != messages::kMacBytes || cmd.hmac.size() != static_cast<std::size_t>(messages::kMacBytes))
    return false;
  const int size = cmd.getEncodedSize();
  buffer_.resize(static_cast<std::size_t>(size));
  if (cmd.encode(buffer_.data(), 0, size) != size) return false;
  return auth_.verify(buffer_.data(), buffer_.size());
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
