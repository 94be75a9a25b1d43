#pragma once
/// @file substructure_endpoint.h
/// The node side of the server <-> substructure protocol (README "LCM, the network rule and
/// the lab"), shared by brfd-substructure's virtual node (damper/substructure) and its
/// physical node (damper/physical):
///  - run-control handshake: START/STOP/ABORT on <prefix>RUN_CONTROL, strictly decoded,
///    filtered by run id (an empty run id adopts the first START's);
///  - heartbeat on <prefix>HEARTBEAT every heartbeat_period_s (and at once on request), with
///    the state the node reports;
///  - command watchdog: the time of the last drift command of this run;
///  - replies: one force_feedback_t per step; a repeated command is answered again with the
///    same reply, without stepping twice.
/// The endpoint decides nothing about the run: it calls the node (Listener) for every START,
/// STOP, ABORT and drift command of its run, and publishes what the node asks. Every publish
/// goes through publish_message (return codes checked); undecodable messages are reported
/// on stderr naming channel and type, and dropped.

#include "hybrid_lcm/drift_command_t.hpp"
#include "hybrid_lcm/force_feedback_t.hpp"
#include "hybrid_lcm/heartbeat_t.hpp"
#include "hybrid_lcm/run_control_t.hpp"
#include "messages/transport.h"

#include <string>
#include <vector>

namespace messages {

struct EndpointSettings {
  Channels channels;
  std::string run_id;                   ///< answer only this run ("" = adopt the first START)
  std::string sender = "brfd-substructure";
  double heartbeat_period_s = 0.2;
};

class SubstructureEndpoint {
 public:
  class Listener {
   public:
    virtual ~Listener() = default;
    /// START, STOP or ABORT of this run (a START also for a repeated one).
    virtual void on_run_control(const hybrid_lcm::run_control_t& msg, TimePoint now) = 0;
    /// A drift command of this run (the watchdog time is already updated).
    virtual void on_drift(hybrid_lcm::drift_command_t& cmd, TimePoint now) = 0;
    /// The state the next heartbeat reports (heartbeat_t::STATE_*).
    virtual int8_t heartbeat_state() const = 0;
  };

  /// Subscribes to run control and drift commands on `lcm`.
  SubstructureEndpoint(LcmInterface& lcm, const EndpointSettings& settings, Listener& listener);
  SubstructureEndpoint(const SubstructureEndpoint&) = delete;
  SubstructureEndpoint& operator=(const SubstructureEndpoint&) = delete;

  const EndpointSettings& settings() const { return s_; }
  const std::string& run_id() const { return run_id_; }

  /// Publishes a heartbeat when one is due. Call from the loop.
  void advance(TimePoint now);
  /// When the next heartbeat is due.
  TimePoint next_heartbeat() const { return next_heartbeat_; }
  /// Publishes a heartbeat now (after a state change; the server waits for READY).
  void publish_heartbeat();

  /// The last drift command of this run arrived at this time (re-armed by arm_watchdog).
  TimePoint last_command_time() const { return last_command_; }
  void arm_watchdog(TimePoint now) { last_command_ = now; }
  /// Seconds since the last drift command of this run.
  double command_silence_s(TimePoint now) const { return seconds_between(last_command_, now); }

  /// Sizes the reply for `num_dampers` (forces and measured drifts zero). Call on START.
  void prepare_reply(int num_dampers);
  /// The reply being built: fill force_kip / measured_drift_in, then reply_ok().
  hybrid_lcm::force_feedback_t& reply() { return feedback_; }
  /// Publishes the reply for `step` with STATUS_OK; the step counts as answered.
  void reply_ok(int64_t step);
  /// Publishes a FAULT or SAFETY_TRIP reply for `step` with the reason.
  void reply_status(int64_t step, int8_t status, const std::string& message);
  /// If `step` is the last step answered OK, publishes that reply again and returns true.
  bool answer_repeat(int64_t step);
  int64_t last_answered_step() const { return last_answered_step_; }

 private:
  void on_control(hybrid_lcm::run_control_t& msg);
  void on_drift(hybrid_lcm::drift_command_t& cmd);

  LcmInterface& lcm_;
  EndpointSettings s_;
  Listener& listener_;
  std::string run_id_;
  hybrid_lcm::run_control_t control_scratch_;
  hybrid_lcm::drift_command_t drift_scratch_;
  hybrid_lcm::force_feedback_t feedback_;
  hybrid_lcm::heartbeat_t heartbeat_;
  std::vector<uint8_t> buffer_;
  TimePoint next_heartbeat_{};
  TimePoint last_command_{};
  int64_t last_answered_step_ = -1;
};

}  // namespace messages
