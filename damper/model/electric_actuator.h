#pragma once
/// @file electric_actuator.h
/// The BRFD's two electric (band) actuators as a servo: the position x_k (in) follows the
/// commanded target through a first-order lag  dx/dt = (r - x)/τ  or a second-order response
///   d²x/dt² = ω_n² (r - x) - 2 ζ ω_n dx/dt,
/// with the target clamped to the stroke [min_in, max_in] and |dx/dt| to the velocity limit.
/// The positions it reaches are the x_1, x_2 of Eq. (4) of the BRFD paper (../shared/seed).
/// Units: in, s. Defaults: docs/control.md "Electric actuator model" (from the measured
/// semi-active tests, ../shared/data/brfd/semiactive).
///
/// The substructure (virtual) runs this model between the controller's targets and the
/// damper model; the controller uses the same limits to know what the actuators can do.

#include "common/strict_yaml.h"

#include <string>

namespace damper {

/// Settings of the two electric actuators (both alike). Config block `electric_actuators:`.
struct ElectricActuatorParams {
  double min_in = 0.30;                  ///< stroke limit, retracted end, in
  double max_in = 1.20;                  ///< stroke limit, extended end, in
  double velocity_limit_in_per_s = 0.6;  ///< |dx/dt| limit, in/s (measured up to 0.54)
  int order = 1;                         ///< 1: first-order lag, 2: second-order response
  double time_constant_s = 0.035;        ///< τ (order 1; median fit 34.5 ms); order 2: ω_n = 1/τ
  double damping_ratio = 0.8;            ///< ζ (order 2 only)
  /// Load-cell force limit of a band actuator, lb: the controller never asks for a kinetic
  /// friction whose taut-band actuator force (Fc / C_taut, Table 2) exceeds it.
  double force_limit_lb = 3000.0;
};

/// Reads an `electric_actuators` block (strict; every key optional). @throws common::ConfigError.
ElectricActuatorParams electric_actuator_params_from_yaml(const common::YamlSection& section);
/// The block as YAML (indented by two spaces under `electric_actuators:`).
std::string electric_actuator_params_to_yaml(const ElectricActuatorParams& p);

/// One electric actuator. Allocation-free; step() is exact for the linear part (held target
/// over the step), then the rate and stroke limits are applied.
class ElectricActuator {
 public:
  ElectricActuator() = default;
  explicit ElectricActuator(const ElectricActuatorParams& params);
  /// At rest at x0 (clamped to the stroke).
  void reset(double x0_in);
  /// Advances dt_s with the target held; returns the position reached, in.
  double step(double target_in, double dt_s);
  double position_in() const { return x_; }
  double velocity_in_per_s() const { return v_; }
  /// Target clamped to the stroke.
  double clamp_to_stroke(double target_in) const;
  const ElectricActuatorParams& params() const { return p_; }

 private:
  ElectricActuatorParams p_;
  double x_ = 0.0, v_ = 0.0;
};

}  // namespace damper
