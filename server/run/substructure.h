#pragma once
/// @file substructure.h
/// The seam between the step loop and whoever produces the damper force: "here is the drum
/// displacement of step i+1, give me the force". In-process (the model called directly) and
/// remote over LCM (a brfd-substructure process, virtual or physical) give identical
/// results for the same model.

#include "damper/model/actuator_drive.h"
#include "damper/model/brfd_model.h"
#include "messages/bad_message_log.h"
#include "messages/lcm_bus.h"
#include "messages/run_key.h"

#include <Eigen/Dense>

#include <chrono>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace hybrid_lcm {
class force_feedback_t;
class heartbeat_t;
}

namespace server {

/// The substructure failed: timed out, reported a fault or a safety trip, or sent garbage.
class SubstructureError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Damper forces and achieved drum displacements for one step.
struct SubstructureReply {
  Eigen::VectorXd force_kip;          ///< per damper, force on its actuator (resisting +velocity)
  Eigen::VectorXd measured_drum_in;   ///< per damper, drum displacement achieved
  /// per damper, electric actuator 1 and 2 positions reached (in); filled by every substructure
  Eigen::MatrixX2d actuator_in;
};

class Substructure {
 public:
  virtual ~Substructure() = default;
  /// Prepares a run of `num_dampers` dampers stepped at dt_s. May block for a handshake.
  virtual void start(const std::string& run_id, int num_dampers, double dt_s) = 0;
  /// One exchange: target drum displacement (in) and velocity (in/s) of step `step`.
  /// Throws SubstructureError.
  virtual void exchange(long step, double sim_time_s, const Eigen::VectorXd& drum_disp_in,
                        const Eigen::VectorXd& drum_vel_in_per_s, SubstructureReply& reply) = 0;
  /// Orderly stop (abort = emergency stop) with a reason for the logs.
  virtual void stop(bool abort, const std::string& reason) = 0;
  /// Semi-active control: electric actuator position targets (num_dampers x 2, in) that the
  /// following exchange() calls send with the drum displacement; nullptr (the default) holds
  /// x'_1, x'_2. The matrix must outlive the exchanges (the step loop owns it).
  void set_actuator_targets(const Eigen::MatrixX2d* targets_in) { actuator_targets_ = targets_in; }

 protected:
  const Eigen::MatrixX2d* actuator_targets_ = nullptr;
};

/// The damper models called directly: a damper::DamperBank of the config's model, one per
/// damper (actuators at their rest positions unless a controller sets them on the bank).
class InProcessSubstructure : public Substructure {
 public:
  explicit InProcessSubstructure(const damper::BrfdParams& params);
  void start(const std::string& run_id, int num_dampers, double dt_s) override;
  void exchange(long step, double sim_time_s, const Eigen::VectorXd& drum_disp_in,
                const Eigen::VectorXd& drum_vel_in_per_s, SubstructureReply& reply) override;
  void stop(bool, const std::string&) override {}

 private:
  /// The dampers of the run (a controller sets actuator positions on it).
  damper::DamperBank& bank() { return bank_; }

 private:
  std::unique_ptr<damper::DamperModel> prototype_;
  damper::DamperBank bank_;
  damper::ActuatorDrive drive_;  ///< electric actuators following set_actuator_targets()
  damper::ElectricActuatorParams actuator_params_;
  double dt_s_ = 0.0;
};

/// Settings of the LCM link, from the run config's transport block.
struct LcmLinkSettings {
  std::string url;
  bool lab_network = false;
  messages::Channels channels;
  double step_timeout_s = 1.0;
  double start_timeout_s = 10.0;
  std::string log_path;   ///< LCM log of all traffic of the run ("" = none)
  /// Asked every ~50 ms while waiting for the peer: a non-empty answer (e.g. "brfd-substructure
  /// exited with code 1") ends the wait at once with that reason instead of at the timeout.
  std::function<std::string()> peer_gone;
  /// The run key (messages/run_key.h): every message signed, every received one verified.
  messages::RunKey key{};
  /// A malformed, foreign, forged, replayed or unbound message: drop (counted) or stop the run.
  messages::BadMessagePolicy on_bad_message = messages::BadMessagePolicy::drop;
};

/// A substructure in another process, over LCM: publishes drift_command_t, waits for the
/// force_feedback_t of the same run and step. Handshake: run_control_t START is repeated
/// until the substructure's heartbeat for this run arrives.
///
/// Authentication (messages/message_auth.h, docs/physical.md "Message authentication"):
/// every command and run control is signed under the run key with the next value of one
/// sequence. A force feedback is taken only when it decodes, names this run, verifies, has a
/// sequence above the last taken reply's (else a replay) and answers the outstanding command:
/// its step and command_sequence equal the command's, and no reply was taken for it yet
/// (else "unbound_reply": early, late or duplicate). A heartbeat is taken when it decodes,
/// names this run, verifies and its sequence increases per sender. Everything else is counted
/// in bad_messages(), said once per kind and dropped (policy stop: the run fails naming it).
class LcmSubstructure : public Substructure {
 public:
  explicit LcmSubstructure(const LcmLinkSettings& settings);
  ~LcmSubstructure() override;
  void start(const std::string& run_id, int num_dampers, double dt_s) override;
  void exchange(long step, double sim_time_s, const Eigen::VectorXd& drum_disp_in,
                const Eigen::VectorXd& drum_vel_in_per_s, SubstructureReply& reply) override;
  void stop(bool abort, const std::string& reason) override;

  /// Round-trip times of every exchange so far, microseconds (for the benchmark).
  const std::vector<double>& round_trip_us() const { return round_trip_us_; }
  void keep_round_trips(bool keep) { keep_round_trips_ = keep; }
  /// Messages this side dropped, by kind ("FORCE_FEEDBACK/bad_mac", ...).
  const messages::BadMessageLog& bad_messages() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<double> round_trip_us_;
  bool keep_round_trips_ = false;
};

}  // namespace server
