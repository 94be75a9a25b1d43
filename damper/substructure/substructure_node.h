#pragma once
/// @file substructure_node.h
/// The LCM side of `brfd-substructure`: answers each drift_command_t of its run with one
/// force_feedback_t, publishes heartbeats, follows run_control_t (start/stop/abort).
/// Virtual mode steps a BrfdModel per damper; echo mode answers at once with zero force
/// (the raw LCM round trip of `hybridsim bench`).

#include "damper/model/actuator_drive.h"
#include "damper/model/brfd_model.h"
#include "messages/lcm_bus.h"
#include "messages/substructure_endpoint.h"
#include "messages/transport.h"

#include <string>
#include <vector>

namespace damper {

struct SubstructureNodeOptions {
  std::string url;                   ///< LCM URL (required; from the server config)
  bool lab_network = false;          ///< allow multicast outside a private network namespace
  messages::Channels channels;
  std::string run_id;                ///< answer only this run ("" = adopt the first START)
  bool echo = false;                 ///< answer with zero force, no model (benchmark)
  BrfdParams model;                  ///< virtual damper model
  double max_drum_displacement_in = 12.0;    ///< commands beyond this are refused (fault)
  double max_drum_velocity_in_per_s = 200.0; ///< commands beyond this are refused (fault)
  double command_watchdog_s = 30.0;  ///< exit with an error if a started run goes silent this long
  double heartbeat_period_s = 0.2;
  messages::RunKey key{};            ///< the run key: every message signed and verified (message_auth.h)
  messages::BadMessagePolicy on_bad_message = messages::BadMessagePolicy::drop;
  std::string results_dir;           ///< where substructure-messages.json goes at exit ("" = none)
};

/// The virtual node as a messages::LoopActor on any messages::LcmInterface; its protocol side
/// is messages::SubstructureEndpoint, shared with the physical node.
class SubstructureNode : public messages::LoopActor, private messages::SubstructureEndpoint::Listener {
 public:
  SubstructureNode(messages::LcmInterface& lcm, const SubstructureNodeOptions& options);
  void advance(messages::TimePoint now) override;
  messages::TimePoint next_deadline(messages::TimePoint now) const override;
  bool finished() const override { return exit_code_ >= 0; }
  /// 0 STOP, 3 ABORT, 1 command watchdog; -1 while running.
  int exit_code() const { return exit_code_; }
  long steps() const { return steps_; }
  /// Messages dropped so far (run control, drift commands), by kind.
  const messages::BadMessageLog& bad_messages() const { return endpoint_.bad_messages(); }

 private:
  void on_run_control(const hybrid_lcm::run_control_t& msg, messages::TimePoint now) override;
  void on_drift(hybrid_lcm::drift_command_t& cmd, messages::TimePoint now) override;
  int8_t heartbeat_state() const override;
  void fault(int64_t step, const std::string& why);

  SubstructureNodeOptions o_;
  messages::SubstructureEndpoint endpoint_;
  DamperBank bank_;  ///< the run's dampers (damper/model/damper_model.h)
  ActuatorDrive drive_;  ///< electric actuators following the controller's targets
  double dt_s_ = 0.0;
  bool started_ = false;
  long steps_ = 0;
  int exit_code_ = -1;
};

/// Runs until STOP (returns 0), ABORT (returns 3) or a watchdog/transport error (returns 1).
/// Bad messages (undecodable, foreign, forged, replayed) are counted, said once per kind on
/// stderr and dropped; the counts go to <results_dir>/substructure-messages.json at exit.
int run_substructure_node(const SubstructureNodeOptions& options);

}  // namespace damper
