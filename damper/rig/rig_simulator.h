#pragma once
/// @file rig_simulator.h
/// The physical BRFD as brfd-rig emulates it, one controller period at a time, with no I/O:
/// servo-hydraulic actuator (delay + lag) -> drum motion -> friction from damper::BrfdModel
/// (LuGre, Eqs. 1-5 of the BRFD paper) -> backlash after reversals, residual static force ->
/// band tension on the electric actuators' load cells -> sensor noise. Each effect is switched
/// by RigConfig. Tests use it in-process (faster than real time).
///
/// Sign convention as force_feedback_t: friction force positive when resisting positive drum
/// velocity. Electric actuator load cells (lb): forward rotation (v >= 0) tensions band 2
/// (actuator 2 taut, friction ≈ C2 · its force) and leaves band 1 slack (≈ C1 · force);
/// backward rotation the other way round (C3 taut actuator 1, C4 slack actuator 2), with the
/// scaling factors C1..C4 of Table 2 (damper model's semiactive.scaling), plus pretension.

#include "damper/model/brfd_model.h"
#include "damper/rig/rig_config.h"

#include <random>
#include <vector>

namespace damper::rig {

/// Positions the rig is told to go to (in).
struct RigCommand {
  double drum_in = 0.0;
  double actuator1_in = 0.0;
  double actuator2_in = 0.0;
};

/// What the sensors read (in, kip, lb).
struct RigReading {
  double drum_in = 0.0;
  double friction_kip = 0.0;
  double actuator1_in = 0.0;
  double actuator2_in = 0.0;
  double actuator1_force_lb = 0.0;
  double actuator2_force_lb = 0.0;
};

class RigSimulator {
 public:
  explicit RigSimulator(const RigConfig& config);

  /// Advances one period (1 / rate_hz) with `command` as the newest target.
  void step(const RigCommand& command);

  /// Sensor readings after the last step (with noise if enabled).
  const RigReading& reading() const { return reading_; }
  /// The same without noise.
  const RigReading& truth() const { return truth_; }
  double drum_velocity_in_per_s() const { return velocity_; }
  /// Backlash weight applied at the last step (1 = no backlash), residual force term (kip).
  double backlash_weight() const { return backlash_weight_; }
  double residual_kip() const { return residual_kip_; }
  long reversals() const { return reversals_; }

 private:
  double backlash(double x);
  double residual(double x, double v, double dynamic_force_kip);
  void set_band_forces(double friction_kip, RigReading& r) const;

  RigConfig c_;
  double dt_;
  BrfdModel model_;
  // Hydraulic actuator.
  std::vector<double> delay_line_;
  std::size_t delay_head_ = 0;
  double delay_samples_ = 0.0;
  double drum_ = 0.0, velocity_ = 0.0;
  double electric1_ = 0.0, electric2_ = 0.0;
  // Backlash: direction (+1/-1/0), extreme position of the current direction, last reversal.
  int direction_ = 0;
  double extreme_ = 0.0, reversal_at_ = 0.0, direction_origin_ = 0.0;
  bool reversed_ = false;
  bool in_gap_ = false;
  long reversals_ = 0;
  double backlash_weight_ = 1.0;
  // Residual static force.
  double residual_kip_ = 0.0;
  double rest_time_ = 0.0;
  bool at_rest_ = true;
  double motion_since_rest_ = 0.0;
  double release_from_kip_ = 0.0;
  int last_motion_sign_ = 0;
  // Sensors.
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  RigReading truth_, reading_;
};

}  // namespace damper::rig
