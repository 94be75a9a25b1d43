#pragma once
/// @file band_brake_model.h
/// Band-brake model of the BRFD (config `model: band_brake`): the friction force follows from
/// the tensions at the two ends of the band wrapped on the drum, not from a fitted Coulomb
/// level. Units: kip, in, s (load-cell forces are returned in kip; the data files hold lb).
///
/// Equations (numbers used in comments, docs/band-brake.md):
///  (B1) capstan law: slip starts when T_taut = E T_slack, E = exp(μ θ_d(x)), with the wrap angle
///       of the loaded direction d changing with the drum travel x (self-energizing geometry):
///       θ_fwd(x) = θ_fwd + κ x, θ_bwd(x) = θ_bwd − κ x.
///  (B2) slack-end tension set by the electric actuators through the band's stiffness:
///       T_slack,d = T_d − k_d1 (x1 − x'1) − k_d2 (x2 − x'2)   (retracting raises tension),
///       clipped below at 1e-4 kip. Forward rotation: actuator 2's end taut, actuator 1's slack;
///       backward: the ends swap.
///  (B3) kinetic friction at the drum (lever ratio L from band tension to drum-line force):
///       Fc_d = L (T_taut − T_slack) = L T_slack,d (E_d − 1).
///  (B4) band stretch state s (in of drum travel) with backlash δ: the taut end carries load
///       only beyond the slack, D = max(|s| − δ, 0); band spring, hardening as it goes taut:
///       S(s) = sign(s) L k_b D (1 + h D).
///  (B5) stick/slip of the band on the drum, LuGre form with the capstan limit:
///       ds/dt = v − |v| sign(S) |S / Fc_{sign v}|^n   (n = 1: LuGre's Eq. 1; larger n: the band
///       slips more abruptly as the taut end reaches the capstan limit).
///  (B6) force at the drum: F = S(s) + c v. Load cells: the loaded end carries
///       T_slack,d + |S|/L, the other T_slack,d; in the slack zone both ends carry T_slack.
/// Linearizing (B1)-(B3) in the actuator positions around x' gives Eq. (4) of the paper
/// (gain of Fc per in of actuator j: −L (E_d − 1) k_dj). With δ = 0, h = 0, κ = 0, c = 0 and
/// fixed actuators and n = 1, (B4)-(B6) is LuGre (Eqs. 1-3) with σ0 = L k_b, σ1 = 0, Fs = Fc = Fc_d.

#include "damper/model/damper_model.h"

#include <array>
#include <memory>
#include <string>

namespace damper {

/// Parameters of the band-brake model, with their physical meaning.
struct BandBrakeParams {
  double friction_coefficient = 0.35;        ///< μ of the lining on the drum
  double wrap_angle_fwd_rad = 11.0;          ///< θ_fwd: wrap angle when actuator 2's end is taut
  double wrap_angle_bwd_rad = 11.0;          ///< θ_bwd: wrap angle when actuator 1's end is taut
  double wrap_change_rad_per_in = 0.0;       ///< κ of (B1): self-energizing geometry
  double lever_ratio = 2.0;                  ///< L of (B3): drum-line force per band tension
  double slack_tension_fwd_kip = 0.03;       ///< T_fwd: actuator 1's end at x', forward loading
  double slack_tension_bwd_kip = 0.03;       ///< T_bwd: actuator 2's end at x', backward loading
  double band_stiffness_kip_per_in = 10.0;   ///< k_b of (B4), band tension per in of stretch
  double band_hardening_per_in = 0.0;        ///< h of (B4): stiffening as the band goes taut
  double backlash_in = 0.0;                  ///< δ of (B4): slack before the taut end loads
  double viscous_kip_s_per_in = 0.0;         ///< c of (B6)
  double transition_exponent = 1.0;          ///< n of (B5): 1 = LuGre, large = sharp slip onset
  /// k_dj of (B2), kip of slack-end tension per in of actuator travel (>0: retracting tightens),
  /// order fwd-act1, fwd-act2, bwd-act1, bwd-act2.
  std::array<double, 4> actuator_tension_kip_per_in{{0.0, 0.0, 0.0, 0.0}};
  double actuator1_initial_in = 0.655;       ///< x'_1
  double actuator2_initial_in = 0.8559;      ///< x'_2
};

/// Inputs of one step: the DamperInput of every model (drum displacement in, velocity in/s,
/// actuator positions in).
using BandBrakeInput = DamperInput;

/// Tensions at one instant (kip).
struct BandTensions {
  double slack_fwd_kip = 0.0, slack_bwd_kip = 0.0;  ///< (B2)
  double ratio_fwd = 1.0, ratio_bwd = 1.0;          ///< E_d of (B1)
  double fc_fwd_kip = 0.0, fc_bwd_kip = 0.0;        ///< (B3)
};

/// The band-brake model with its band stretch state s (in): a DamperModel (one continuous
/// state, s; the same physics for the hybrid loop and the CVODE reference).
class BandBrakeModel final : public DamperModel {
 public:
  explicit BandBrakeModel(const BandBrakeParams& params);

  /// Advances s over dt_s with the input held (exact solution of (B5) with S linearized at the
  /// start of each piece: slack zone, loaded zone; stable for any stiffness) and returns F (kip).
  double step(const BandBrakeInput& in, double dt_s) override;

  /// (B1)-(B3) at an input.
  BandTensions tensions(const BandBrakeInput& in) const;
  /// Kinetic friction F_c of one sliding direction (forward: drum velocity > 0), equal to
  /// tensions(in).fc_fwd_kip / fc_bwd_kip (Eqs. B1-B3), computing only that direction.
  double kinetic_friction_kip(const BandBrakeInput& in, bool forward) const;
  /// Capstan ratio E = exp(μθ) (B1).
  static double capstan_ratio(double friction_coefficient, double wrap_angle_rad);
  /// Band spring force S(s) (B4), kip.
  double spring_force_kip(double s_in) const;
  /// ds/dt of (B5), in/s.
  double stretch_rate(double s_in, const BandBrakeInput& in) const;
  /// F of (B6), kip.
  double force_kip(double s_in, const BandBrakeInput& in) const;
  /// Load-cell forces (kip) of actuators 1 and 2 at state s, (B6).
  std::array<double, 2> actuator_forces_kip(double s_in, const BandBrakeInput& in) const;
  /// Stretch state whose spring force is f (kip); |f| inside the backlash maps to the slack edge.
  double stretch_for_force(double f_kip) const;

  double stretch_in() const { return s_in_; }
  void set_stretch_in(double s) { s_in_ = s; }
  void reset() override { s_in_ = 0.0; }
  const BandBrakeParams& params() const { return p_; }

  // DamperModel: rest positions x'_1, x'_2; one continuous state s ((B5) and (B6)).
  double actuator1_rest_in() const override { return p_.actuator1_initial_in; }
  double actuator2_rest_in() const override { return p_.actuator2_initial_in; }
  int num_states() const override { return 1; }
  void initial_states(double* states) const override { states[0] = 0.0; }
  void state_rate(const double* states, const DamperInput& in, double* rate) const override {
    rate[0] = stretch_rate(states[0], in);
  }
  double force_for_states(const double* states, const DamperInput& in) const override {
    return force_kip(states[0], in);
  }
  std::unique_ptr<DamperModel> fresh_copy() const override { return std::make_unique<BandBrakeModel>(p_); }

 private:
  BandBrakeParams p_;
  double sigma0_ = 0.0;  // L k_b
  double s_in_ = 0.0;
};

}  // namespace damper
