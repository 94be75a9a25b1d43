#include "messages/substructure_endpoint.h"

#include <iostream>

namespace messages {

SubstructureEndpoint::SubstructureEndpoint(LcmInterface& lcm, const EndpointSettings& settings, Listener& listener)
    : lcm_(lcm), s_(settings), listener_(listener), run_id_(settings.run_id) {
  buffer_.reserve(1024);
  feedback_.message.reserve(512);
  feedback_.num_dampers = 0;
  feedback_.step = -1;
  feedback_.status = hybrid_lcm::force_feedback_t::STATUS_OK;
  heartbeat_.sender = s_.sender;
  heartbeat_.sequence = 0;
  next_heartbeat_ = lcm_.now();  // the first heartbeat goes out at once
  last_command_ = lcm_.now();
  const std::string who = s_.sender;
  auto on_error = [who](const DecodeError& e, const RawMessage&) { std::cerr << who << ": " << e.what() << "\n"; };
  subscribe_message<hybrid_lcm::run_control_t>(
      lcm_, s_.channels.run_control(), control_scratch_,
      [this](hybrid_lcm::run_control_t& m, const RawMessage&) { on_control(m); }, on_error);
  subscribe_message<hybrid_lcm::drift_command_t>(
      lcm_, s_.channels.drift_command(), drift_scratch_,
      [this](hybrid_lcm::drift_command_t& m, const RawMessage&) { on_drift(m); }, on_error);
}

void SubstructureEndpoint::on_control(hybrid_lcm::run_control_t& msg) {
  if (!run_id_.empty() && msg.run_id != run_id_) return;
  if (msg.command == hybrid_lcm::run_control_t::COMMAND_START && run_id_.empty()) run_id_ = msg.run_id;
  listener_.on_run_control(msg, lcm_.now());
}

void SubstructureEndpoint::on_drift(hybrid_lcm::drift_command_t& cmd) {
  if (run_id_.empty() || cmd.run_id != run_id_) return;
  last_command_ = lcm_.now();
  listener_.on_drift(cmd, last_command_);
}

void SubstructureEndpoint::advance(TimePoint now) {
  if (now < next_heartbeat_) return;
  publish_heartbeat();
  next_heartbeat_ = now + seconds_to_duration(s_.heartbeat_period_s);
}

void SubstructureEndpoint::publish_heartbeat() {
  heartbeat_.utime = lcm_.utime();
  heartbeat_.run_id = run_id_;
  heartbeat_.state = listener_.heartbeat_state();
  publish_message(lcm_, s_.channels.heartbeat(), heartbeat_, buffer_);
  ++heartbeat_.sequence;
}

void SubstructureEndpoint::prepare_reply(int num_dampers) {
  feedback_.run_id = run_id_;
  feedback_.num_dampers = num_dampers;
  feedback_.force_kip.assign(static_cast<std::size_t>(num_dampers), 0.0);
  feedback_.measured_drift_in.assign(static_cast<std::size_t>(num_dampers), 0.0);
  feedback_.actuator1_position_in.assign(static_cast<std::size_t>(num_dampers), 0.0);  // the node fills them
  feedback_.actuator2_position_in.assign(static_cast<std::size_t>(num_dampers), 0.0);
}

void SubstructureEndpoint::reply_ok(int64_t step) {
  feedback_.step = step;
  feedback_.status = hybrid_lcm::force_feedback_t::STATUS_OK;
  feedback_.message.clear();
  feedback_.utime = lcm_.utime();
  publish_message(lcm_, s_.channels.force_feedback(), feedback_, buffer_);
  last_answered_step_ = step;
}

void SubstructureEndpoint::reply_status(int64_t step, int8_t status, const std::string& message) {
  feedback_.run_id = run_id_;
  feedback_.step = step;
  feedback_.status = status;
  feedback_.message = message;
  feedback_.utime = lcm_.utime();
  publish_message(lcm_, s_.channels.force_feedback(), feedback_, buffer_);
}

bool SubstructureEndpoint::answer_repeat(int64_t step) {
  if (step != last_answered_step_ || last_answered_step_ < 0) return false;
  publish_message(lcm_, s_.channels.force_feedback(), feedback_, buffer_);
  return true;
}

}  // namespace messages
