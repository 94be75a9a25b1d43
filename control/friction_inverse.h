#pragma once
/// @file friction_inverse.h
/// Eq. (4) of the BRFD paper (../shared/seed) forward and inverted: the semi-active kinetic
/// friction from the two electric actuator positions,
///   Fc = b + (C_a m_a1 + C_c m_a'1)(x_1 - x'_1) + (C_a m_a2 + C_c m_a'2)(x_2 - x'_2),
/// rows (1, 2) of Tables 1-2 for forward drum rotation (v >= 0; band of actuator 2 taut,
/// actuator 1 slack) and rows (3, 4) backward (band of actuator 1 taut, actuator 2 slack),
/// and its inverse: a desired kinetic friction -> actuator targets.
///
/// Inverse: Eq. (4) has two inputs and one output; the inverse moves both actuators by the
/// same displacement D from x' (x_k = x'_k + D, the "both" semi-active tests 5-6 of Table 3),
/// which keeps the two directions' frictions close (their gains G_fwd = -94.1 kip/in and
/// G_bwd = -97.4 kip/in with Tables 1-2 are within 4 %). The bounds: the actuators' stroke
/// [min_in, max_in], and the load-cell force of the TAUT band's actuator, which carries the
/// band tension: Fc = C_taut F_taut (Fig. 6b and Table 2: C_2 = 2.10 forward, C_3 = 1.94
/// backward; measured at 4.0 kip forward: 1.9 klb predicted, 2.0 klb measured in
/// harmonic0.03ea1forward), so Fc <= C_taut * force_limit_lb / 1000. Below, the
/// friction never drops under max(min_kinetic_friction_kip, fc_floor_kip).
/// The effect library (damper/effects.h) is not inverted: b and the gains are Eq. (4)'s own.
///
/// Band-brake model (damper/model/band_brake_model.h, `model: band_brake`): the actuators set the
/// slack-end tension (B2), T_slack,d = T_d - k_d1 (x1 - x'1) - k_d2 (x2 - x'2), and the kinetic
/// friction is (B3) Fc_d = L (E_d - 1) T_slack,d with E_d = exp(mu theta_d(x)) at the current drum
/// displacement x (B1). That is Eq. (4)'s form exactly, linear in x1, x2, with
///   b_d = L (E_d - 1) T_d,  G_dj = -L (E_d - 1) k_dj,
/// so the same inverse applies with these b and gains (evaluated at the drum displacement given,
/// 0 when none). The taut end carries E_d T_slack,d = Fc E_d / (L (E_d - 1)) (B6 at slip), so the
/// load-cell bound is Fc <= L (E_d - 1)/E_d * F_limit; the floor is (B2)'s 1e-4 kip slack tension.
/// Units: kip, in, s, lb for actuator load cells.

#include "damper/model/brfd_model.h"

namespace control {

/// Actuator position targets for one damper and the kinetic friction they give in the
/// direction they were computed for.
struct ActuatorTargets {
  double actuator1_in = 0.0;
  double actuator2_in = 0.0;
  double kinetic_friction_kip = 0.0;  ///< Eq. (4) at the targets, in the requested direction
  bool saturated = false;             ///< the desired friction was outside the reachable range
};

/// Reachable kinetic friction in one direction, kip.
struct FrictionRange {
  double min_kip = 0.0;
  double max_kip = 0.0;
};

/// Eq. (4) and its inverse for one damper model and its actuators' limits.
class FrictionInverse {
 public:
  /// @throws std::invalid_argument if x' is outside the stroke, or a gain of Eq. (4) is not
  /// negative (retraction must raise the friction), or the model has no actuators (passive_lugre).
  FrictionInverse(const damper::BrfdParams& params, double min_kinetic_friction_kip = 0.0);

  /// Gain dFc/dx_k of Eq. (4), kip/in, k = 1, 2 (band brake: at drum displacement drum_in).
  double gain_kip_per_in(bool forward, int actuator, double drum_in = 0.0) const {
    return linear(forward, forward ? 0.0 : -1.0, drum_in).gain[actuator - 1];
  }
  /// b of Eq. (4) at drum velocity v (band brake: at drum displacement drum_in), kip.
  double base_kip(double v_in_per_s, double drum_in = 0.0) const { return linear(v_in_per_s >= 0.0, v_in_per_s, drum_in).b; }
  /// Eq. (4) at positions x1, x2 and drum velocity v (with the model's floor), kip.
  double kinetic_friction_kip(double x1_in, double x2_in, double v_in_per_s, double drum_in = 0.0) const;
  /// Load-cell force of the taut band's actuator for kinetic friction fc, lb.
  double taut_actuator_force_lb(double fc_kip, bool forward, double drum_in = 0.0) const;
  /// The kinetic friction reachable at drum velocity v within stroke and force limits.
  FrictionRange range(double v_in_per_s, double drum_in = 0.0) const;
  /// The inverse: targets for desired kinetic friction fc (kip, magnitude) at drum velocity v
  /// (and drum displacement drum_in, which only the band brake's wrap angle uses).
  /// Outside range(v) the targets saturate at the nearer bound (saturated = true).
  ActuatorTargets targets(double fc_kip, double v_in_per_s, double drum_in = 0.0) const;
  /// Time the electric actuators need to go from the targets of the most friction to those of
  /// the least at drum velocity v (and drum displacement drum_in): the servo's lag (τ, first
  /// order; 2ζτ, second order) plus the common stroke between the two at the velocity limit,
  /// lag + |D(max) - D(min)| / v_lim, s (0.142 s with the paper's model and the default actuators).
  double release_time_s(double v_in_per_s, double drum_in = 0.0) const;
  /// Drum speed below which the actuators lose their hold on the friction: the Stribeck velocity
  /// v_s of Eq. (5) for the semi-active model (g(v) = Fc + (Fs - Fc) exp(-(v/v_s)²), Fs does not
  /// follow the actuators), 0 for the band brake (its capstan friction has no speed term), in/s.
  double stribeck_velocity_in_per_s() const { return band_brake_ ? 0.0 : params_.lugre.vs_in_per_s; }
  /// passive_on: the fixed positions giving the largest friction that keeps both directions
  /// within stroke and force limits (at b of zero speed).
  const ActuatorTargets& strongest() const { return strongest_; }
  /// passive_off: x'_1, x'_2.
  ActuatorTargets initial() const;
  const damper::ElectricActuatorParams& actuators() const { return params_.electric_actuators; }
  /// x'_1, x'_2 of the model (semi-active or band brake), in.
  double rest1_in() const { return x1_rest_; }
  double rest2_in() const { return x2_rest_; }

 private:
  /// Eq. (4) of one direction as Fc = b + g1 dx1 + g2 dx2, with the taut-actuator factor
  /// c_taut (kip of Fc per kip of taut-end load cell force) and the floor of Fc.
  struct Linear {
    double b = 0.0, gain[2] = {0.0, 0.0}, c_taut = 1.0, floor = 0.0;
  };
  Linear linear(bool forward, double v_in_per_s, double drum_in) const;

  damper::BrfdParams params_;
  damper::BrfdModel model_;
  bool band_brake_ = false;
  double x1_rest_ = 0.0, x2_rest_ = 0.0;
  double d_lo_ = 0.0, d_hi_ = 0.0;  // common displacement range from the stroke, in
  double fc_min_ = 0.0;
  ActuatorTargets strongest_;
};

}  // namespace control
