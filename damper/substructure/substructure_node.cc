#include "damper/substructure/substructure_node.h"

#include <cmath>
#include <iostream>

namespace damper {

SubstructureNode::SubstructureNode(messages::LcmInterface& lcm, const SubstructureNodeOptions& o)
    : o_(o), endpoint_(lcm, messages::endpoint_settings_of(o, o.key), *this) {}

void SubstructureNode::advance(messages::TimePoint now) {
  if (finished()) return;
  endpoint_.advance(now);  // heartbeat when due
  if (started_ && endpoint_.command_silence_s(now) > o_.command_watchdog_s) {
    std::cerr << "brfd-substructure: no drift command on '" << o_.channels.drift_command() << "' for "
              << o_.command_watchdog_s << " s: the server is gone, exiting\n";
    exit_code_ = 1;
  }
}

messages::TimePoint SubstructureNode::next_deadline(messages::TimePoint now) const {
  messages::TimePoint d = std::min(endpoint_.next_heartbeat(), now + std::chrono::milliseconds(20));
  if (started_) d = std::min(d, endpoint_.last_command_time() + messages::seconds_to_duration(o_.command_watchdog_s) +
                                    std::chrono::milliseconds(1));
  return d;
}

int8_t SubstructureNode::heartbeat_state() const {
  return !started_ ? hybrid_lcm::heartbeat_t::STATE_IDLE
         : steps_ == 0 ? hybrid_lcm::heartbeat_t::STATE_READY
                       : hybrid_lcm::heartbeat_t::STATE_RUNNING;
}

void SubstructureNode::on_run_control(const hybrid_lcm::run_control_t& msg, messages::TimePoint now) {
  if (msg.command == hybrid_lcm::run_control_t::COMMAND_START) {
    if (!started_) {
      if (msg.num_dampers < 1 || msg.num_dampers > 64 || !(msg.dt_s > 0.0 && msg.dt_s < 1.0)) {
        std::cerr << "brfd-substructure: START on '" << o_.channels.run_control() << "' has num_dampers "
                  << msg.num_dampers << " and dt_s " << msg.dt_s << ": out of range, ignored\n";
        return;
      }
      bank_ = DamperBank(*make_damper_model(o_.model), msg.num_dampers);
      drive_ = ActuatorDrive(o_.model.electric_actuators, bank_);
      dt_s_ = msg.dt_s;
      endpoint_.prepare_reply(msg.num_dampers);
      for (int k = 0; k < bank_.size(); ++k) {
        endpoint_.reply().actuator1_position_in[static_cast<std::size_t>(k)] = bank_.input(k).actuator1_in;
        endpoint_.reply().actuator2_position_in[static_cast<std::size_t>(k)] = bank_.input(k).actuator2_in;
      }
      started_ = true;
      endpoint_.arm_watchdog(now);
    }
    endpoint_.publish_heartbeat();  // the server waits for this before the first step
  } else if (msg.command == hybrid_lcm::run_control_t::COMMAND_STOP) {
    exit_code_ = 0;
  } else if (msg.command == hybrid_lcm::run_control_t::COMMAND_ABORT) {
    std::cerr << "brfd-substructure: run aborted by the server: " << msg.reason << "\n";
    exit_code_ = 3;
  }
}

void SubstructureNode::on_drift(hybrid_lcm::drift_command_t& cmd, messages::TimePoint) {
  if (!started_) return;
  if (endpoint_.answer_repeat(cmd.step)) return;  // a repeated command: answer again, do not step twice
  if (cmd.num_dampers != bank_.size()) {
    fault(cmd.step, "drift command on '" + o_.channels.drift_command() + "' has " + std::to_string(cmd.num_dampers) +
                        " dampers, the run started with " + std::to_string(bank_.size()));
    return;
  }
  for (std::size_t k = 0; k < static_cast<std::size_t>(bank_.size()); ++k) {
    const double d = cmd.drift_in[k], v = cmd.drift_velocity_in_per_s[k];
    if (!std::isfinite(d) || !std::isfinite(v) || std::abs(d) > o_.max_drum_displacement_in ||
        std::abs(v) > o_.max_drum_velocity_in_per_s ||
        (cmd.actuator_targets_valid &&
         (!std::isfinite(cmd.actuator1_target_in[k]) || !std::isfinite(cmd.actuator2_target_in[k])))) {
      fault(cmd.step, "drift command step " + std::to_string(cmd.step) + " damper " + std::to_string(k + 1) +
                          ": drum displacement " + std::to_string(d) + " in / velocity " + std::to_string(v) +
                          " in/s outside the limits +-" + std::to_string(o_.max_drum_displacement_in) + " in, +-" +
                          std::to_string(o_.max_drum_velocity_in_per_s) + " in/s, or a non-finite actuator target");
      return;
    }
  }
  hybrid_lcm::force_feedback_t& reply = endpoint_.reply();
  const bool targets = cmd.actuator_targets_valid != 0;
  for (int k = 0; k < bank_.size(); ++k) {
    const auto kk = static_cast<std::size_t>(k);
    // The electric actuators follow the controller's targets through the actuator model
    // (stroke, rate, lag; damper/model/electric_actuator.h); without targets they hold x'.
    if (targets) drive_.follow(bank_, k, cmd.actuator1_target_in[kk], cmd.actuator2_target_in[kk], dt_s_);
    reply.force_kip[kk] = o_.echo ? 0.0 : bank_.step(k, cmd.drift_in[kk], cmd.drift_velocity_in_per_s[kk], dt_s_);
    reply.measured_drift_in[kk] = cmd.drift_in[kk];
    reply.actuator1_position_in[kk] = bank_.input(k).actuator1_in;
    reply.actuator2_position_in[kk] = bank_.input(k).actuator2_in;
  }
  ++steps_;
  endpoint_.reply_ok(cmd.step);
}

void SubstructureNode::fault(int64_t step, const std::string& why) {
  std::cerr << "brfd-substructure: " << why << "\n";
  endpoint_.reply_status(step, hybrid_lcm::force_feedback_t::STATUS_FAULT, why);
}

int run_substructure_node(const SubstructureNodeOptions& options) {
  messages::LcmTransport lcm(options.url, options.lab_network);
  SubstructureNode node(lcm, options);
  try {
    messages::run_loop(lcm, node);
  } catch (const std::exception& e) {  // the transport failed, or a handler threw (after lcm_handle)
    std::cerr << "brfd-substructure: LCM handle failed on '" << options.url << "': " << e.what() << "\n";
    if (!options.results_dir.empty())
      node.bad_messages().write_json_file(options.results_dir + "/" + messages::kSubstructureMessagesFile);
    return 1;
  }
  if (!options.results_dir.empty())
    node.bad_messages().write_json_file(options.results_dir + "/" + messages::kSubstructureMessagesFile);
  return node.exit_code();
}

}  // namespace damper
