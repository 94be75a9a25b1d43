#pragma once
/// @file brfd_model.h
/// The BRFD damper model: LuGre friction (Eqs. 1-3 of the BRFD paper, ../shared/seed) with
/// direction-dependent static and kinetic friction, and the semi-active kinetic friction of
/// Eq. (4) fed into the Stribeck function, Eq. (5). Units: kip, in, s.
///
/// The model is a pure function of its bristle state and its inputs; the same code serves
/// the virtual substructure, `hybridsim damper predict`, `diagnose` and the SUNDIALS
/// monolithic reference (bristle_rate() is the right-hand side of Eq. 1).

#include "damper/model/band_brake_model.h"
#include "damper/model/damper_model.h"
#include "damper/model/effects.h"
#include "damper/model/electric_actuator.h"

#include <array>
#include <deque>
#include <string>
#include <optional>
#include <vector>

namespace damper {

/// LuGre parameters, Eqs. (1)-(3). Forward means drum velocity v >= 0.
struct LugreParams {
  double sigma0_kip_per_in = 60.0;       ///< aggregate bristle stiffness σ0
  double sigma1_kip_s_per_in = 0.5;      ///< bristle micro-damping σ1
  double sigma2_kip_s_per_in = 0.05;     ///< viscous friction σ2
  double fs_fwd_kip = 2.4;               ///< static friction Fs, forward (magnitude)
  double fs_bwd_kip = 2.4;               ///< static friction Fs, backward (magnitude)
  double fc_fwd_kip = 2.0;               ///< kinetic friction Fc (= b of Eq. 4), forward
  double fc_bwd_kip = 2.0;               ///< kinetic friction Fc (= b of Eq. 4), backward
  double vs_in_per_s = 0.5;              ///< Stribeck velocity v_s
};

/// Semi-active part, Eq. (4): slopes m_ij (Table 1, kip/in) and scaling factors C_k (Table 2).
/// Row i of `slopes_kip_per_in` is m_i1, m_i2 (i = 1..4 stored at index i-1).
struct SemiActiveParams {
  std::array<std::array<double, 2>, 4> slopes_kip_per_in{{{-0.14, -0.15},
                                                          {-15.29, -13.00},
                                                          {-16.66, -15.77},
                                                          {-0.13, -0.15}}};
  std::array<double, 4> scaling{{119.68, 2.10, 1.94, 123.31}};  ///< C_1..C_4 (Table 2)
  double actuator1_initial_in = 0.655;   ///< x'_1: electric actuator 1 position at t = 0, in
  double actuator2_initial_in = 0.8559;  ///< x'_2: electric actuator 2 position at t = 0, in
  double fc_floor_kip = 0.05;            ///< Eq. (4) is clipped below at this kinetic friction
};

/// Optional b = F(v) of Eq. (4) ("for erratic or asymmetric excitations, b itself may be a
/// function of drum velocity"): b per direction, piecewise linear in the speed |v| and held
/// constant beyond the end points. Empty (the default) means b = fc_fwd_kip / fc_bwd_kip.
struct KineticFrictionCurve {
  std::vector<double> speed_in_per_s;  ///< strictly increasing, >= 0
  std::vector<double> fwd_kip;         ///< b for v >= 0 at each speed, kip (> 0)
  std::vector<double> bwd_kip;         ///< b for v < 0 at each speed, kip (> 0)
  bool empty() const { return speed_in_per_s.empty(); }
  /// b (kip) at drum velocity v; requires !empty(). Does not allocate.
  double at(double v_in_per_s) const;
};

/// passive_lugre: LuGre (Eqs. 1-3); semiactive (config name also `paper_semiactive`): the paper's
/// model, Eqs. (1)-(5); band_brake: BandBrakeModel (damper/model/band_brake_model.h).
enum class DamperKind { passive_lugre, semiactive, band_brake };

/// Everything needed to build a BrfdModel.
struct BrfdParams {
  DamperKind kind = DamperKind::semiactive;
  LugreParams lugre;
  SemiActiveParams semiactive;
  /// b = F(v), optional; when set it replaces fc_fwd_kip / fc_bwd_kip as b in both models.
  KineticFrictionCurve b_of_velocity;
  /// Physical extensions of the model (damper/model/effects.h: backlash, residual static force,
  /// actuator lag, asymmetry, velocity dependence, pre-tension), all absent by default. Found
  /// by `hybridsim diagnose` (docs/diagnose.md); config key `effects:`.
  ModelEffects effects;
  /// The band-brake model's parameters (used when kind == band_brake; the LuGre blocks are then unused).
  BandBrakeParams band_brake;
  /// The electric actuators that move x_1, x_2 (stroke, velocity limit, response; config key
  /// `electric_actuators:`). Used by the virtual substructure and the controller
  /// (control/controller.h); a run without a controller holds x'_1, x'_2 and never moves them.
  ElectricActuatorParams electric_actuators;
};

/// The BRFD friction model with its bristle state z (in): the DamperModel of the paper
/// (`passive_lugre` or `semiactive`).
class BrfdModel final : public DamperModel {
 public:
  explicit BrfdModel(const BrfdParams& params);

  /// Advances the bristle state over dt_s with the input held constant and returns the
  /// friction force (kip) at the end of the step, Eq. (3). The bristle ODE, Eq. (1), is
  /// linear in z for constant v, so the step uses its exact exponential solution:
  /// unconditionally stable for any σ0 (the bristle state is stiff at 1024 Hz).
  /// With effects (params().effects) the ODE stays piecewise linear in z (backlash dead zone,
  /// asymmetric stiffness, rest relaxation): the step chains the exact solutions of the pieces.
  /// The actuator lag and the low-passed speed of residual_static are advanced here too.
  double step(const DamperInput& in, double dt_s) override;

  /// b of Eq. (4), kip: fc_fwd_kip / fc_bwd_kip by the sign of v, or b_of_velocity if set.
  double base_kinetic_friction_kip(double v_in_per_s) const;
  /// Kinetic friction Fc (kip, magnitude): the constant b per direction for passive LuGre,
  /// Eq. (4) of the paper for the semi-active model (with effects: lagged actuator positions,
  /// pre-tension and asymmetry factors).
  double kinetic_friction_kip(const DamperInput& in) const;
  /// Stribeck function g(v), Eqs. (2)/(5), kip (with effects: velocity effect).
  double stribeck_kip(const DamperInput& in) const;
  /// dz/dt of Eq. (1), in/s, for bristle state z (in). With effects it includes the backlash
  /// dead zone, asymmetric stiffness and the rest relaxation; the actuator lag and the
  /// low-passed speed are taken from the model's state (advanced only by step()).
  double bristle_rate(double z_in, const DamperInput& in) const;
  /// Friction force, Eq. (3), kip, for bristle state z (with effects: F = S(z) + σ1 dz/dt + σ2 v).
  double force_kip(double z_in, const DamperInput& in) const;
  /// Band spring force S(z), kip: σ0 z without effects (Eq. 3's first term).
  double spring_force_kip(double z_in) const;
  /// Bristle state whose spring force is f_kip (inverse of spring_force_kip; f = 0 gives z = 0).
  double bristle_for_force(double f_kip) const;
  /// Initial bristle state for a measured force f_kip at the start of a record: bristle_for_force,
  /// except with backlash, where a force within 10 % of the smaller Fc places the state inside the
  /// slack in proportion (a band at rest with almost no force need not be taut).
  double initial_bristle_for_force(double f_kip) const;

  double bristle_in() const { return z_in_; }
  /// Sets the bristle state (and the states that follow it: the held state at rest, the slow
  /// contact element of transition_shape at the same force ratio).
  void set_bristle_in(double z_in);
  /// The drum displacement the run starts from (self_energizing's drum_start_share counts the
  /// rotation from it); without a call, the displacement of the first step.
  void set_drum_start_in(double d_in) { drum_start_in_ = d_in; }
  /// z = 0 and the effect states back to their initial values.
  void reset() override;

  // DamperModel: rest positions x'_1, x'_2; one continuous state, z (bristle_rate, force_kip).
  double actuator1_rest_in() const override { return params_.semiactive.actuator1_initial_in; }
  double actuator2_rest_in() const override { return params_.semiactive.actuator2_initial_in; }
  int num_states() const override { return 1; }
  void initial_states(double* states) const override { states[0] = 0.0; }
  void state_rate(const double* states, const DamperInput& in, double* rate) const override {
    rate[0] = bristle_rate(states[0], in);
  }
  double force_for_states(const double* states, const DamperInput& in) const override {
    return force_kip(states[0], in);
  }
  std::unique_ptr<DamperModel> fresh_copy() const override { return std::make_unique<BrfdModel>(params_); }
  const BrfdParams& params() const { return params_; }

 private:
  struct Levels {
    double fc, fs;   // kinetic and static friction (kip, magnitudes) of one direction
    double tension;  // N_λ of the pretension effect (1 without it)
    double passive;  // b, the passive kinetic friction of the direction (kip)
  };
  Levels levels(const DamperInput& in, bool forward) const;
  struct Frame {
    double g = 1.0;        // Stribeck function g(v), kip
    double tension = 1.0;  // N_λ
    double servo = 0.0;    // η / b + χ of self_energizing's band-force feedback, 1/kip
    double servo_share = 0.0;  // η
    bool servo_on = false;     // the self-servo factor φ_s applies
    bool servo_lagged = false;      // φ_s sees the lagged force (band_force_lag_s > 0)
    double servo_lagged_kip = 0.0;  // max(0, sgn(v) y), kip
    double servo_level = 0.0;  // the part of g that φ_s scales (all of g, or Eq. (4)'s Fc part), kip
    double relax = 0.0;    // w / τ_r of residual_static, 1/s
    double motion = 1.0;   // asymmetry's 1 ± a_m: the bristle rate's stiffness by the direction of motion
    double band_spring_kip = 0.0;  // self_energizing's k_b d, kip
    double viscous_velocity = 0.0;  // v_σ: the velocity the viscous force sees (velocity's lag_viscous_share)
    bool viscous_lagged = false;
    double target_pos = 0.0, target_neg = 0.0;  // z_r for z >= 0 / z < 0, in
  };
  Frame frame(const DamperInput& in) const;
  /// The level the bristle law sees with the self-servo at this band force: g + (φ_s − 1) × servo_level.
  double servo_level_kip(double band_kip, const Frame& f) const;
  /// The carried force φ_s sees: |band_kip| at once, or the lagged force (effects.h).
  double servo_feedback_kip(double band_kip, const Frame& f) const;
  double rate_in_frame(double z, double v, const Frame& f) const;
  double force_in_frame(double z, double v, const Frame& f) const;
  double stiffness(bool positive_z) const;
  double step_with_effects(const DamperInput& in, double dt_s);
  /// The states of step_with_effects (bristle, actuator lag, rest speed, slip memory); returns the force.
  double step_states_with_effects(const DamperInput& in, double dt_s);

  BrfdParams params_;
  bool has_effects_ = false;
  double z_in_ = 0.0;
  double lag1_in_ = 0.0, lag2_in_ = 0.0;  ///< x~_1, x~_2 of actuator_lag (first-order stage)
  double resp1_in_ = 0.0, resp2_in_ = 0.0;  ///< y_1, y_2 of actuator_lag (second-order stage)
  /// actuator_lag's delay line: (time, x_1, x_2) back to t − t_d, oldest first; and its clock, s.
  std::deque<std::array<double, 3>> actuator_history_;
  double actuator_clock_s_ = 0.0;
  double rated1_in_ = 0.0, rated2_in_ = 0.0;  ///< actuator positions after the rate limit, in
  double played1_in_ = 0.0, played2_in_ = 0.0;  ///< actuator positions after the drive's play, in
  double resp1_rate_ = 0.0, resp2_rate_ = 0.0;  ///< dy_k/dt, in/s
  double soft_spring(double over) const;  ///< h(u) of backlash's re-tensioning (u itself without it)
  double slow_speed_ = 0.0;               ///< s~ of residual_static, in/s
  double held_z_in_ = 0.0;                ///< z_h of residual_static: z when the drum last moved, in
  double rest_time_s_ = 0.0;              ///< t_r of residual_static: time since the drum came to rest, s
  double ring_time_s_ = -1.0;             ///< t_s of residual_static's ring-down: time since the drum stopped (< 0: moving), s
  double ring_sign_ = 0.0;                ///< sign(F_stop) of the ring-down
  double reversal_time_s_ = -1.0;         ///< t of backlash's impact ring: time since the last reversal (< 0: none yet), s
  bool impact_pending_ = false;           ///< a reversal seen, the impact ring not yet started (clearance open)
  double reversal_force_kip_ = 0.0;       ///< F_rev of the impact ring: the force just before the last reversal, kip
  double last_force_kip_ = 0.0;           ///< the friction force of the last step (without the rings), kip
  double rest_rate_per_s_ = -1.0;         ///< residual_static's rate over the current step (< 0: w/τ_r)
  double slow_z_in_ = 0.0;                ///< z2 of transition_shape's slow contact element, in
  double overshoot_kip_ = 0.0;            ///< F_2 of transition_shape's Bliman-Sorine overshoot, kip
  double pulse_fast_ = 0.0, pulse_slow_ = 0.0;  ///< w1, w2 of transition_shape's travel pulse (−1..1)
  double pulse_kip_ = 0.0;                ///< the travel pulse's force q Fc (w1 − w2)/(2 P_max), kip
  /// e_k of transition_shape's Iwan bank: each element's force (before N_λ), kip; and w_k, its slip share of g
  std::array<double, TransitionShapeEffect::kBankElements> bank_kip_{}, bank_limit_{};
  double bank_sum_kip() const;  ///< Σ e_k
  double rate_state_s_ = 0.0;             ///< θ of the velocity effect's slip memory, s
  double stribeck_speed_ = 0.0;           ///< ṽ_L: the lagged speed of the velocity effect, in/s
  double lagged_velocity_ = 0.0;          ///< v_L: the drum velocity through the same lag (signed), in/s
  double friction_work_kip_in_ = 0.0;     ///< W of the pretension effect's wear: ∫|F v| dt, kip·in
  double servo_band_kip_ = 0.0;           ///< y of self_energizing's lagged servo: the force seen through τ_s, kip
  double band_work_fwd_kip_in_ = 0.0;     ///< W_fwd of asymmetry's band fade: ∫|F v| dt moving forward, kip·in
  double band_work_bwd_kip_in_ = 0.0;     ///< W_bwd: the same moving backward
  static constexpr double kEngagedTravelIn = 1e3;  ///< s at the start: long past any reversal
  double reversal_travel_in_ = kEngagedTravelIn;  ///< s of backlash's take-up: drum travel since the last reversal, in
  double stroke_travel_in_ = 0.0;  ///< drum travel since the last reversal (from the start, uncapped), in
  double previous_stroke_in_ = 0.0;  ///< S_p of backlash's take-up: the travel between the last two reversals, in
  int last_direction_ = 0;                ///< +1/−1: the direction the drum last moved in (0: not yet known)
  double drum_position_in_ = 0.0;         ///< ∫v dt since the start: the drum position the reversals are told on, in
  double turn_position_in_ = 0.0;         ///< the furthest position of the last direction since its reversal, in
  double turn_force_kip_ = 0.0;           ///< the force on the step that furthest position was reached, kip
  double strike_clock_s_ = -1.0;          ///< time since the drum passed impact_travel_in back from the turn point (< 0: not), s
  double strike_speed_in_per_s_ = 0.0;    ///< the drum speed on the step the drum passed impact_travel_in back, in/s
  double impact_speed_in_per_s_ = 0.0;    ///< v_i of the ring now ringing: the drum speed where its clearance closed, in/s
  std::optional<double> drum_start_in_;   ///< drum displacement at the start of the run (first step), in
  std::optional<double> play_band_in_;    ///< x_b of backlash's drive-line play: the band's side, in
  double play_drum_in_ = 0.0;             ///< the drum displacement of the last step (travel in the play), in
  double rotation_in(const DamperInput& in) const;  ///< d of self_energizing (its drum_start_share)
  double engaged_share(double z) const;   ///< e(z) of backlash (1 without it)
  /// δ of backlash's slack as it acts now: 0 until the first turn of the drum where the play is
  /// taken up by the first motion (first_motion_engages), slack_in (+ the load-dependent part) otherwise
  double slack_now_in() const;
  bool play_opened_ = true;  ///< the slack acts (false: first_motion_engages and no turn of the drum yet)
  double load_slack_in_ = 0.0;  ///< κ_s |F_turn| of backlash's load-dependent slack, set at each reversal, in
  double rate_factor(double speed) const;  ///< φ of the velocity effect's log-rate levels (1 without it)
  /// transition_shape's sub-step bound: slope_to_steady_[i] = the largest |d(rate/|v|)/dw| of the
  /// shaped bristle law between w_i and the steady state w = 1, w = sign(v) y on the grid
  /// kSlopeGridLo + i kSlopeGridStep (empty without a nonlinear transition_shape).
  std::vector<double> slope_to_steady_;
  static constexpr double kSlopeGridLo = -4.0, kSlopeGridStep = 0.01;
  /// That bound for a step starting at w0; < 0 when w0 is off the grid.
  double shape_slope_to_steady(double w0) const;
};

/// The damper model a BrfdParams describes (the factory every user of a config calls).
std::unique_ptr<DamperModel> make_damper_model(const BrfdParams& params);

/// Name of a DamperKind as used in configs ("passive_lugre", "semiactive").
std::string to_string(DamperKind kind);
/// Parses a DamperKind; throws std::invalid_argument naming the value.
DamperKind damper_kind_from_string(const std::string& name);

}  // namespace damper
