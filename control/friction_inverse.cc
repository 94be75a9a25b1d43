#include "control/friction_inverse.h"

#include "damper/model/band_brake_model.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace control {

namespace {
constexpr double kBandMinSlackTensionKip = 1e-4;  // (B2)'s floor in band_brake_model.cc
}

FrictionInverse::Linear FrictionInverse::linear(bool fwd, double v, double drum_in) const {
  Linear l;
  if (band_brake_) {
    // (B1)-(B3) of band_brake_model.h at this drum displacement: Fc = L (E - 1) T_slack.
    const damper::BandBrakeParams& p = params_.band_brake;
    damper::BandBrakeModel m(p);
    damper::DamperInput in;
    in.drum_disp_in = drum_in;
    in.actuator1_in = p.actuator1_initial_in;
    in.actuator2_in = p.actuator2_initial_in;
    const damper::BandTensions t = m.tensions(in);
    const double e = fwd ? t.ratio_fwd : t.ratio_bwd;
    const double s = p.lever_ratio * (e - 1.0);
    const int row = fwd ? 0 : 2;
    l.b = s * (fwd ? p.slack_tension_fwd_kip : p.slack_tension_bwd_kip);
    l.gain[0] = -s * p.actuator_tension_kip_per_in[row];
    l.gain[1] = -s * p.actuator_tension_kip_per_in[row + 1];
    l.c_taut = s / e;
    l.floor = s * kBandMinSlackTensionKip;
    return l;
  }
  const damper::SemiActiveParams& sa = params_.semiactive;
  const int a = fwd ? 0 : 2, c = fwd ? 1 : 3;
  for (int k = 0; k < 2; ++k)
    l.gain[k] = sa.scaling[a] * sa.slopes_kip_per_in[a][k] + sa.scaling[c] * sa.slopes_kip_per_in[c][k];
  l.b = model_.base_kinetic_friction_kip(fwd ? std::max(v, 0.0) : std::min(v, -1e-300));
  l.c_taut = fwd ? sa.scaling[1] : sa.scaling[2];
  l.floor = sa.fc_floor_kip;
  return l;
}

FrictionInverse::FrictionInverse(const damper::BrfdParams& params, double min_kinetic_friction_kip)
    : params_(params), model_(params), band_brake_(params.kind == damper::DamperKind::band_brake) {
  if (params.kind == damper::DamperKind::passive_lugre)
    throw std::invalid_argument(
        "control needs a damper model with electric actuators (model: semiactive or band_brake), not passive_lugre");
  x1_rest_ = band_brake_ ? params.band_brake.actuator1_initial_in : params.semiactive.actuator1_initial_in;
  x2_rest_ = band_brake_ ? params.band_brake.actuator2_initial_in : params.semiactive.actuator2_initial_in;
  for (int dir = 0; dir < 2; ++dir) {
    const Linear l = linear(dir == 0, dir == 0 ? 0.0 : -1.0, 0.0);
    for (int k = 0; k < 2; ++k)
      if (!(l.gain[k] < 0.0))
        throw std::invalid_argument(std::string(band_brake_ ? "band-brake (B2)-(B3)" : "Eq. (4)") + " gain of actuator " +
                                    std::to_string(k + 1) + (dir == 0 ? " forward" : " backward") + " is " +
                                    std::to_string(l.gain[k]) + " kip/in; control needs it < 0");
  }
  const damper::ElectricActuatorParams& e = params.electric_actuators;
  const double x1 = x1_rest_, x2 = x2_rest_;
  if (x1 < e.min_in || x1 > e.max_in || x2 < e.min_in || x2 > e.max_in)
    throw std::invalid_argument("initial actuator positions x'1 = " + std::to_string(x1) + ", x'2 = " + std::to_string(x2) +
                                " in lie outside the electric actuator stroke [" + std::to_string(e.min_in) + ", " +
                                std::to_string(e.max_in) + "] in");
  d_lo_ = std::max(e.min_in - x1, e.min_in - x2);
  d_hi_ = std::min(e.max_in - x1, e.max_in - x2);
  fc_min_ = min_kinetic_friction_kip;  // range() adds the model's own floor at the drum position
  // passive_on: the most retracted common displacement allowed in both directions.
  double d_on = d_lo_;
  for (int dir = 0; dir < 2; ++dir) {
    const Linear l = linear(dir == 0, dir == 0 ? 0.0 : -1e-300, 0.0);
    const double fc_force = l.c_taut * e.force_limit_lb / 1000.0;
    d_on = std::max(d_on, (fc_force - l.b) / (l.gain[0] + l.gain[1]));
  }
  d_on = std::min(d_on, d_hi_);
  strongest_.actuator1_in = x1 + d_on;
  strongest_.actuator2_in = x2 + d_on;
  strongest_.kinetic_friction_kip = kinetic_friction_kip(strongest_.actuator1_in, strongest_.actuator2_in, 0.0);
}

double FrictionInverse::kinetic_friction_kip(double x1, double x2, double v, double drum_in) const {
  const Linear l = linear(v >= 0.0, v, drum_in);
  const double fc = l.b + l.gain[0] * (x1 - x1_rest_) + l.gain[1] * (x2 - x2_rest_);
  return std::max(fc, l.floor);
}

double FrictionInverse::taut_actuator_force_lb(double fc_kip, bool forward, double drum_in) const {
  return 1000.0 * fc_kip / linear(forward, forward ? 0.0 : -1.0, drum_in).c_taut;
}

FrictionRange FrictionInverse::range(double v, double drum_in) const {
  const Linear l = linear(v >= 0.0, v, drum_in);
  const double g = l.gain[0] + l.gain[1];
  FrictionRange r;
  r.max_kip = std::min(l.b + g * d_lo_, l.c_taut * params_.electric_actuators.force_limit_lb / 1000.0);
  r.min_kip = std::max(l.b + g * d_hi_, std::max(fc_min_, l.floor));
  if (r.max_kip < r.min_kip) r.max_kip = r.min_kip;
  return r;
}

ActuatorTargets FrictionInverse::targets(double fc, double v, double drum_in) const {
  const Linear l = linear(v >= 0.0, v, drum_in);
  const FrictionRange r = range(v, drum_in);
  ActuatorTargets t;
  const double fc_used = std::clamp(fc, r.min_kip, r.max_kip);
  t.saturated = fc_used != fc;
  const double d = std::clamp((fc_used - l.b) / (l.gain[0] + l.gain[1]), d_lo_, d_hi_);
  t.actuator1_in = x1_rest_ + d;
  t.actuator2_in = x2_rest_ + d;
  t.kinetic_friction_kip = kinetic_friction_kip(t.actuator1_in, t.actuator2_in, v, drum_in);
  return t;
}

double FrictionInverse::release_time_s(double v, double drum_in) const {
  const Linear l = linear(v >= 0.0, v, drum_in);
  const FrictionRange r = range(v, drum_in);
  const double g = l.gain[0] + l.gain[1];
  const double d_max = std::clamp((r.max_kip - l.b) / g, d_lo_, d_hi_), d_min = std::clamp((r.min_kip - l.b) / g, d_lo_, d_hi_);
  const damper::ElectricActuatorParams& e = params_.electric_actuators;
  // The servo's lag: τ of the first-order response, 2ζ/ω_n = 2ζτ of the second-order one.
  const double lag_s = e.order == 2 ? 2.0 * e.damping_ratio * e.time_constant_s : e.time_constant_s;
  return lag_s + std::abs(d_max - d_min) / e.velocity_limit_in_per_s;
}

ActuatorTargets FrictionInverse::initial() const {
  ActuatorTargets t;
  t.actuator1_in = x1_rest_;
  t.actuator2_in = x2_rest_;
  t.kinetic_friction_kip = kinetic_friction_kip(t.actuator1_in, t.actuator2_in, 0.0);
  return t;
}

}  // namespace control
