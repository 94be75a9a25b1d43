#include "messages/substructure_endpoint.h"

#include <iostream>

namespace messages {

SubstructureEndpoint::SubstructureEndpoint(LcmInterface& lcm, const EndpointSettings& settings, Listener& listener)
    : lcm_(lcm),
      s_(settings),
      listener_(listener),
      run_id_(settings.run_id),
      auth_(settings.key),
      bad_(settings.sender, settings.on_bad_message) {
  buffer_.reserve(1024);
  feedback_.message.reserve(512);
  feedback_.num_dampers = 0;
  feedback_.step = -1;
  feedback_.status = hybrid_lcm::force_feedback_t::STATUS_OK;
  feedback_.hmac.reserve(kMacBytes);
  heartbeat_.sender = s_.sender;
  heartbeat_.sequence = 0;
  heartbeat_.hmac.reserve(kMacBytes);
  next_heartbeat_ = lcm_.now();  // the first heartbeat goes out at once
  last_command_ = lcm_.now();
  lcm_.subscribe(s_.channels.run_control(), [this](const RawMessage& raw) {
    if (accept("RUN_CONTROL", raw, control_scratch_, last_control_sequence_)) on_control(control_scratch_);
  });
  lcm_.subscribe(s_.channels.drift_command(), [this](const RawMessage& raw) {
    if (accept("DRIFT_COMMAND", raw, drift_scratch_, last_drift_sequence_)) on_drift(drift_scratch_);
  });
}

template <class T>
bool SubstructureEndpoint::accept(const char* channel, const RawMessage& raw, T& msg, int64_t& last_sequence) {
  const std::string ch(channel);
  // Another run's traffic (its key is not ours) is foreign whatever its HMAC. Before the first
  // START (no run id yet) only a START can be ours; a drift command is foreign.
  const bool is_control = ch == "RUN_CONTROL";
  std::string detail;
  const Received r = check_and_decode(
      raw, auth_,
      [&](const std::string& id) { return run_id_.empty() ? (is_control && !id.empty()) : id == run_id_; }, msg,
      detail);
  if (r != Received::ok) {
    bad_.report(ch + "/" + to_string(r), detail + (r == Received::foreign_run ? " is not '" + run_id_ + "'" : ""), false);
    return false;
  }
  const int64_t sequence = msg.sequence;
  if (sequence <= last_sequence) {
    bad_.report(ch + "/replayed",
                "sequence " + std::to_string(sequence) + " <= last accepted " + std::to_string(last_sequence), false);
    return false;
  }
  last_sequence = sequence;
  return true;
}

void SubstructureEndpoint::on_control(hybrid_lcm::run_control_t& msg) {
  if (msg.command == hybrid_lcm::run_control_t::COMMAND_START && run_id_.empty()) run_id_ = msg.run_id;
  listener_.on_run_control(msg, lcm_.now());
}

void SubstructureEndpoint::on_drift(hybrid_lcm::drift_command_t& cmd) {
  last_command_ = lcm_.now();
  last_drift_step_ = cmd.step;
  if (!bad_.stop_reason().empty()) {  // policy stop: the server learns why at once
    reply_status(cmd.step, hybrid_lcm::force_feedback_t::STATUS_FAULT, bad_.stop_reason());
    return;
  }
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
  ++heartbeat_.sequence;  // 1, 2, ...: the receiver wants it to increase
  auth_.publish(lcm_, s_.channels.heartbeat(), heartbeat_, buffer_);
}

void SubstructureEndpoint::prepare_reply(int num_dampers) {
  feedback_.run_id = run_id_;
  feedback_.num_dampers = num_dampers;
  feedback_.force_kip.assign(static_cast<std::size_t>(num_dampers), 0.0);
  feedback_.measured_drift_in.assign(static_cast<std::size_t>(num_dampers), 0.0);
  feedback_.actuator1_position_in.assign(static_cast<std::size_t>(num_dampers), 0.0);  // the node fills them
  feedback_.actuator2_position_in.assign(static_cast<std::size_t>(num_dampers), 0.0);
}

void SubstructureEndpoint::publish_reply() {
  // Bound to the command answered: its step and its sequence (0 if that command never came).
  feedback_.command_sequence = feedback_.step == last_drift_step_ ? last_drift_sequence_ : 0;
  feedback_.sequence = ++sequence_;
  feedback_.utime = lcm_.utime();
  auth_.publish(lcm_, s_.channels.force_feedback(), feedback_, buffer_);
}

void SubstructureEndpoint::reply_ok(int64_t step) {
  feedback_.step = step;
  feedback_.status = hybrid_lcm::force_feedback_t::STATUS_OK;
  feedback_.message.clear();
  publish_reply();
  last_answered_step_ = step;
}

void SubstructureEndpoint::reply_status(int64_t step, int8_t status, const std::string& message) {
  feedback_.run_id = run_id_;
  feedback_.step = step;
  feedback_.status = status;
  feedback_.message = message;
  publish_reply();
}

bool SubstructureEndpoint::answer_repeat(int64_t step) {
  if (step != last_answered_step_ || last_answered_step_ < 0) return false;
  publish_reply();  // same forces, bound to the repeated command's sequence
  return true;
}

}  // namespace messages
