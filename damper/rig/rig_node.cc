#include "damper/rig/rig_node.h"

#include "damper/data/brfd_data.h"
#include "damper/physical/realtime.h"

#include <nlohmann/json.hpp>

#include <csignal>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>

namespace damper::rig {

namespace {

using hybrid_lcm::actuator_command_t;
using physical::CommandGate;

volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_signal(int) { g_stop = 1; }

messages::Duration seconds(double s) { return messages::seconds_to_duration(s); }

}  // namespace

RigNode::RigNode(messages::LcmInterface& lcm, const RigNodeOptions& o)
    : RigNode(lcm, o, physical::read_key_file(o.key_file)) {}

RigNode::RigNode(messages::LcmInterface& lcm, const RigNodeOptions& o, const physical::RunKey& key)
    : lcm_(lcm),
      o_(o),
      c_(o.config),
      period_(1.0 / o.config.rate_hz),
      gate_(key, physical::GateSettings{o.run_id, o.config.auth.max_command_age_s, o.config.auth.max_future_s}),
      frame_auth_(key),
      sim_(o.config) {
  if (!c_.replay.file.empty()) {
    replay_ = std::make_unique<BrfdTest>(read_brfd_test(c_.replay.file));
    if (std::abs(replay_->dt_s - period_) > 1e-9)
      throw std::runtime_error("replay file " + c_.replay.file + " is sampled every " + std::to_string(replay_->dt_s) +
                               " s, the rig runs at " + std::to_string(period_) + " s");
  }
  target_ = {c_.initial.drum_in, c_.initial.actuator1_in, c_.initial.actuator2_in};
  frame_.run_id = o.run_id;
  frame_.last_rejection.reserve(512);
  buffer_.reserve(1024);
  // Nothing unauthenticated is decoded (messages/message_auth.h): a forged hmac_length of
  // 2^31 - 1 would make LCM's decoder allocate it. The gate's first rule is the HMAC anyway.
  lcm_.subscribe(o.channels.actuator_command(), [this](const messages::RawMessage& raw) {
    if (!frame_auth_.verify(raw)) return on_forged(raw.size, lcm_.utime());
    try {
      messages::decode_message(raw, cmd_);
    } catch (const messages::DecodeError& e) {
      return on_undecodable(e.what(), lcm_.utime());
    }
    on_command(cmd_, lcm_.utime());
  });
  if (!o.log_dir.empty()) {
    std::filesystem::create_directories(o.log_dir);
    const std::string path = (std::filesystem::path(o.log_dir) / "rig-commands.csv").string();
    log_ = std::fopen(path.c_str(), "w");
    if (!log_) throw std::runtime_error("cannot write " + path);
    std::setvbuf(log_, nullptr, _IOFBF, 1 << 20);
    std::fprintf(log_, "rx_utime,utime,sequence,mode,drum_in,actuator1_in,actuator2_in,verdict,within_rig_limits,reason\n");
    std::ofstream(std::filesystem::path(o.log_dir) / "rig-config.yaml") << rig_config_to_yaml(c_);
  }
  started_ = next_tick_ = lcm_.now();
  std::cout << "brfd-rig: " << (replay_ ? "replaying " + c_.replay.file : std::string("emulating the BRFD")) << " at "
            << c_.rate_hz << " Hz on '" << o_.channels.sensor_frame() << "', commands on '"
            << o_.channels.actuator_command() << "'" << std::endl;
}

RigNode::~RigNode() {
  if (log_) std::fclose(log_);
}

bool RigNode::finished() const { return g_stop || stop_requested_ || end_requested_ || done_; }

void RigNode::advance(TimePoint now) {
  if (finished() || now < next_tick_) return;
  const double late = messages::seconds_between(next_tick_, now);
  if (late > max_lateness_s_) {
    max_lateness_s_ = late;
    max_lateness_frame_ = frames_ + 1;
  }
  if (now - next_tick_ > seconds(8 * period_)) {  // descheduled: resynchronise, do not burst
    ++overruns_;
    next_tick_ = now;
  }
  tick();
  next_tick_ += seconds(period_);
  if (accepted_ > 0 && now - last_accepted_ > seconds(c_.idle_exit_s)) {
    exit_reason_ = "no accepted command for " + std::to_string(c_.idle_exit_s) + " s (idle_exit_s)";
    done_ = true;
  } else if (received_ == 0 && now - started_ > seconds(c_.start_timeout_s)) {
    exit_reason_ = "no command at all within start_timeout_s";
    code_ = 1;
    done_ = true;
  }
}

void RigNode::transport_failed(const std::string& why) {
  exit_reason_ = why;
  code_ = 1;
  done_ = true;
}

int RigNode::finish() {
  if (end_requested_) exit_reason_ = "MODE_END command: the run is over";
  if (g_stop || stop_requested_) exit_reason_ = "signal";
  write_summary();
  std::cout << "brfd-rig: exit: " << exit_reason_ << "; " << received_ << " commands received, " << accepted_
            << " accepted, " << rejected_ << " rejected, " << out_of_limit_received_ << " out of the rig's limits; "
            << frames_ << " frames" << std::endl;
  return code_;
}

void RigNode::on_undecodable(const std::string& what, int64_t rx) {
  ++received_;
  reject("undecodable: not an actuator_command_t of this protocol version: " + what);
  log_row(rx, nullptr, "undecodable", -1);
}

void RigNode::on_forged(std::size_t bytes, int64_t rx) {
  ++received_;
  ++by_kind_[physical::to_string(CommandGate::Verdict::forged)];
  reject("forged: HMAC does not verify under the run key (" + std::to_string(bytes) + " bytes, not decoded)");
  log_row(rx, nullptr, physical::to_string(CommandGate::Verdict::forged), -1);
}

void RigNode::on_command(const actuator_command_t& cmd, int64_t rx) {
  ++received_;
  max_abs_drum_received_ = std::max(max_abs_drum_received_, std::abs(cmd.drum_displacement_in));
  // The rig's own limits, for every command that arrives (the log is the proof that none
  // beyond them reached the rig).
  std::string limit_why;
  const bool within = within_limits(cmd, limit_why);
  if (!within) ++out_of_limit_received_;
  const CommandGate::Verdict v = gate_.check(cmd, rx, why_);
  if (v != CommandGate::Verdict::accepted) {
    ++by_kind_[physical::to_string(v)];
    reject(why_);
    log_row(rx, &cmd, physical::to_string(v), within ? 1 : 0);
    return;
  }
  if (!within) {
    ++by_kind_["out_of_limit"];
    reject("out of limit: " + limit_why);
    log_row(rx, &cmd, "out_of_limit", 0);
    return;
  }
  if (accepted_ > 0) {
    const double dseq = static_cast<double>(std::max<int64_t>(1, cmd.sequence - last_sequence_));
    max_rate_accepted_ = std::max(max_rate_accepted_, std::abs(cmd.drum_displacement_in - target_.drum_in) * c_.rate_hz / dseq);
  }
  ++accepted_;
  last_sequence_ = cmd.sequence;
  last_accepted_ = lcm_.now();
  target_ = {cmd.drum_displacement_in, cmd.actuator1_position_in, cmd.actuator2_position_in};
  max_abs_drum_accepted_ = std::max(max_abs_drum_accepted_, std::abs(cmd.drum_displacement_in));
  if (frame_.run_id.empty()) frame_.run_id = gate_.run_id();
  if (cmd.mode == actuator_command_t::MODE_END) end_requested_ = true;
  log_row(rx, &cmd, "accepted", 1);
}

bool RigNode::within_limits(const actuator_command_t& c, std::string& why) const {
  char b[200];
  const RigLimits& l = c_.limits;
  if (!std::isfinite(c.drum_displacement_in) || std::abs(c.drum_displacement_in) > l.stroke_in) {
    std::snprintf(b, sizeof b, "drum command %.4f in beyond the rig stroke +-%.4f in", c.drum_displacement_in, l.stroke_in);
    why = b;
    return false;
  }
  if (accepted_ > 0) {
    const double dseq = static_cast<double>(std::max<int64_t>(1, c.sequence - last_sequence_));
    const double rate = std::abs(c.drum_displacement_in - target_.drum_in) * c_.rate_hz / dseq;
    if (rate > l.velocity_in_per_s) {
      std::snprintf(b, sizeof b, "drum command rate %.3f in/s beyond the rig limit %.3f in/s", rate, l.velocity_in_per_s);
      why = b;
      return false;
    }
  }
  for (double a : {c.actuator1_position_in, c.actuator2_position_in}) {
    if (!std::isfinite(a) || a < l.actuator_min_in || a > l.actuator_max_in) {
      std::snprintf(b, sizeof b, "electric actuator command %.4f in outside [%.4f, %.4f] in", a, l.actuator_min_in,
                    l.actuator_max_in);
      why = b;
      return false;
    }
  }
  return true;
}

void RigNode::reject(const std::string& why) {
  ++rejected_;
  frame_.last_rejection = why;
  if (rejected_ <= 20 || rejected_ % 1000 == 0)
    std::cerr << "brfd-rig: rejected command (" << rejected_ << " so far): " << why << "\n";
}

void RigNode::log_row(int64_t rx, const actuator_command_t* c, const char* verdict, int within) {
  if (!log_) return;
  if (c) {
    std::fprintf(log_, "%lld,%lld,%lld,%d,%.10g,%.10g,%.10g,%s,%d,\"%s\"\n", static_cast<long long>(rx),
                 static_cast<long long>(c->utime), static_cast<long long>(c->sequence), c->mode,
                 c->drum_displacement_in, c->actuator1_position_in, c->actuator2_position_in, verdict, within,
                 std::strcmp(verdict, "accepted") == 0 ? "" : frame_.last_rejection.c_str());
  } else {
    std::fprintf(log_, "%lld,,,,,,,%s,%d,\"%s\"\n", static_cast<long long>(rx), verdict, within,
                 frame_.last_rejection.c_str());
  }
}

void RigNode::tick() {
  RigReading r;
  if (replay_) {
    const std::size_t n = replay_->size();
    std::size_t i = replay_index_;
    if (i >= n) i = c_.replay.loop ? (replay_index_ = 0) : n - 1;
    r.drum_in = replay_->drum_disp_in[i];
    r.friction_kip = replay_->force_kip[i];
    r.actuator1_in = replay_->has_actuator_positions ? replay_->actuator1_in[i] : c_.initial.actuator1_in;
    r.actuator2_in = replay_->has_actuator_positions ? replay_->actuator2_in[i] : c_.initial.actuator2_in;
    r.actuator1_force_lb = replay_->actuator1_force_lb[i];
    r.actuator2_force_lb = replay_->actuator2_force_lb[i];
    ++replay_index_;
  } else {
    sim_.step(target_);
    r = sim_.reading();
  }
  frame_.utime = lcm_.utime();
  frame_.sequence = ++frames_;
  frame_.command_sequence = accepted_ > 0 ? last_sequence_ : 0;
  frame_.drum_displacement_in = r.drum_in;
  frame_.friction_force_kip = r.friction_kip;
  frame_.actuator1_position_in = r.actuator1_in;
  frame_.actuator2_position_in = r.actuator2_in;
  frame_.actuator1_force_lb = r.actuator1_force_lb;
  frame_.actuator2_force_lb = r.actuator2_force_lb;
  frame_.rejected_commands = static_cast<int32_t>(rejected_);
  frame_auth_.publish(lcm_, o_.channels.sensor_frame(), frame_, buffer_);
}


void RigNode::write_summary() {
  if (log_) std::fflush(log_);
  if (o_.log_dir.empty()) return;
  nlohmann::json j;
  j["exit_reason"] = exit_reason_;
  j["run_id"] = gate_.run_id();
  j["mode"] = replay_ ? "replay" : "emulate";
  j["commands_received"] = received_;
  j["commands_accepted"] = accepted_;
  j["commands_rejected"] = rejected_;
  nlohmann::json kinds = nlohmann::json::object();
  for (const auto& [k, n] : by_kind_) kinds[k] = n;
  j["rejected_by_kind"] = kinds;
  j["last_rejection"] = frame_.last_rejection;
  j["out_of_limit_received"] = out_of_limit_received_;
  j["max_abs_drum_command_received_in"] = max_abs_drum_received_;
  j["max_abs_drum_command_accepted_in"] = max_abs_drum_accepted_;
  j["max_drum_command_rate_accepted_in_per_s"] = max_rate_accepted_;
  j["frames_published"] = frames_;
  j["tick_overruns"] = overruns_;
  j["max_tick_lateness_ms"] = 1e3 * max_lateness_s_;
  j["max_tick_lateness_frame"] = max_lateness_frame_;
  j["reversals"] = sim_.reversals();
  j["limits"] = {{"stroke_in", c_.limits.stroke_in},
                 {"velocity_in_per_s", c_.limits.velocity_in_per_s},
                 {"actuator_min_in", c_.limits.actuator_min_in},
                 {"actuator_max_in", c_.limits.actuator_max_in}};
  j["effects"] = {{"hydraulic_delay_lag", c_.hydraulic.enabled},
                  {"delay_s", c_.hydraulic.delay_s},
                  {"lag_time_constant_s", c_.hydraulic.lag_time_constant_s},
                  {"noise", c_.noise.enabled},
                  {"backlash", c_.backlash.enabled},
                  {"residual_force", c_.residual_force.enabled}};
  std::ofstream(std::filesystem::path(o_.log_dir) / "rig-summary.json") << std::setw(2) << j << "\n";
}


int run_rig(const RigNodeOptions& options) {
  // Before LCM starts its receive thread, so that thread inherits the real-time priority.
  physical::enter_realtime(options.config.realtime_priority, "brfd-rig");
  std::signal(SIGTERM, on_signal);
  std::signal(SIGINT, on_signal);
  messages::LcmTransport lcm(options.url, options.lab_network);
  RigNode node(lcm, options);
  try {
    messages::run_loop(lcm, node);
  } catch (const std::exception& e) {  // the transport failed, or a handler threw (after lcm_handle)
    node.transport_failed(std::string("LCM handle failed: ") + e.what());
  }
  return node.finish();
}

}  // namespace damper::rig
