#include "damper/model/band_brake_model.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace damper {

namespace {
constexpr double kMinSlackTensionKip = 1e-4;  // a band end never pushes: T_slack > 0
constexpr double kQuarterTurnRad = 1.5707963267948966;
}

BandBrakeModel::BandBrakeModel(const BandBrakeParams& params)
    : p_(params), sigma0_(params.lever_ratio * params.band_stiffness_kip_per_in) {}

double BandBrakeModel::capstan_ratio(double mu, double theta) { return std::exp(mu * theta); }

BandTensions BandBrakeModel::tensions(const BandBrakeInput& in) const {
  BandTensions t;
  const double d1 = in.actuator1_in - p_.actuator1_initial_in;
  const double d2 = in.actuator2_in - p_.actuator2_initial_in;
  const std::array<double, 4>& k = p_.actuator_tension_kip_per_in;
  t.slack_fwd_kip = std::max(p_.slack_tension_fwd_kip - k[0] * d1 - k[1] * d2, kMinSlackTensionKip);  // (B2)
  t.slack_bwd_kip = std::max(p_.slack_tension_bwd_kip - k[2] * d1 - k[3] * d2, kMinSlackTensionKip);
  const double x = in.drum_disp_in;
  // (B1): the wrap angle follows the drum; it never drops below a quarter turn.
  const double theta_f = std::max(p_.wrap_angle_fwd_rad + p_.wrap_change_rad_per_in * x, kQuarterTurnRad);
  const double theta_b = std::max(p_.wrap_angle_bwd_rad - p_.wrap_change_rad_per_in * x, kQuarterTurnRad);
  t.ratio_fwd = capstan_ratio(p_.friction_coefficient, theta_f);
  t.ratio_bwd = capstan_ratio(p_.friction_coefficient, theta_b);
  t.fc_fwd_kip = p_.lever_ratio * t.slack_fwd_kip * (t.ratio_fwd - 1.0);  // (B3)
  t.fc_bwd_kip = p_.lever_ratio * t.slack_bwd_kip * (t.ratio_bwd - 1.0);
  return t;
}

double BandBrakeModel::kinetic_friction_kip(const BandBrakeInput& in, bool forward) const {
  // tensions() for one direction only (the step needs the one its velocity slides in): the
  // same expressions, so the same bits, and one exp per step instead of two.
  const double d1 = in.actuator1_in - p_.actuator1_initial_in;
  const double d2 = in.actuator2_in - p_.actuator2_initial_in;
  const std::array<double, 4>& k = p_.actuator_tension_kip_per_in;
  const double x = in.drum_disp_in;
  if (forward) {
    const double slack = std::max(p_.slack_tension_fwd_kip - k[0] * d1 - k[1] * d2, kMinSlackTensionKip);  // (B2)
    const double theta = std::max(p_.wrap_angle_fwd_rad + p_.wrap_change_rad_per_in * x, kQuarterTurnRad);  // (B1)
    return p_.lever_ratio * slack * (capstan_ratio(p_.friction_coefficient, theta) - 1.0);  // (B3)
  }
  const double slack = std::max(p_.slack_tension_bwd_kip - k[2] * d1 - k[3] * d2, kMinSlackTensionKip);
  const double theta = std::max(p_.wrap_angle_bwd_rad - p_.wrap_change_rad_per_in * x, kQuarterTurnRad);
  return p_.lever_ratio * slack * (capstan_ratio(p_.friction_coefficient, theta) - 1.0);
}

double BandBrakeModel::spring_force_kip(double s) const {
  const double d = std::max(std::abs(s) - p_.backlash_in, 0.0);
  const double f = sigma0_ * d * (1.0 + p_.band_hardening_per_in * d);  // (B4)
  return s >= 0.0 ? f : -f;
}

double BandBrakeModel::stretch_for_force(double f) const {
  if (f == 0.0) return 0.0;
  const double a = std::abs(f) / sigma0_;
  const double h = p_.band_hardening_per_in;
  // D (1 + h D) = a  ->  D = (sqrt(1 + 4 h a) - 1) / (2 h)
  const double d = h > 0.0 ? 2.0 * a / (1.0 + std::sqrt(1.0 + 4.0 * h * a)) : a;
  return std::copysign(p_.backlash_in + d, f);
}

double BandBrakeModel::stretch_rate(double s, const BandBrakeInput& in) const {
  const double v = in.drum_vel_in_per_s;
  if (v == 0.0) return 0.0;
  const BandTensions t = tensions(in);
  const double fc = v > 0.0 ? t.fc_fwd_kip : t.fc_bwd_kip;
  const double y = spring_force_kip(s) / std::max(fc, 1e-9);
  const double n = p_.transition_exponent;
  return v - std::abs(v) * (n == 1.0 ? y : std::copysign(std::pow(std::abs(y), n), y));  // (B5)
}

double BandBrakeModel::force_kip(double s, const BandBrakeInput& in) const {
  return spring_force_kip(s) + p_.viscous_kip_s_per_in * in.drum_vel_in_per_s;  // (B6)
}

std::array<double, 2> BandBrakeModel::actuator_forces_kip(double s, const BandBrakeInput& in) const {
  const BandTensions t = tensions(in);
  const double sp = spring_force_kip(s);
  if (sp > 0.0) return {t.slack_fwd_kip, t.slack_fwd_kip + sp / p_.lever_ratio};   // act. 2 taut
  if (sp < 0.0) return {t.slack_bwd_kip - sp / p_.lever_ratio, t.slack_bwd_kip};   // act. 1 taut
  return {t.slack_fwd_kip, t.slack_bwd_kip};
}

double BandBrakeModel::step(const BandBrakeInput& in, double dt_s) {
  const double v = in.drum_vel_in_per_s;
  if (v != 0.0) {
    const double fc = std::max(kinetic_friction_kip(in, v > 0.0), 1e-9);
    const double k = std::abs(v);
    const double n = p_.transition_exponent;
    const double delta = p_.backlash_in, h = p_.band_hardening_per_in;
    constexpr double inf = std::numeric_limits<double>::infinity();
    double s = s_in_;
    double left = dt_s;
    // Pieces: s < -δ (actuator 1's end loaded), |s| <= δ (slack), s > δ (actuator 2's end).
    for (int seg = 0; seg < 6 && left > 0.0; ++seg) {
      const int piece = s < -delta ? -1 : s > delta ? 1 : 0;
      double a = 0.0, c = v, lo = -inf, hi = inf;
      if (piece == 0) {
        lo = -delta;
        hi = delta;
      } else {
        // y = S/Fc, q(y) = sign(y)|y|^n linearized at s: q ≈ q0 + q' (s' - s);
        // ds/dt = v - |v| q  ->  c - a s'.
        const double d = std::abs(s) - delta;
        const double y = spring_force_kip(s) / fc;
        const double dy = sigma0_ * (1.0 + 2.0 * h * d) / fc;
        const double ay = std::abs(y);
        const double q0 = n == 1.0 ? y : std::copysign(std::pow(ay, n), y);
        const double dq = n == 1.0 ? dy : n * std::pow(ay, n - 1.0) * dy;
        a = k * dq;
        c = v - k * (q0 - dq * s);
        if (piece > 0) lo = delta; else hi = -delta;
      }
      const double u = c - a * s;  // ds/dt at the start of the piece
      if (u == 0.0) break;
      const double bound = u > 0.0 ? hi : lo;
      double t_hit = inf;
      if (std::isfinite(bound)) {
        if (a == 0.0) {
          t_hit = (bound - s) / u;
        } else {
          const double q = a * (bound - s) / u;  // reaches the bound before its asymptote if q < 1
          if (q < 1.0) t_hit = -std::log1p(-q) / a;
        }
      }
      if (t_hit >= left) {
        const double phi = a * left < 1e-12 ? left : -std::expm1(-a * left) / a;
        s += u * phi;
        left = 0.0;
      } else {
        // Step just past the boundary so the next piece is entered.
        s = bound + (u > 0.0 ? 1e-12 : -1e-12);
        left -= std::max(t_hit, 0.0);
      }
    }
    s_in_ = s;
  }
  return force_kip(s_in_, in);
}

}  // namespace damper
