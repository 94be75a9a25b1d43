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
/// STOP, ABORT and drift command of its run, and publishes what the node asks.
///
/// Authentication (messages/message_auth.h): every message it publishes is signed under the
/// run key with its own increasing sequence; a reply carries the step and the sequence of the
/// command it answers (command_sequence). A received run control or drift command reaches the
/// node only when it decodes, belongs to the run, carries a valid HMAC and a sequence above
/// the last accepted one of its channel; anything else is counted in bad_messages() (kinds
/// "RUN_CONTROL/bad_mac" etc.), said once per kind on stderr and dropped. Under policy stop
/// the next drift command is answered with a FAULT naming the first bad message (the server
/// then aborts the run; a physical node ramps to its safe state as on any abort).

#include "hybrid_lcm/drift_command_t.hpp"
#include "hybrid_lcm/force_feedback_t.hpp"
#include "hybrid_lcm/heartbeat_t.hpp"
#include "hybrid_lcm/run_control_t.hpp"
#include "messages/bad_message_log.h"
#include "messages/message_auth.h"
#include "messages/run_key.h"
#include "messages/transport.h"

#include <string>
#include <vector>

namespace messages {

struct EndpointSettings {
  Channels channels;
  std::string run_id;                   ///< answer only this run ("" = adopt the first START)
  std::string sender = "brfd-substructure";
  double heartbeat_period_s = 0.2;
  RunKey key{};                         ///< the run key (run_key.h): signs and verifies everything
  BadMessagePolicy on_bad_message = BadMessagePolicy::drop;
};

/// The endpoint settings of a node (the virtual node, substructure_node.h; the physical lab
/// node, physical_node.h) from the fields every node's options have (channels, run_id,
/// heartbeat_period_s, on_bad_message) and the run key.
template <typename NodeOptions>
EndpointSettings endpoint_settings_of(const NodeOptions& o, const RunKey& key) {
  EndpointSettings e;
  e.channels = o.channels;
  e.run_id = o.run_id;
  e.heartbeat_period_s = o.heartbeat_period_s;
  e.key = key;
  e.on_bad_message = o.on_bad_message;
  return e;
}

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

  /// Bad messages received so far, by kind.
  const BadMessageLog& bad_messages() const { return bad_; }
  /// Counts a bad message of a channel the node reads itself (sensor frames).
  BadMessageLog& bad_message_log() { return bad_; }
  /// The run key's signer/verifier (the node's other links use the same key).
  const MessageAuth& auth() const { return auth_; }

 private:
  void on_control(hybrid_lcm::run_control_t& msg);
  void on_drift(hybrid_lcm::drift_command_t& cmd);
  /// Authentication and replay checks of a decoded run control / drift command; false (and
  /// counted) when it must be dropped. `last_sequence` is the channel's last accepted one.
  template <class T>
  bool accept(const char* channel, const RawMessage& raw, T& msg, int64_t& last_sequence);
  void publish_reply();

  LcmInterface& lcm_;
  EndpointSettings s_;
  Listener& listener_;
  std::string run_id_;
  hybrid_lcm::run_control_t control_scratch_;
  hybrid_lcm::drift_command_t drift_scratch_;
  hybrid_lcm::force_feedback_t feedback_;
  hybrid_lcm::heartbeat_t heartbeat_;
  std::vector<uint8_t> buffer_;
  MessageAuth auth_;
  BadMessageLog bad_;
  int64_t sequence_ = 0;                 ///< of the messages this endpoint publishes
  int64_t last_control_sequence_ = 0;    ///< last accepted run control's
  int64_t last_drift_sequence_ = 0;      ///< last accepted drift command's
  int64_t last_drift_step_ = -1;         ///< step of the last accepted drift command
  TimePoint next_heartbeat_{};
  TimePoint last_command_{};
  int64_t last_answered_step_ = -1;
};

}  // namespace messages
