#pragma once
/// @file safety.h
/// The safety layer of the physical substructure (docs/physical.md, "Safety"): checks every
/// actuator setpoint before it may be published, every sensor frame as it arrives, the
/// server's drift targets and the tracking error, and shapes the ramps (positioning,
/// excitation ramp-in, ramp-out to the safe state). It is always on; there is no switch.
///
/// A failed check returns false with the reason; ActuatorInterface::send() then does not
/// publish, and the substructure trips: hold, ramp to the safe state, abort the run.

#include "damper/physical/physical_config.h"
#include "hybrid_lcm/sensor_frame_t.hpp"

#include <string>

namespace damper::physical {

/// What the actuators are told: drum displacement (hydraulic actuator) and the positions of
/// electric actuators 1 and 2, all in in.
struct ActuatorSetpoint {
  double drum_in = 0.0;
  double actuator1_in = 0.0;
  double actuator2_in = 0.0;
};

class SafetyLayer {
 public:
  /// `period_s` is the controller period (command rate = change per period / period).
  SafetyLayer(const SafetyLimits& limits, double period_s);

  /// Stroke (|drum| <= stroke_in), command rate (|drum - last published drum| / period <=
  /// velocity_in_per_s), electric actuator range and rate (actuator_velocity_in_per_s),
  /// finiteness. Does not publish.
  bool command_ok(const ActuatorSetpoint& sp, std::string& why) const;
  /// Records a setpoint that was published (the reference of the rate check).
  void published(const ActuatorSetpoint& sp);
  /// Drift limit on the target drum displacement the server asks for.
  bool target_ok(double target_in, std::string& why) const;
  /// Electric actuator force limit and finiteness of a sensor frame.
  bool frame_ok(const hybrid_lcm::sensor_frame_t& frame, std::string& why) const;
  /// |measured - target| <= tracking_error_in.
  bool tracking_ok(double target_in, double measured_in, std::string& why) const;

  bool has_published() const { return has_published_; }
  const ActuatorSetpoint& last_published() const { return last_; }
  const SafetyLimits& limits() const { return limits_; }
  double period_s() const { return period_s_; }

 private:
  SafetyLimits limits_;
  double period_s_;
  ActuatorSetpoint last_;
  bool has_published_ = false;
};

/// A cosine-shaped move between two setpoints (zero velocity at both ends).
class SetpointRamp {
 public:
  SetpointRamp() = default;
  SetpointRamp(const ActuatorSetpoint& from, const ActuatorSetpoint& to, double duration_s);
  /// The shortest duration >= min_s whose peak drum and actuator velocity stays <= peak_velocity
  /// (electric actuators: <= min(peak_velocity, actuator_peak_velocity) when that is > 0).
  static double duration_for(const ActuatorSetpoint& from, const ActuatorSetpoint& to, double min_s,
                             double peak_velocity_in_per_s, double actuator_peak_velocity_in_per_s = 0.0);
  ActuatorSetpoint at(double t_s) const;
  double duration_s() const { return duration_s_; }
  const ActuatorSetpoint& to() const { return to_; }

 private:
  ActuatorSetpoint from_, to_;
  double duration_s_ = 0.0;
};

/// Cosine blend factor 0 -> 1 over [0, duration] (1 for duration <= 0).
double ramp_factor(double t_s, double duration_s);

}  // namespace damper::physical
