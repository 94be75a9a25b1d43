#pragma once
/// @file physical_node.h
/// `brfd-substructure --mode physical`: the physical BRFD substructure. Towards the server it
/// speaks the same protocol as the virtual one (run_control_t, heartbeat_t, one
/// force_feedback_t per drift_command_t): the server does not know whether a model or a rig
/// answered. Towards the lab controller (or brfd-rig) it publishes authenticated
/// actuator_command_t at the controller rate and consumes sensor_frame_t
/// (docs/physical.md).
///
/// One step: drift command k (target drum displacement) -> drift limit -> ATS compensation
/// -> excitation ramp-in -> safety layer -> signed command -> the next sensor frame ->
/// actuator force and tracking checks -> force_feedback_t with the MEASURED friction force and
/// drum displacement. The controller's frames pace the loop, so the run proceeds in real time.
///
/// Lifecycle: START -> wait for the rig's frames -> positioning ramp to the start position
/// (the rig must accept our commands) -> READY -> steps -> STOP: ramp-out to the safe state.
/// On a trip (any limit or watchdog): answer the step with STATUS_SAFETY_TRIP and the reason,
/// hold, ramp to the safe state, exit 4. On ABORT from the server: hold, ramp, exit 3.
///
/// Results (in results_dir): physical.csv (every step), tracking.json (tracking indicators,
/// ATS coefficients), safety.json (limits in force, trip reason and step).
///
/// PhysicalNode is that state machine (phases idle -> waiting_rig -> positioning -> running ->
/// ramp_out | hold -> safe_ramp -> done), a messages::LoopActor on any messages::LcmInterface:
/// run_physical_substructure() drives it on liblcm in real time; tests drive it with brfd-rig's
/// RigNode on the in-memory fake, on a simulated clock. Its protocol side towards the server
/// is messages::SubstructureEndpoint, shared with the virtual node.

#include "damper/model/brfd_model.h"
#include "damper/physical/actuator_interface.h"
#include "damper/physical/ats_compensator.h"
#include "damper/physical/physical_config.h"
#include "damper/physical/safety.h"
#include "damper/physical/sample_recorder.h"
#include "damper/physical/tracking.h"
#include "messages/lcm_bus.h"
#include "messages/substructure_endpoint.h"
#include "messages/transport.h"

#include <memory>
#include <string>
#include <vector>

namespace damper::physical {

struct PhysicalNodeOptions {
  std::string url;                  ///< LCM URL (the server's transport.url)
  bool lab_network = false;
  messages::Channels channels;
  std::string run_id;               ///< answer only this run ("" = adopt the first START)
  BrfdParams model;                 ///< x'_1, x'_2: electric actuator hold positions
  PhysicalSettings settings;
  std::string key_file;             ///< HMAC key of every message of the run (messages/run_key.h)
  /// Bad messages (messages/bad_message_log.h): drop, or answer the next command with a FAULT.
  messages::BadMessagePolicy on_bad_message = messages::BadMessagePolicy::drop;
  std::string results_dir;          ///< where physical.csv, tracking.json, safety.json go ("" = none)
  double heartbeat_period_s = 0.2;
  double start_watchdog_s = 120.0;  ///< exit 1 if no START arrives this long
};

class PhysicalNode : public messages::LoopActor, private messages::SubstructureEndpoint::Listener {
 public:
  enum class Phase { idle, waiting_rig, positioning, running, ramp_out, hold, safe_ramp, done };
  using TimePoint = messages::TimePoint;

  /// Reads the key file (throws std::runtime_error naming it), subscribes on `lcm`.
  PhysicalNode(messages::LcmInterface& lcm, const PhysicalNodeOptions& options);
  PhysicalNode(messages::LcmInterface& lcm, const PhysicalNodeOptions& options, const RunKey& key);

  // messages::LoopActor
  void advance(TimePoint now) override;
  TimePoint next_deadline(TimePoint now) const override;
  bool finished() const override { return phase_ == Phase::done || quit_; }

  /// The transport failed (or a handler threw): trip without sending anything more.
  void transport_failed(const std::string& why);
  /// Writes physical.csv, tracking.json, safety.json (when results_dir is set), prints the
  /// summary lines and returns the exit code (see run_physical_substructure).
  int finish();

  Phase phase() const { return phase_; }
  bool tripped() const { return tripped_; }
  const std::string& trip_reason() const { return trip_reason_; }
  long steps_done() const { return steps_done_; }
  int64_t last_answered_step() const { return endpoint_.last_answered_step(); }
  const ActuatorInterface& actuator() const { return act_; }
  /// Messages dropped so far (run control, drift commands, sensor frames), by kind.
  const messages::BadMessageLog& bad_messages() const { return endpoint_.bad_messages(); }
  const AtsCompensator& ats() const { return ats_; }
  /// Tracking indicators of the steps so far (delay on the controller's clock).
  TrackingIndicators tracking() const;

 private:
  // messages::SubstructureEndpoint::Listener
  void on_run_control(const hybrid_lcm::run_control_t& msg, TimePoint now) override;
  void on_drift(hybrid_lcm::drift_command_t& cmd, TimePoint now) override;
  int8_t heartbeat_state() const override;

  bool drain_pending_traffic();
  void tick(TimePoint now);
  void begin_ramp(Phase phase, TimePoint now);
  void process_command(TimePoint now);
  void answer_step(TimePoint now);
  void trip(const std::string& why, TimePoint now);
  void fail_start(const std::string& why, TimePoint now);

  messages::LcmInterface& lcm_;
  PhysicalNodeOptions o_;
  PhysicalSettings s_;
  double period_;
  TimePoint created_;
  SafetyLayer safety_;
  ActuatorInterface act_;
  AtsCompensator ats_;
  messages::SubstructureEndpoint endpoint_;
  std::unique_ptr<SampleRecorder> recorder_;

  Phase phase_ = Phase::idle;
  bool quit_ = false;           // start watchdog or transport failure: leave the loop
  bool start_watchdog_fired_ = false;
  int exit_code_ = -1;
  ActuatorSetpoint hold_positions_, safe_, start_;
  SetpointRamp ramp_;
  TimePoint phase_start_{}, next_tick_{}, rig_deadline_{}, hold_until_{}, run_start_{};
  long tick_ = 0;
  int64_t first_positioning_sequence_ = 0;

  hybrid_lcm::drift_command_t pending_;
  bool has_pending_ = false, step_open_ = false;
  int64_t current_step_ = -1;
  double current_sim_time_ = 0, current_target_ = 0, current_compensated_ = 0, current_command_ = 0;
  double current_intended_ = 0;
  /// ATS correction (compensated - target) of the last command, in, and how many steps had
  /// its change limited (PhysicalNode::process_command).
  double ats_correction_in_ = 0;
  long ats_correction_limited_steps_ = 0;
  long frames_at_publish_ = 0, frames_checked_ = 0;
  long steps_done_ = 0, late_frames_ = 0;
  int32_t rejected_seen_ = 0;

  bool tripped_ = false, aborted_ = false, start_failed_ = false;
  std::string trip_reason_, start_failure_, why_;
  int64_t trip_step_ = -1;
  std::vector<double> target_, measured_;
  std::vector<double> target_by_command_;  // target of run command first_run_command_ + i
  int64_t first_run_command_ = 0;
  std::vector<FrameSample> frames_seen_;   // every frame while running (controller clock)
};

/// `brfd-substructure --mode physical`: real-time priority, liblcm on options.url, a
/// PhysicalNode driven by messages::run_loop. Exit codes: 0 orderly stop, 1 watchdog before
/// start / transport error, 2 bad input or the rig refuses us, 3 aborted by the server,
/// 4 safety trip.
int run_physical_substructure(const PhysicalNodeOptions& options);

}  // namespace damper::physical
