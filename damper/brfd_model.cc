#include "damper/brfd_model.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace damper {

BrfdModel::BrfdModel(const BrfdParams& params) : params_(params) {}

double KineticFrictionCurve::at(double v) const {
  const std::vector<double>& b = v >= 0.0 ? fwd_kip : bwd_kip;
  const double s = std::abs(v);
  if (s <= speed_in_per_s.front()) return b.front();
  if (s >= speed_in_per_s.back()) return b.back();
  const auto it = std::upper_bound(speed_in_per_s.begin(), speed_in_per_s.end(), s);
  const std::size_t k = static_cast<std::size_t>(it - speed_in_per_s.begin());
  const double w = (s - speed_in_per_s[k - 1]) / (speed_in_per_s[k] - speed_in_per_s[k - 1]);
  return b[k - 1] + w * (b[k] - b[k - 1]);
}

double BrfdModel::base_kinetic_friction_kip(double v) const {
  if (!params_.b_of_velocity.empty()) return params_.b_of_velocity.at(v);
  return v >= 0.0 ? params_.lugre.fc_fwd_kip : params_.lugre.fc_bwd_kip;
}

double BrfdModel::kinetic_friction_kip(const DamperInput& in) const {
  const bool forward = in.drum_vel_in_per_s >= 0.0;
  const double b = base_kinetic_friction_kip(in.drum_vel_in_per_s);
  if (params_.kind == DamperKind::passive_lugre) return b;
  // Eq. (4): b + (C_a m_a1 + C_b m_b1)(x1 - x1') + (C_a m_a2 + C_b m_b2)(x2 - x2'),
  // rows (1,2) forward and (3,4) backward.
  const SemiActiveParams& s = params_.semiactive;
  const int a = forward ? 0 : 2;
  const int c = forward ? 1 : 3;
  const double gain1 = s.scaling[a] * s.slopes_kip_per_in[a][0] + s.scaling[c] * s.slopes_kip_per_in[c][0];
  const double gain2 = s.scaling[a] * s.slopes_kip_per_in[a][1] + s.scaling[c] * s.slopes_kip_per_in[c][1];
  const double fc = b + gain1 * (in.actuator1_in - s.actuator1_initial_in) +
                    gain2 * (in.actuator2_in - s.actuator2_initial_in);
  return std::max(fc, s.fc_floor_kip);
}

double BrfdModel::stribeck_kip(const DamperInput& in) const {
  const LugreParams& p = params_.lugre;
  const double v = in.drum_vel_in_per_s;
  const double fs = v >= 0.0 ? p.fs_fwd_kip : p.fs_bwd_kip;
  const double fc = kinetic_friction_kip(in);
  const double r = v / p.vs_in_per_s;
  return fc + (fs - fc) * std::exp(-r * r);  // Eq. (2) / Eq. (5)
}

double BrfdModel::bristle_rate(double z_in, const DamperInput& in) const {
  const double v = in.drum_vel_in_per_s;
  return v - params_.lugre.sigma0_kip_per_in * std::abs(v) / stribeck_kip(in) * z_in;  // Eq. (1)
}

double BrfdModel::force_kip(double z_in, const DamperInput& in) const {
  const LugreParams& p = params_.lugre;
  return p.sigma0_kip_per_in * z_in + p.sigma1_kip_s_per_in * bristle_rate(z_in, in) +
         p.sigma2_kip_s_per_in * in.drum_vel_in_per_s;  // Eq. (3)
}

double BrfdModel::step(const DamperInput& in, double dt_s) {
  const double v = in.drum_vel_in_per_s;
  if (v != 0.0) {
    // Eq. (1) with v constant: dz/dt = v - a z, a = σ0|v|/g(v) > 0.
    const double a = params_.lugre.sigma0_kip_per_in * std::abs(v) / stribeck_kip(in);
    const double z_steady = v / a;
    const double decay = std::exp(-a * dt_s);
    z_in_ = z_steady + (z_in_ - z_steady) * decay;
  }
  return force_kip(z_in_, in);
}

std::string to_string(DamperKind kind) {
  return kind == DamperKind::passive_lugre ? "passive_lugre" : "semiactive";
}

DamperKind damper_kind_from_string(const std::string& name) {
  if (name == "passive_lugre") return DamperKind::passive_lugre;
  if (name == "semiactive") return DamperKind::semiactive;
  throw std::invalid_argument("unknown damper model '" + name +
                              "' (expected passive_lugre or semiactive)");
}

}  // namespace damper
