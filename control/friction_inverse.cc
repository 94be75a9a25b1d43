#include "control/friction_inverse.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace control {

FrictionInverse::FrictionInverse(const damper::BrfdParams& params, double min_kinetic_friction_kip)
    : params_(params), model_(params) {
  if (params.kind != damper::DamperKind::semiactive)
    throw std::invalid_argument("control needs the semi-active damper model (model: semiactive)");
  const damper::SemiActiveParams& s = params.semiactive;
  for (int dir = 0; dir < 2; ++dir) {
    const int a = dir == 0 ? 0 : 2, c = dir == 0 ? 1 : 3;
    for (int k = 0; k < 2; ++k) {
      gain_[dir][k] = s.scaling[a] * s.slopes_kip_per_in[a][k] + s.scaling[c] * s.slopes_kip_per_in[c][k];
      if (!(gain_[dir][k] < 0.0))
        throw std::invalid_argument("Eq. (4) gain of actuator " + std::to_string(k + 1) + (dir == 0 ? " forward" : " backward") +
                                    " is " + std::to_string(gain_[dir][k]) + " kip/in; control needs it < 0");
    }
  }
  const damper::ElectricActuatorParams& e = params.electric_actuators;
  const double x1 = s.actuator1_initial_in, x2 = s.actuator2_initial_in;
  if (x1 < e.min_in || x1 > e.max_in || x2 < e.min_in || x2 > e.max_in)
    throw std::invalid_argument("initial actuator positions x'1 = " + std::to_string(x1) + ", x'2 = " + std::to_string(x2) +
                                " in lie outside the electric actuator stroke [" + std::to_string(e.min_in) + ", " +
                                std::to_string(e.max_in) + "] in");
  d_lo_ = std::max(e.min_in - x1, e.min_in - x2);
  d_hi_ = std::min(e.max_in - x1, e.max_in - x2);
  fc_min_ = std::max(min_kinetic_friction_kip, s.fc_floor_kip);
  // passive_on: the most retracted common displacement allowed in both directions.
  double d_on = d_lo_;
  for (int dir = 0; dir < 2; ++dir) {
    const bool fwd = dir == 0;
    const double b = base_kip(fwd ? 0.0 : -1e-300);
    const double g = gain_[dir][0] + gain_[dir][1];
    const double fc_force = (fwd ? s.scaling[1] : s.scaling[2]) * e.force_limit_lb / 1000.0;
    d_on = std::max(d_on, (fc_force - b) / g);
  }
  d_on = std::min(d_on, d_hi_);
  strongest_.actuator1_in = x1 + d_on;
  strongest_.actuator2_in = x2 + d_on;
  strongest_.kinetic_friction_kip = kinetic_friction_kip(strongest_.actuator1_in, strongest_.actuator2_in, 0.0);
}

double FrictionInverse::kinetic_friction_kip(double x1, double x2, double v) const {
  const bool fwd = v >= 0.0;
  const damper::SemiActiveParams& s = params_.semiactive;
  const double fc = base_kip(v) + gain_kip_per_in(fwd, 1) * (x1 - s.actuator1_initial_in) +
                    gain_kip_per_in(fwd, 2) * (x2 - s.actuator2_initial_in);
  return std::max(fc, s.fc_floor_kip);
}

double FrictionInverse::taut_actuator_force_lb(double fc_kip, bool forward) const {
  const double c_taut = forward ? params_.semiactive.scaling[1] : params_.semiactive.scaling[2];
  return 1000.0 * fc_kip / c_taut;
}

FrictionRange FrictionInverse::range(double v) const {
  const bool fwd = v >= 0.0;
  const double b = base_kip(v);
  const double g = gain_kip_per_in(fwd, 1) + gain_kip_per_in(fwd, 2);
  const double c_taut = fwd ? params_.semiactive.scaling[1] : params_.semiactive.scaling[2];
  FrictionRange r;
  r.max_kip = std::min(b + g * d_lo_, c_taut * params_.electric_actuators.force_limit_lb / 1000.0);
  r.min_kip = std::max(b + g * d_hi_, fc_min_);
  if (r.max_kip < r.min_kip) r.max_kip = r.min_kip;
  return r;
}

ActuatorTargets FrictionInverse::targets(double fc, double v) const {
  const bool fwd = v >= 0.0;
  const FrictionRange r = range(v);
  ActuatorTargets t;
  const double fc_used = std::clamp(fc, r.min_kip, r.max_kip);
  t.saturated = fc_used != fc;
  const double g = gain_kip_per_in(fwd, 1) + gain_kip_per_in(fwd, 2);
  const double d = std::clamp((fc_used - base_kip(v)) / g, d_lo_, d_hi_);
  t.actuator1_in = params_.semiactive.actuator1_initial_in + d;
  t.actuator2_in = params_.semiactive.actuator2_initial_in + d;
  t.kinetic_friction_kip = kinetic_friction_kip(t.actuator1_in, t.actuator2_in, v);
  return t;
}

ActuatorTargets FrictionInverse::initial() const {
  ActuatorTargets t;
  t.actuator1_in = params_.semiactive.actuator1_initial_in;
  t.actuator2_in = params_.semiactive.actuator2_initial_in;
  t.kinetic_friction_kip = kinetic_friction_kip(t.actuator1_in, t.actuator2_in, 0.0);
  return t;
}

}  // namespace control
