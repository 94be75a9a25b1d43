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
  /// negative (retraction must raise the friction), or the model is not semi-active.
  FrictionInverse(const damper::BrfdParams& params, double min_kinetic_friction_kip = 0.0);

  /// Gain dFc/dx_k of Eq. (4), kip/in, k = 1, 2.
  double gain_kip_per_in(bool forward, int actuator) const { return gain_[forward ? 0 : 1][actuator - 1]; }
  /// b of Eq. (4) at drum velocity v, kip.
  double base_kip(double v_in_per_s) const { return model_.base_kinetic_friction_kip(v_in_per_s); }
  /// Eq. (4) at positions x1, x2 and drum velocity v (with the model's floor), kip.
  double kinetic_friction_kip(double x1_in, double x2_in, double v_in_per_s) const;
  /// Load-cell force of the taut band's actuator for kinetic friction fc, lb.
  double taut_actuator_force_lb(double fc_kip, bool forward) const;
  /// The kinetic friction reachable at drum velocity v within stroke and force limits.
  FrictionRange range(double v_in_per_s) const;
  /// The inverse: targets for desired kinetic friction fc (kip, magnitude) at drum velocity v.
  /// Outside range(v) the targets saturate at the nearer bound (saturated = true).
  ActuatorTargets targets(double fc_kip, double v_in_per_s) const;
  /// passive_on: the fixed positions giving the largest friction that keeps both directions
  /// within stroke and force limits (at b of zero speed).
  const ActuatorTargets& strongest() const { return strongest_; }
  /// passive_off: x'_1, x'_2.
  ActuatorTargets initial() const;
  const damper::ElectricActuatorParams& actuators() const { return params_.electric_actuators; }

 private:
  damper::BrfdParams params_;
  damper::BrfdModel model_;
  double gain_[2][2];          // [fwd, bwd][actuator 1, 2], kip/in
  double d_lo_ = 0.0, d_hi_ = 0.0;  // common displacement range from the stroke, in
  double fc_min_ = 0.0;
  ActuatorTargets strongest_;
};

}  // namespace control
