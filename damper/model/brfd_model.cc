#include "damper/model/brfd_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace damper {

namespace {
// Initial low-passed speed of residual_static (in/s): the model starts "moving", so a record
// that starts at rest is not relaxed before its first motion.
constexpr double kInitialSlowSpeed = 1e3;
}  // namespace

std::unique_ptr<DamperModel> make_damper_model(const BrfdParams& params) {
  if (params.kind == DamperKind::band_brake) return std::make_unique<BandBrakeModel>(params.band_brake);
  return std::make_unique<BrfdModel>(params);
}

namespace {

// |d(rate/|v|)/dw| of transition_shape's bristle law at w = sign(v) y (rate_in_frame): the shaped
// ratio s(w) = sign(w) |w|^α e(w) (1 − u [w < 0]), the breakaway gate e only while the band loads
// (e = 1 for w <= 0), and Dahl's sign(q)|q|^n of q = 1 − s(w). The
// α term is taken at |w| >= 0.05 for α < 1 (its slope is unbounded at w = 0), Dahl's at
// |q| >= 0.05 for n < 1, as the sub-step bound always did.
double shape_slope(const TransitionShapeEffect& ts, double w) {
  const double aw = std::abs(w), alpha = ts.exponent, beta = ts.breakaway_ratio;
  const double power = std::pow(aw, alpha);
  const double power_slope = alpha * std::pow(alpha < 1.0 ? std::max(aw, 0.05) : aw, alpha - 1.0);
  double gate = 1.0, gate_slope = 0.0;
  if (beta > 0.0 && w > 0.0) {  // the breakaway gate acts while the band loads (w > 0) only
    const double full = ts.breakaway_full_slip_ratio();
    const double phase = M_PI * (aw - 0.5 * (beta + full)) / (full - beta);
    gate = aw <= beta ? 0.0 : aw >= full ? 1.0 : 0.5 + 0.5 * std::sin(phase);
    gate_slope = aw <= beta || aw >= full ? 0.0 : 0.5 * M_PI / (full - beta) * std::cos(phase);
  }
  const double unloading = w < 0.0 ? 1.0 - ts.elastic_unloading : 1.0;
  const double shaped = std::copysign(power * gate * unloading, w);
  const double shaped_slope = unloading * (power_slope * gate + power * gate_slope);
  const double n = ts.dahl_exponent, q = std::abs(1.0 - shaped);
  const double dahl = n == 1.0 ? 1.0 : n * std::pow(n < 1.0 ? std::max(q, 0.05) : q, n - 1.0);
  return dahl * shaped_slope;
}

// One actuator's Eq. (4) term g u under pretension's band stretch law (clamp_stiffening_per_in =
// beta, 1/in): the band's tension rises exponentially with its stretch (Fung's J-shaped law),
// |g| (e^(beta t) - 1)/beta with t = g u/|g| the tightening travel (in); beta > 0 stiffens as the
// band is drawn taut and softens as it is released, beta < 0 saturates. Slope |g| at t = 0.
double stretched_clamp_term_kip(double term_kip, double gain_kip_per_in, double beta_per_in) {
  const double g = std::abs(gain_kip_per_in);
  if (g <= 0.0) return term_kip;
  const double travel_in = term_kip / g;
  return g * std::expm1(std::min(beta_per_in * travel_in, 30.0)) / beta_per_in;
}

// The same term under pretension's symmetric stretch law (clamp_saturation_per_in = kappa, 1/in):
// |g| tanh(kappa t)/kappa (kappa > 0: saturating alike tightening and releasing) or
// |g| sinh(-kappa t)/(-kappa) (kappa < 0: stiffening alike); slope |g| at t = 0 (effects.h).
double saturated_clamp_term_kip(double term_kip, double gain_kip_per_in, double kappa_per_in) {
  const double g = std::abs(gain_kip_per_in);
  if (g <= 0.0) return term_kip;
  const double travel_in = term_kip / g;
  if (kappa_per_in > 0.0) return g * std::tanh(kappa_per_in * travel_in) / kappa_per_in;
  return g * std::sinh(std::clamp(-kappa_per_in * travel_in, -30.0, 30.0)) / -kappa_per_in;
}

}  // namespace

BrfdModel::BrfdModel(const BrfdParams& params)
    : params_(params), has_effects_(!params.effects.empty()) {
  const std::optional<TransitionShapeEffect>& ts = params_.effects.transition_shape;
  if (ts && ts->nonlinear()) {
    // Running maxima of the slope from each grid point towards w = 1, where the bristle state
    // settles (for constant v it moves monotonically towards it).
    const int n = static_cast<int>(std::lround(-2.0 * kSlopeGridLo / kSlopeGridStep)) + 1;
    const int one = static_cast<int>(std::lround((1.0 - kSlopeGridLo) / kSlopeGridStep));
    slope_to_steady_.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) slope_to_steady_[i] = shape_slope(*ts, kSlopeGridLo + i * kSlopeGridStep);
    for (int i = one - 1; i >= 0; --i) slope_to_steady_[i] = std::max(slope_to_steady_[i], slope_to_steady_[i + 1]);
    for (int i = one + 1; i < n; ++i) slope_to_steady_[i] = std::max(slope_to_steady_[i], slope_to_steady_[i - 1]);
  }
  reset();
}

double BrfdModel::shape_slope_to_steady(double w0) const {
  if (slope_to_steady_.empty()) return -1.0;
  const double x = (w0 - kSlopeGridLo) / kSlopeGridStep;
  if (!(x >= 0.0) || x >= static_cast<double>(slope_to_steady_.size() - 1)) return -1.0;
  // The cell [w_i, w_i+1] holding w0 and everything from it to w = 1: below 1 the maxima grow
  // towards lower w (take w_i's), above 1 towards higher w (take w_i+1's).
  const std::size_t i = static_cast<std::size_t>(x);
  const double one = (1.0 - kSlopeGridLo) / kSlopeGridStep;
  return static_cast<double>(i) < one ? slope_to_steady_[i] : slope_to_steady_[i + 1];
}

void BrfdModel::reset() {
  z_in_ = 0.0;
  lag1_in_ = params_.semiactive.actuator1_initial_in;
  lag2_in_ = params_.semiactive.actuator2_initial_in;
  resp1_in_ = lag1_in_;
  rated1_in_ = lag1_in_;
  rated2_in_ = lag2_in_;
  played1_in_ = lag1_in_;
  played2_in_ = lag2_in_;
  actuator_clock_s_ = 0.0;
  actuator_history_.clear();
  actuator_history_.push_back({0.0, lag1_in_, lag2_in_});  // at x'_k at the start and before it
  resp2_in_ = lag2_in_;
  resp1_rate_ = resp2_rate_ = 0.0;
  slow_speed_ = kInitialSlowSpeed;
  held_z_in_ = 0.0;
  rest_time_s_ = 0.0;
  ring_time_s_ = -1.0;
  ring_sign_ = 0.0;
  reversal_time_s_ = -1.0;
  impact_pending_ = false;
  reversal_force_kip_ = last_force_kip_ = 0.0;
  rest_rate_per_s_ = -1.0;
  slow_z_in_ = 0.0;
  overshoot_kip_ = 0.0;
  pulse_fast_ = pulse_slow_ = 1.0;  // as set_bristle_in(0): the memories at +1, no pulse
  pulse_kip_ = 0.0;
  servo_band_kip_ = 0.0;
  bank_kip_.fill(0.0);
  const TransitionShapeEffect* bank = params_.effects.transition_shape ? &*params_.effects.transition_shape : nullptr;
  for (int k = 0; k < TransitionShapeEffect::kBankElements; ++k)
    bank_limit_[k] = bank && bank->bank_share > 0.0 ? bank->bank_limit_share(k) : 0.0;
  const VelocityEffect* ve = params_.effects.velocity ? &*params_.effects.velocity : nullptr;
  rate_state_s_ = ve && ve->memory_in > 0.0 ? ve->memory_in / ve->reference_speed_in_per_s : 0.0;
  stribeck_speed_ = 0.0;
  lagged_velocity_ = 0.0;
  friction_work_kip_in_ = 0.0;
  band_work_fwd_kip_in_ = band_work_bwd_kip_in_ = 0.0;
  reversal_travel_in_ = kEngagedTravelIn;
  stroke_travel_in_ = previous_stroke_in_ = 0.0;
  last_direction_ = 0;
  drum_position_in_ = turn_position_in_ = turn_force_kip_ = 0.0;
  play_opened_ = !(params_.effects.backlash && params_.effects.backlash->first_motion_engages >= 0.5);
  load_slack_in_ = 0.0;
  strike_clock_s_ = -1.0;
  strike_speed_in_per_s_ = impact_speed_in_per_s_ = 0.0;
  drum_start_in_.reset();
  play_band_in_.reset();
  play_drum_in_ = 0.0;
}

double BrfdModel::rotation_in(const DamperInput& in) const {
  const SelfEnergizingEffect& se = *params_.effects.self_energizing;
  return in.drum_disp_in - se.drum_start_share * drum_start_in_.value_or(in.drum_disp_in);
}

void BrfdModel::set_bristle_in(double z_in) {
  z_in_ = held_z_in_ = z_in;
  // The band loaded by the last motion; with the play taken up by the first motion
  // (first_motion_engages), not known: the first travel sets it.
  last_direction_ = play_opened_ ? (z_in > 0.0 ? 1 : z_in < 0.0 ? -1 : 0) : 0;
  const TransitionShapeEffect* ts = params_.effects.transition_shape ? &*params_.effects.transition_shape : nullptr;
  // The slow element carries the same share of its capacity as the main one: k2 z2 = S(z)/σ0.
  slow_z_in_ = ts && ts->slow_share > 0.0
                   ? spring_force_kip(z_in) / (params_.lugre.sigma0_kip_per_in * ts->slow_stiffness_ratio)
                   : 0.0;
  // The overshoot's slow element as at steady state: the held force shared (1 + θ) and −θ.
  overshoot_kip_ = ts && ts->overshoot_share > 0.0 ? -ts->overshoot_share * spring_force_kip(z_in) : 0.0;
  // The travel pulse's memories: the direction the band was last loaded in, no pulse held.
  pulse_fast_ = pulse_slow_ = z_in >= 0.0 ? 1.0 : -1.0;
  pulse_kip_ = 0.0;
  // The Iwan bank: the held force shared by the elements' slip shares.
  for (int k = 0; k < TransitionShapeEffect::kBankElements; ++k) bank_kip_[k] = bank_limit_[k] * spring_force_kip(z_in);
  servo_band_kip_ = spring_force_kip(z_in);  // the lagged servo as at a steady hold
}

double BrfdModel::bank_sum_kip() const {
  double sum = 0.0;
  for (const double e : bank_kip_) sum += e;
  return sum;
}

double BrfdModel::rate_factor(double speed) const {
  const VelocityEffect* ve = params_.effects.velocity ? &*params_.effects.velocity : nullptr;
  if (!ve || (ve->rate_slope == 0.0 && ve->direct_slope == 0.0 && ve->flash_weakening == 0.0 && ve->peak_share == 0.0 &&
              ve->speed_power_share == 0.0))
    return 1.0;
  // Flash heating above v_w: × (1 − a_w (1 − v_w/|v|)).
  double flash = ve->flash_weakening != 0.0 && speed > ve->weakening_speed_in_per_s
                     ? 1.0 - ve->flash_weakening * (1.0 - ve->weakening_speed_in_per_s / speed)
                     : 1.0;
  if (ve->peak_share != 0.0 && speed > 0.0) {  // a friction peak over log speed (Grosch): × (1 + A e^(−ln²(v/v_p)/(2w²)))
    const double decades = std::log(speed / ve->peak_speed_in_per_s) / ve->peak_log_width;
    flash *= 1.0 + ve->peak_share * std::exp(-0.5 * decades * decades);
  }
  // A power law of the speed (third body): × (1 + B (|v| / 1 in/s)^m), effects.h.
  if (ve->speed_power_share != 0.0) flash *= 1.0 + ve->speed_power_share * std::pow(speed, ve->speed_power_exponent);
  if (ve->rate_slope == 0.0 && ve->direct_slope == 0.0) return std::max(0.2, flash);
  const double now = speed + VelocityEffect::kSpeedFloorInPerS;
  const double seen = ve->memory_in > 0.0 ? ve->memory_in / rate_state_s_ : now;
  const double c = ve->rate_regularization;  // ln(c + v/v_r): 0 the plain law, 1 regularized (effects.h)
  const double direct = ve->direct_slope != 0.0 ? ve->direct_slope * std::log(c + now / ve->reference_speed_in_per_s) : 0.0;
  const double state = ve->rate_slope != 0.0 ? ve->rate_slope * std::log(c + seen / ve->reference_speed_in_per_s) : 0.0;
  return std::max(0.2, (1.0 + direct + state) * flash);
}

double BrfdModel::slack_now_in() const {
  return params_.effects.backlash && play_opened_ ? params_.effects.backlash->slack_in + load_slack_in_ : 0.0;
}

double BrfdModel::engaged_share(double z) const {
  const BacklashEffect* b = params_.effects.backlash ? &*params_.effects.backlash : nullptr;
  const double slack = slack_now_in();
  if (!b || (slack == 0.0 && b->retension_in == 0.0)) return 1.0;
  const double over = std::abs(z) - slack;
  if (over <= 0.0) return 0.0;
  const double width = std::max(b->retension_in, 0.25 * slack);
  return std::min(1.0, over / width);
}

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
  if (has_effects_) return levels(in, in.drum_vel_in_per_s >= 0.0).fc;
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

BrfdModel::Levels BrfdModel::levels(const DamperInput& in, bool forward) const {
  const LugreParams& p = params_.lugre;
  const ModelEffects& e = params_.effects;
  const double speed = std::abs(in.drum_vel_in_per_s);
  double b = forward ? p.fc_fwd_kip : p.fc_bwd_kip;
  if (!params_.b_of_velocity.empty()) b = params_.b_of_velocity.at(forward ? speed : -std::max(speed, 1e-300));
  double dfc = 0.0;  // Eq. (4) increment, with the lagged positions x~ if actuator_lag is on
  if (params_.kind == DamperKind::semiactive) {
    const SemiActiveParams& s = params_.semiactive;
    const int a = forward ? 0 : 2;
    const int c = forward ? 1 : 3;
    const double gain1 = s.scaling[a] * s.slopes_kip_per_in[a][0] + s.scaling[c] * s.slopes_kip_per_in[c][0];
    const double gain2 = s.scaling[a] * s.slopes_kip_per_in[a][1] + s.scaling[c] * s.slopes_kip_per_in[c][1];
    const bool second = e.actuator_lag && e.actuator_lag->natural_period_s > 0.0;
    const double late = e.actuator_lag ? e.actuator_lag->lagged_share : 0.0;  // (1 − a) x + a y
    const double x1 = in.actuator1_in + late * ((second ? resp1_in_ : lag1_in_) - in.actuator1_in);
    const double x2 = in.actuator2_in + late * ((second ? resp2_in_ : lag2_in_) - in.actuator2_in);
    double term1 = gain1 * (x1 - s.actuator1_initial_in);
    double term2 = gain2 * (x2 - s.actuator2_initial_in);
    // pretension's band stretch law, per actuator: g u -> |g| (e^(beta t) - 1)/beta, t = g u/|g| the
    // tightening travel (in) of that actuator's band (effects.h, clamp_stiffening_per_in).
    if (e.pretension && e.pretension->clamp_stiffening_per_in != 0.0) {
      term1 = stretched_clamp_term_kip(term1, gain1, e.pretension->clamp_stiffening_per_in);
      term2 = stretched_clamp_term_kip(term2, gain2, e.pretension->clamp_stiffening_per_in);
    }
    if (e.pretension && e.pretension->clamp_saturation_per_in != 0.0) {  // alike both ways (effects.h)
      term1 = saturated_clamp_term_kip(term1, gain1, e.pretension->clamp_saturation_per_in);
      term2 = saturated_clamp_term_kip(term2, gain2, e.pretension->clamp_saturation_per_in);
    }
    dfc = term1 + term2;
    // pretension's Fung law on the tension ratio: ΔFc → (b/γ)(e^(γ ΔFc/b) − 1) (effects.h)
    if (e.pretension && e.pretension->clamp_stiffening_per_tension != 0.0 && b > 0.0)
      dfc = b * std::expm1(std::min(e.pretension->clamp_stiffening_per_tension * dfc / b, 30.0)) /
            e.pretension->clamp_stiffening_per_tension;
    // pretension's clamping law: ΔFc = k b (N^q − 1), N = 1 + ΔFc/b the tension ratio of Eq. (4).
    if (e.pretension && e.pretension->clamp_exponent != 1.0 && b > 0.0)
      dfc = b * (std::pow(std::max(1.0 + dfc / b, 0.01), e.pretension->clamp_exponent) - 1.0);
    if (e.pretension) {
      dfc *= e.pretension->clamp_gain;
      if (dfc < 0.0) dfc *= e.pretension->release_gain;  // a kink at the pre-tension (effects.h)
      // Non-additive clamping of the two actuators: c u1 u2.
      dfc += e.pretension->actuator_coupling_kip_per_in2 * (x1 - s.actuator1_initial_in) * (x2 - s.actuator2_initial_in);
    }
  }
  double fc = b + dfc;
  double fs = forward ? p.fs_fwd_kip : p.fs_bwd_kip;
  double tension = 1.0;
  double factor = 1.0;
  if (e.pretension) {
    // Fs follows a share of the Eq. (4) tension change; a share of it scales the band force at once.
    fs *= std::max(0.05, 1.0 + e.pretension->fs_share * dfc / b);
    tension = std::max(0.05, 1.0 + e.pretension->instant_share * dfc / b);
    if (e.pretension->wear_per_kip_in != 0.0) {
      // Linear in the friction work W, or saturating over W0: w W0 (1 − e^(−W/W0)) (effects.h).
      const double w0 = e.pretension->wear_saturation_kip_in;
      const double worn = w0 > 0.0 ? -w0 * std::expm1(-friction_work_kip_in_ / w0) : friction_work_kip_in_;
      const double psi = std::max(0.05, 1.0 - e.pretension->wear_per_kip_in * worn);
      // The pre-tension b loosens by ψ, the actuators' increment by the share u of it (effects.h).
      fc = psi * b + (1.0 - e.pretension->wear_actuator_share * (1.0 - psi)) * dfc;
      fs *= psi;
    }
  }
  double rotation = 1.0;  // self_energizing's rotation terms: on Fc, and on Fs by its share (effects.h)
  if (e.self_energizing) {
    const double kappa = forward ? e.self_energizing->drum_fwd_per_in : e.self_energizing->drum_bwd_per_in;
    const double d = rotation_in(in);
    const double ad = std::abs(d);
    const double grow = e.self_energizing->abs_exponent == 1.0 ? ad : std::pow(ad, e.self_energizing->abs_exponent);
    rotation = std::max(0.05, 1.0 + kappa * d + e.self_energizing->drum_abs_per_in * grow);
    // the wrap built up over the stroke since the last reversal (effects.h)
    const double k_wrap = forward ? e.self_energizing->stroke_wrap_fwd : e.self_energizing->stroke_wrap_bwd;
    if (k_wrap != 0.0)
      rotation *= std::max(0.05, 1.0 + k_wrap * (1.0 - std::exp(-stroke_travel_in_ / e.self_energizing->stroke_wrap_length_in)));
  }
  // asymmetry's and velocity's level factors: on Fc, and on Fs by their stiction shares (effects.h)
  double kinetic = 1.0, stiction = 1.0;
  if (e.asymmetry) {  // each band its level difference: constant, its own speed law, its own fade (effects.h)
    const double asym = e.asymmetry->factor(e.asymmetry->level_at(speed, forward ? band_work_fwd_kip_in_ : band_work_bwd_kip_in_, in.drum_disp_in), forward);
    kinetic *= asym;
    stiction *= 1.0 - e.asymmetry->stiction_share * (1.0 - asym);
  }
  if (e.velocity) {
    const double phi = rate_factor(speed);
    kinetic *= phi;
    stiction *= 1.0 - e.velocity->rate_stiction_share * (1.0 - phi);
  }
  // velocity's flash temperature by the load: the kinetic level × φ_T = 1 − c Fc |v|^n_T, the
  // stiction level × (1 − w_T + w_T φ_T) (effects.h).
  double kinetic_only = 1.0;
  if (e.velocity && e.velocity->flash_load_per_kip != 0.0)
    kinetic_only = std::max(0.2, 1.0 - e.velocity->flash_load_per_kip * fc * std::pow(speed, e.velocity->flash_speed_exponent));
  if (e.backlash && e.backlash->takeup_dip > 0.0) {
    // Grip lost at the last reversal, taken up with travel: the capacity, and the share f of it in
    // the band force at once (f = 1: the bristle state unchanged, the force scaled; effects.h).
    // Each band its own take-up (takeup_forward_share h_t), by the direction since the last reversal.
    const double h = e.backlash->takeup_forward_share;
    const double band_gain = last_direction_ >= 0 ? 2.0 * h : 2.0 * (1.0 - h);
    const double stroke = e.backlash->takeup_stroke_in;  // the loss by the previous stroke, min(1, S_p/L_s)
    const double by_stroke = stroke > 0.0 ? std::min(1.0, previous_stroke_in_ / stroke) : 1.0;
    const double lost =
        reversal_travel_in_ < e.backlash->takeup_onset_in  // the band still taut (its onset δ_t)
            ? 0.0
            : std::min(0.95, band_gain * by_stroke * e.backlash->takeup_dip * std::exp(-reversal_travel_in_ / e.backlash->takeup_length_in));
    factor *= 1.0 - e.backlash->takeup_level_share * lost;  // ℓ = 0: the levels kept, the stiffness only
    tension *= 1.0 - e.backlash->takeup_force_share * lost;
  }
  // transition_shape's slip weakening since the reversal: both levels × (1 + ρ_w W(s)) (effects.h)
  if (e.transition_shape && e.transition_shape->weakening_share != 0.0)
    factor *= 1.0 + e.transition_shape->weakening_share * e.transition_shape->slip_weakening(stroke_travel_in_);
  fc *= factor * kinetic * kinetic_only * rotation;
  fs *= factor * stiction * (e.velocity ? 1.0 - e.velocity->flash_stiction_share * (1.0 - kinetic_only) : 1.0) *
        (e.self_energizing ? 1.0 - e.self_energizing->stiction_share * (1.0 - rotation) : 1.0);
  if (params_.kind == DamperKind::semiactive) fc = std::max(fc, params_.semiactive.fc_floor_kip);
  return {std::max(fc, 1e-6), std::max(fs, 1e-6), tension, b};
}

double BrfdModel::stribeck_kip(const DamperInput& in) const {
  const LugreParams& p = params_.lugre;
  const double v = in.drum_vel_in_per_s;
  if (has_effects_) return frame(in).g;  // Eq. (2)/(5) with the effects
  const double fs = v >= 0.0 ? p.fs_fwd_kip : p.fs_bwd_kip;
  const double fc = kinetic_friction_kip(in);
  const double r = v / p.vs_in_per_s;
  return fc + (fs - fc) * std::exp(-r * r);  // Eq. (2) / Eq. (5)
}

double BrfdModel::stiffness(bool positive_z) const {
  const double s0 = params_.lugre.sigma0_kip_per_in * (params_.effects.backlash ? params_.effects.backlash->stiffness_ratio : 1.0);
  if (!params_.effects.asymmetry) return s0;
  return s0 * params_.effects.asymmetry->factor(params_.effects.asymmetry->stiffness, positive_z);
}

double BrfdModel::soft_spring(double over) const {
  const double eps = params_.effects.backlash ? params_.effects.backlash->retension_in : 0.0;
  if (eps <= 0.0) return over;
  return over < eps ? over * over / (2.0 * eps) : over - 0.5 * eps;  // stiffness grows over ε
}

double BrfdModel::spring_force_kip(double z) const {
  if (!has_effects_) return params_.lugre.sigma0_kip_per_in * z;
  const double slack = slack_now_in();
  const double over = soft_spring(std::max(std::abs(z) - slack, 0.0));  // backlash dead zone D(z)
  return z >= 0.0 ? stiffness(true) * over : -stiffness(false) * over;
}

double BrfdModel::bristle_for_force(double f) const {
  if (!has_effects_) return f / params_.lugre.sigma0_kip_per_in;
  const double slack = slack_now_in();
  const double eps = params_.effects.backlash ? params_.effects.backlash->retension_in : 0.0;
  auto over_of = [eps](double s) {  // inverse of h: s = h(u)
    if (eps <= 0.0) return s;
    return s < 0.5 * eps ? std::sqrt(2.0 * eps * s) : s + 0.5 * eps;
  };
  if (f > 0.0) return slack + over_of(f / stiffness(true));
  if (f < 0.0) return -slack - over_of(-f / stiffness(false));
  return 0.0;
}

double BrfdModel::initial_bristle_for_force(double f) const {
  if (!has_effects_ || !params_.effects.backlash) return bristle_for_force(f);
  // A force within 10 % of the smaller kinetic friction may be a band still in its slack: the state
  // moves through the slack in proportion (a force of exactly 0 is the centre of the slack).
  const double slack = slack_now_in();
  const double engage = 0.1 * std::min(params_.lugre.fc_fwd_kip, params_.lugre.fc_bwd_kip);
  const double share = engage > 0.0 ? std::min(1.0, std::abs(f) / engage) : 1.0;
  const double z = bristle_for_force(f);
  return z - (f > 0.0 ? 1.0 : f < 0.0 ? -1.0 : 0.0) * slack * (1.0 - share);
}

double BrfdModel::servo_level_kip(double band_kip, const Frame& f) const {
  if (!f.servo_on) return f.g;
  // self_energizing's self-servo: g + (φ_s − 1) × the part of g it scales (Fc and Fs, or Fc only).
  const double servo = std::clamp(1.0 - f.servo_share + f.servo * servo_feedback_kip(band_kip, f), 0.2, 3.0);
  if (f.servo_level == f.g) return f.g * servo;  // on both levels (w = 1)
  return std::max(f.g + (servo - 1.0) * f.servo_level, 1e-6);
}

double BrfdModel::servo_feedback_kip(double band_kip, const Frame& f) const {
  // |N S(z)| at once, or the lagged force while it pulls the band of the direction of sliding (effects.h)
  return f.servo_lagged ? f.servo_lagged_kip : std::abs(band_kip);
}

BrfdModel::Frame BrfdModel::frame(const DamperInput& in) const {
  // Everything the effects need at one input, computed once: g(v), N_λ, rest relaxation.
  const LugreParams& p = params_.lugre;
  const ModelEffects& e = params_.effects;
  const double v = in.drum_vel_in_per_s;
  const bool forward = v >= 0.0;
  const Levels l = levels(in, forward);
  Frame f;
  const double vs = e.asymmetry ? p.vs_in_per_s * e.asymmetry->factor(e.asymmetry->stribeck_speed, forward)
                                : p.vs_in_per_s;
  const VelocityEffect* ve = e.velocity ? &*e.velocity : nullptr;
  const double r = (ve && ve->stribeck_lag_s > 0.0 ? stribeck_speed_ : std::abs(v)) / vs;
  // The Stribeck exponent n (velocity), × (1 ± a_n) by direction (asymmetry's stribeck_shape).
  const double n = (ve ? ve->stribeck_exponent : 2.0) *
                   (e.asymmetry && e.asymmetry->stribeck_shape != 0.0 ? e.asymmetry->factor(e.asymmetry->stribeck_shape, forward) : 1.0);
  const double shape = n == 2.0 ? std::exp(-r * r) : std::exp(-std::pow(r, n));
  f.g = std::max(l.fc + (l.fs - l.fc) * shape + (ve ? ve->viscous_kip_s_per_in * std::abs(v) : 0.0), 1e-6);
  if (e.self_energizing && e.self_energizing->brake_factor_per_kip != 0.0) {
    // Leading/trailing brake factor by the friction level: g / (1 − λ g), ρ_s λ moving backward (effects.h).
    const double lambda = e.self_energizing->brake_factor_per_kip * (forward ? 1.0 : e.self_energizing->servo_backward_ratio);
    const double w = e.self_energizing->stiction_share;
    const double whole = f.g / std::max(1.0 - lambda * f.g, 0.25);  // w = 1: on g(v)
    double kinetic = whole;
    if (w < 1.0) {  // w = 0: on Eq. (4)'s Fc only, Fs kept: Fc' + (Fs − Fc') shape
      const double fc = l.fc / std::max(1.0 - lambda * l.fc, 0.25);
      kinetic = std::max(f.g + (fc - l.fc) * (1.0 - shape), 1e-6);
    }
    f.g = w * whole + (1.0 - w) * kinetic;
  }
  f.tension = l.tension;
  if (ve && ve->stribeck_lag_s > 0.0 && ve->lag_viscous_share > 0.0) {
    f.viscous_velocity = v + ve->lag_viscous_share * (lagged_velocity_ - v);
    f.viscous_lagged = true;
  }
  if (e.self_energizing) {
    const double d = rotation_in(in);  // each band stretches in its own direction of rotation
    f.band_spring_kip = e.self_energizing->band_spring_kip_per_in * (d < 0.0 ? e.self_energizing->band_spring_neg_ratio : 1.0) * d;
  }
  if (e.asymmetry) f.motion = e.asymmetry->factor(e.asymmetry->motion_stiffness, forward);
  if (e.transition_shape && e.transition_shape->overshoot_share > 0.0) {
    // Bliman-Sorine: the fast element's rate keeps the initial stiffness N σ0 (effects.h).
    const double th = e.transition_shape->overshoot_share;
    f.motion *= (1.0 + th * f.g / (f.tension * params_.lugre.sigma0_kip_per_in * e.transition_shape->overshoot_length_in)) / (1.0 + th);
  }
  if (e.self_energizing && (e.self_energizing->band_force_share != 0.0 || e.self_energizing->band_force_per_kip != 0.0)) {
    // φ_s = 1 − η + (η/b + χ)|N S(z)|: η relative to the direction's passive b, χ per kip (effects.h).
    f.servo_share = e.self_energizing->band_force_share;
    f.servo = f.servo_share / std::max(l.passive, 1e-6) + e.self_energizing->band_force_per_kip;
    if (!forward) {  // the trailing (or equally energized) band: its gains × ρ_s
      f.servo_share *= e.self_energizing->servo_backward_ratio;
      f.servo *= e.self_energizing->servo_backward_ratio;
    }
    f.servo_on = true;
    if (e.self_energizing->band_force_lag_s > 0.0) {  // the servo through its lag, tightening only
      f.servo_lagged = true;
      f.servo_lagged_kip = std::max(0.0, (forward ? 1.0 : -1.0) * servo_band_kip_);
    }
    // The part of g that φ_s scales: all of it (stiction_share w = 1), or Eq. (4)'s kinetic level
    // Fc (1 − e^(−(v/vs)²)) only, Fs kept (w = 0; effects.h).
    const double w = e.self_energizing->stiction_share;
    f.servo_level = w * f.g + (1.0 - w) * l.fc * (1.0 - shape);
  }
  if (e.residual_static) {
    const double q = slow_speed_ / ResidualStaticEffect::kRestSpeedInPerS;
    f.relax = rest_rate_per_s_ >= 0.0 ? rest_rate_per_s_ : std::exp(-q * q) / e.residual_static->time_constant_s;
    if (f.relax > 0.0) {
      // z_r = (1 − m) z_h + m z_o, S(z_o) N_λ = ±ρ Fc of the loaded direction + f_o; the held
      // force's set change Δ_h (in its own direction) on top, in force.
      const ResidualStaticEffect& rs = *e.residual_static;
      const double fc_pos = forward ? l.fc : levels(in, true).fc;
      const double fc_neg = forward ? levels(in, false).fc : l.fc;
      const double m = rs.relaxed_share;
      f.target_pos = (1.0 - m) * held_z_in_ + m * bristle_for_force((rs.ratio * fc_pos + rs.offset_kip) / f.tension);
      f.target_neg = (1.0 - m) * held_z_in_ + m * bristle_for_force((-rs.ratio * fc_neg + rs.offset_kip) / f.tension);
      if (rs.held_change_kip != 0.0 && held_z_in_ != 0.0) {
        const double change = (held_z_in_ > 0.0 ? rs.held_change_kip : -rs.held_change_kip) / f.tension;
        f.target_pos = bristle_for_force(spring_force_kip(f.target_pos) + change);
        f.target_neg = bristle_for_force(spring_force_kip(f.target_neg) + change);
      }
    }
  }
  return f;
}

double BrfdModel::rate_in_frame(double z, double v, const Frame& f) const {
  const double band = f.tension * spring_force_kip(z);
  // self_energizing's self-servo: Fc and Fs (so g) follow the force the band carries.
  const double y = band / servo_level_kip(band, f);  // force ratio
  const TransitionShapeEffect* ts = params_.effects.transition_shape ? &*params_.effects.transition_shape : nullptr;
  double shaped = ts && ts->exponent != 1.0 ? std::copysign(std::pow(std::abs(y), ts->exponent), y) : y;
  if (ts && ts->breakaway_ratio > 0.0 && y * v > 0.0) {  // elasto-plastic loading: no slip below the breakaway ratio
    const double beta = ts->breakaway_ratio, full = ts->breakaway_full_slip_ratio(), ay = std::abs(y);
    shaped *= ay <= beta ? 0.0 : ay >= full ? 1.0 : 0.5 + 0.5 * std::sin(M_PI * (ay - 0.5 * (beta + full)) / (full - beta));
  }
  if (ts && ts->elastic_unloading != 0.0 && y * v < 0.0) shaped *= 1.0 - ts->elastic_unloading;  // sticks, unloads elastically
  double rate = v - std::abs(v) * shaped;
  if (ts && ts->dahl_exponent != 1.0 && v != 0.0) {  // Dahl: v sign(u) |u|^n, u = 1 − sign(v) shaped
    const double u = rate / v;
    rate = v * std::copysign(std::pow(std::abs(u), ts->dahl_exponent), u);
  }
  const BacklashEffect* b = params_.effects.backlash ? &*params_.effects.backlash : nullptr;
  if (b && b->release_ratio != 1.0 && v * z < 0.0 && std::abs(z) > slack_now_in()) rate *= b->release_ratio;
  rate *= f.motion;  // asymmetry: the band stiffness by the direction of motion
  if (f.relax > 0.0) rate -= f.relax * (z - (z >= 0.0 ? f.target_pos : f.target_neg));
  return rate;
}

double BrfdModel::force_in_frame(double z, double v, const Frame& f) const {
  const LugreParams& p = params_.lugre;
  const AsymmetryEffect* as = params_.effects.asymmetry ? &*params_.effects.asymmetry : nullptr;
  const double sigma2 = as ? p.sigma2_kip_s_per_in * as->factor(as->viscous, v >= 0.0) : p.sigma2_kip_s_per_in;
  const VelocityEffect* ve = params_.effects.velocity ? &*params_.effects.velocity : nullptr;
  // The film: c_a v + c_q sgn(v) |v|^n (n = viscous_exponent; written as a coefficient of v), seen
  // through velocity's lag (lag_viscous_share) where it has one.
  const double vv = f.viscous_lagged ? f.viscous_velocity : v;
  double film = 0.0;
  if (ve && ve->quadratic_viscous_kip_s2_per_in2 != 0.0 && vv != 0.0)
    film = ve->quadratic_viscous_kip_s2_per_in2 *
           (ve->viscous_exponent == 2.0 ? std::abs(vv) : std::pow(std::abs(vv), ve->viscous_exponent - 1.0));
  const double viscous = sigma2 + (ve ? ve->added_viscous_kip_s_per_in + film : 0.0);
  // Backlash: the bristle damping acts only on the engaged band; the viscous force keeps the share
  // slack_viscous_share of itself while the band is slack (effects.h).
  const double engaged = engaged_share(z);
  const double slack_viscous = params_.effects.backlash ? params_.effects.backlash->slack_viscous_share : 0.0;
  const TransitionShapeEffect* ts = params_.effects.transition_shape ? &*params_.effects.transition_shape : nullptr;
  const double slow = ts ? ts->slow_share : 0.0;  // transition_shape's slow contact element
  const double overshoot = ts ? ts->overshoot_share : 0.0;  // Bliman-Sorine: fast (1 + θ), slow F_2
  double band = (1.0 + overshoot) * ((1.0 - slow) * spring_force_kip(z) +
                                     (slow > 0.0 ? slow * p.sigma0_kip_per_in * ts->slow_stiffness_ratio * slow_z_in_ : 0.0));
  // The Iwan bank carries φ_b of the band force (effects.h).
  if (ts && ts->bank_share > 0.0) band = (1.0 - ts->bank_share) * band + ts->bank_share * bank_sum_kip();
  // The stiction bump since the reversal, on the band loaded in the direction of motion (effects.h).
  if (ts && ts->stroke_peak_share != 0.0 && band * v > 0.0) band *= 1.0 + ts->stroke_peak_share * ts->stroke_peak(stroke_travel_in_);
  // σ1 of Eq. (3), and transition_shape's micro-damping σ1' e^(−(v/v_d)²) (effects.h)
  double sigma1 = p.sigma1_kip_s_per_in;
  if (ts && ts->micro_damping_kip_s_per_in != 0.0) {
    const double r = v / ts->micro_damping_speed_in_per_s;
    sigma1 += ts->micro_damping_kip_s_per_in * std::exp(-r * r);
  }
  const double pulse = ts && ts->travel_pulse_share > 0.0 ? pulse_kip_ : 0.0;  // Bliman-Sorine's travel pulse
  return f.tension * band + (overshoot > 0.0 ? overshoot_kip_ : 0.0) + pulse +
         (sigma1 != 0.0 ? engaged * sigma1 * rate_in_frame(z, v, f) : 0.0) +
         (engaged + (1.0 - engaged) * slack_viscous) * viscous * vv + f.band_spring_kip;
}

double BrfdModel::bristle_rate(double z_in, const DamperInput& in) const {
  const double v = in.drum_vel_in_per_s;
  if (has_effects_) return rate_in_frame(z_in, v, frame(in));
  return v - params_.lugre.sigma0_kip_per_in * std::abs(v) / stribeck_kip(in) * z_in;  // Eq. (1)
}

double BrfdModel::force_kip(double z_in, const DamperInput& in) const {
  const LugreParams& p = params_.lugre;
  if (has_effects_) return force_in_frame(z_in, in.drum_vel_in_per_s, frame(in));
  return p.sigma0_kip_per_in * z_in + p.sigma1_kip_s_per_in * bristle_rate(z_in, in) +
         p.sigma2_kip_s_per_in * in.drum_vel_in_per_s;  // Eq. (3)
}

double BrfdModel::step(const DamperInput& in, double dt_s) {
  if (has_effects_) return step_with_effects(in, dt_s);
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

double BrfdModel::step_with_effects(const DamperInput& in, double dt_s) {
  double force = step_states_with_effects(in, dt_s);
  last_force_kip_ = force;
  // backlash's impact ring after the last reversal (effects.h), from the step the drum has travelled
  // impact_travel_in past it (the clearance closed; 0: the step the reversal was seen).
  const BacklashEffect* bl = params_.effects.backlash ? &*params_.effects.backlash : nullptr;
  if (bl && bl->impact_rings() && reversal_time_s_ >= 0.0) {
    const double t = reversal_time_s_ - dt_s, phase = 2.0 * M_PI * bl->impact_frequency_hz * t;
    const double scale = (1.0 - bl->impact_force_share + bl->impact_force_share * std::abs(reversal_force_kip_)) *
                         (1.0 - bl->impact_speed_share + bl->impact_speed_share * impact_speed_in_per_s_);
    force += last_direction_ * scale * std::exp(-t / bl->impact_decay_s) *
             (bl->impact_sin_kip * std::sin(phase) + bl->impact_cos_kip * std::cos(phase));
  }
  // residual_static's ring-down while the drum is still (effects.h): from the step the drum speed
  // fell below v_rest, signed by the band force then; the bristle state is left alone.
  const ResidualStaticEffect* rs = params_.effects.residual_static ? &*params_.effects.residual_static : nullptr;
  if (rs && rs->ring_kip != 0.0) {
    if (std::abs(in.drum_vel_in_per_s) >= ResidualStaticEffect::kRestSpeedInPerS) {
      ring_time_s_ = -1.0;
    } else if (ring_time_s_ < 0.0) {
      ring_time_s_ = 0.0;
      ring_sign_ = force > 0.0 ? 1.0 : force < 0.0 ? -1.0 : 0.0;
    } else {
      ring_time_s_ += dt_s;
      force += rs->ring_kip * ring_sign_ * std::exp(-ring_time_s_ / rs->ring_decay_s) *
               std::sin(2.0 * M_PI * rs->ring_frequency_hz * ring_time_s_);
    }
  }
  // self_energizing's lagged servo: τ_s dy/dt = F − y with the step's end force held (exact).
  const SelfEnergizingEffect* se = params_.effects.self_energizing ? &*params_.effects.self_energizing : nullptr;
  if (se && se->band_force_lag_s > 0.0) servo_band_kip_ = force + (servo_band_kip_ - force) * std::exp(-dt_s / se->band_force_lag_s);
  // Friction work of the step (pretension's wear), with the force at its end; with a recovery rate
  // k_r (thermal fade) the exact solution of dW/dt = |F v| − k_r W over the step.
  if (params_.effects.pretension && params_.effects.pretension->wear_per_kip_in != 0.0) {
    const double power = std::abs(force * in.drum_vel_in_per_s);
    const double k = params_.effects.pretension->wear_recovery_per_s;
    if (k > 0.0) {
      const double decay = std::exp(-k * dt_s);
      friction_work_kip_in_ = friction_work_kip_in_ * decay + power * (1.0 - decay) / k;
    } else {
      friction_work_kip_in_ += power * dt_s;
    }
  }
  // asymmetry's band fade: the friction work of the band of the direction of motion, both relaxing.
  const AsymmetryEffect* as = params_.effects.asymmetry ? &*params_.effects.asymmetry : nullptr;
  if (as && as->band_fade_per_kip_in != 0.0) {
    const double power = std::abs(force * in.drum_vel_in_per_s);
    const double k = as->band_fade_recovery_per_s;
    const double decay = k > 0.0 ? std::exp(-k * dt_s) : 1.0;
    const double added = k > 0.0 ? power * (1.0 - decay) / k : power * dt_s;
    band_work_fwd_kip_in_ = band_work_fwd_kip_in_ * decay + (in.drum_vel_in_per_s > 0.0 ? added : 0.0);
    band_work_bwd_kip_in_ = band_work_bwd_kip_in_ * decay + (in.drum_vel_in_per_s < 0.0 ? added : 0.0);
  }
  return force;
}

double BrfdModel::step_states_with_effects(const DamperInput& drum, double dt_s) {
  const ModelEffects& e = params_.effects;
  if (!drum_start_in_) drum_start_in_ = drum.drum_disp_in;
  DamperInput in = drum;  // what the bands see: the drum, or through backlash's drive-line play
  if (e.backlash && e.backlash->play_in > 0.0) {
    const double half = e.backlash->play_in, x = drum.drum_disp_in, v = drum.drum_vel_in_per_s;
    if (!play_band_in_) {  // in contact on the side of the initial band force
      play_band_in_ = x - last_direction_ * half;
      play_drum_in_ = x;
    }
    const double travel = std::abs(x - play_drum_in_);
    play_drum_in_ = x;
    bool contact = false;
    if (x - *play_band_in_ >= half) {
      play_band_in_ = x - half;
      contact = v > 0.0;
    } else if (x - *play_band_in_ <= -half) {
      play_band_in_ = x + half;
      contact = v < 0.0;
    }
    if (!contact) {
      in.drum_vel_in_per_s = 0.0;
      if (e.backlash->play_release_per_in > 0.0) z_in_ *= std::exp(-e.backlash->play_release_per_in * travel);
    }
  }
  if (e.actuator_lag) {
    // The chain: transport delay, rate limit, play, first-order lag, second-order response (effects.h).
    double x1 = in.actuator1_in, x2 = in.actuator2_in;
    if (e.actuator_lag->delay_s > 0.0) {
      actuator_clock_s_ += dt_s;
      actuator_history_.push_back({actuator_clock_s_, x1, x2});
      const double seen = actuator_clock_s_ - e.actuator_lag->delay_s;
      while (actuator_history_.size() >= 2 && actuator_history_[1][0] <= seen) actuator_history_.pop_front();
      const std::array<double, 3>& a = actuator_history_[0];
      if (actuator_history_.size() >= 2 && a[0] < seen) {
        const std::array<double, 3>& b = actuator_history_[1];
        const double w = (seen - a[0]) / (b[0] - a[0]);
        x1 = a[1] + w * (b[1] - a[1]);
        x2 = a[2] + w * (b[2] - a[2]);
      } else {
        x1 = a[1];
        x2 = a[2];
      }
    }
    const double limit = e.actuator_lag->rate_limit_in_per_s;
    if (limit > 0.0 && limit < ActuatorLagEffect::kNoRateLimitInPerS) {
      const double most = limit * dt_s;
      rated1_in_ += std::clamp(x1 - rated1_in_, -most, most);
      rated2_in_ += std::clamp(x2 - rated2_in_, -most, most);
      x1 = rated1_in_;
      x2 = rated2_in_;
    }
    const double play = e.actuator_lag->actuator_play_in;  // the drive's clearance: a play operator (effects.h)
    if (play > 0.0) {
      played1_in_ = std::clamp(played1_in_, x1 - play, x1 + play);
      played2_in_ = std::clamp(played2_in_, x2 - play, x2 + play);
      x1 = played1_in_;
      x2 = played2_in_;
    }
    // First-order lag, exact for the step's input held; τ_a retracting, ρ_e τ_a extending.
    auto follow = [&](double x, double lagged) {
      const double tau = e.actuator_lag->time_constant_s * (x > lagged ? e.actuator_lag->extend_time_ratio : 1.0);
      return x + (lagged - x) * (tau > 0.0 ? std::exp(-dt_s / tau) : 0.0);
    };
    lag1_in_ = follow(x1, lag1_in_);
    lag2_in_ = follow(x2, lag2_in_);
    const double period = e.actuator_lag->natural_period_s;
    if (period > 0.0) {
      // Second-order response to x~ held over the step: semi-implicit sub-steps (h <= T/40),
      // each solving the damping and stiffness terms implicitly (stable for any ζ, h).
      const double w = 2.0 * M_PI / period, zeta = e.actuator_lag->damping_ratio;
      const int n = std::clamp(static_cast<int>(std::ceil(dt_s * 40.0 / period)), 1, 4000);
      const double h = dt_s / n;
      const double den = 1.0 + 2.0 * zeta * w * h + w * w * h * h;
      for (int i = 0; i < n; ++i) {
        resp1_rate_ = (resp1_rate_ + h * w * w * (lag1_in_ - resp1_in_)) / den;
        resp1_in_ += h * resp1_rate_;
        resp2_rate_ = (resp2_rate_ + h * w * w * (lag2_in_ - resp2_in_)) / den;
        resp2_in_ += h * resp2_rate_;
      }
    } else {
      resp1_in_ = lag1_in_;
      resp2_in_ = lag2_in_;
      resp1_rate_ = resp2_rate_ = 0.0;
    }
  }
  const double v = in.drum_vel_in_per_s;
  const double speed = std::abs(v);
  const bool stroke_wrap = e.self_energizing && (e.self_energizing->stroke_wrap_fwd != 0.0 || e.self_energizing->stroke_wrap_bwd != 0.0);
  const bool stroke_peak = e.transition_shape && (e.transition_shape->stroke_peak_share != 0.0 || e.transition_shape->weakening_share != 0.0);
  if ((e.backlash && (e.backlash->takeup_dip > 0.0 || e.backlash->impact_rings() || e.backlash->slack_per_kip > 0.0 ||
                      (!play_opened_ && e.backlash->slack_in > 0.0))) ||
      stroke_wrap || stroke_peak) {
    // backlash's take-up and impact ring, self_energizing's stroke wrap, transition_shape's stroke
    // peak and slip weakening: a reversal is the drum turned
    // back by kReversalTravelIn from the furthest point of its last direction (a hysteresis on the
    // drum position ∫v dt: rest jitter and a creeping stop are none); the travel since the reversal
    // counts from that turn point (effects.h).
    const double travel = speed * dt_s;
    drum_position_in_ += v * dt_s;
    if (last_direction_ == 0) {  // the direction not known yet: the first travel of kReversalTravelIn sets it
      if (std::abs(drum_position_in_ - turn_position_in_) >= BacklashEffect::kReversalTravelIn) {
        last_direction_ = drum_position_in_ > turn_position_in_ ? 1 : -1;
        turn_position_in_ = drum_position_in_;
      }
      reversal_travel_in_ = std::min(reversal_travel_in_ + travel, kEngagedTravelIn);
      stroke_travel_in_ += travel;
    } else {
      const double back = last_direction_ * (turn_position_in_ - drum_position_in_);  // travel back from the turn point
      const double strike = e.backlash ? e.backlash->impact_travel_in : 0.0;
      if (back <= 0.0) {  // still going the last direction: a new furthest point
        turn_position_in_ = drum_position_in_;
        turn_force_kip_ = last_force_kip_;
        strike_clock_s_ = -1.0;
      } else if (strike_clock_s_ < 0.0 && back >= strike) {
        strike_clock_s_ = 0.0;  // the clearance δ_i closed on this step (if it turns out a reversal)
        strike_speed_in_per_s_ = speed;
      } else if (strike_clock_s_ >= 0.0 && back < strike) {
        strike_clock_s_ = -1.0;
      }
      if (strike_clock_s_ >= 0.0) strike_clock_s_ += dt_s;
      if (back >= BacklashEffect::kReversalTravelIn) {
        last_direction_ = -last_direction_;
        if (!play_opened_) {  // the first turn of the drum: the slack acts from here, the band force kept
          const double band = spring_force_kip(z_in_);
          play_opened_ = true;
          z_in_ = bristle_for_force(band);
        }
        if (e.backlash && e.backlash->slack_per_kip > 0.0) {  // the slack set by the load before the reversal
          const double old_slack = slack_now_in();
          const double band = spring_force_kip(z_in_);
          load_slack_in_ = e.backlash->slack_per_kip * std::abs(turn_force_kip_);
          const double new_slack = slack_now_in();
          if (std::abs(z_in_) <= old_slack) {  // inside the dead zone: the travel made into it kept
            const int entered_from = -last_direction_;  // the side the band was loaded on before the turn
            z_in_ += entered_from * (new_slack - old_slack);
            z_in_ = std::clamp(z_in_, -new_slack, new_slack);
          } else {
            z_in_ = bristle_for_force(band);
          }
        }
        previous_stroke_in_ = std::max(stroke_travel_in_ + travel - back, 0.0);
        stroke_travel_in_ = back;
        reversal_travel_in_ = back;
        reversal_force_kip_ = turn_force_kip_;
        // The ring's clock runs from the step the drum passed δ_i beyond the turn point; beyond this
        // step's travel it waits (impact_pending_).
        impact_pending_ = strike_clock_s_ < 0.0;
        reversal_time_s_ = impact_pending_ ? -1.0 : strike_clock_s_ - dt_s;
        if (!impact_pending_) impact_speed_in_per_s_ = strike_speed_in_per_s_;
        turn_position_in_ = drum_position_in_;
        turn_force_kip_ = last_force_kip_;
        strike_clock_s_ = -1.0;
      } else {
        reversal_travel_in_ = std::min(reversal_travel_in_ + travel, kEngagedTravelIn);
        stroke_travel_in_ += travel;
      }
    }
    if (impact_pending_ && e.backlash && reversal_travel_in_ >= e.backlash->impact_travel_in) {  // the clearance closes: the strike
      impact_pending_ = false;
      reversal_time_s_ = 0.0;
      impact_speed_in_per_s_ = speed;
    }
    if (reversal_time_s_ >= 0.0) reversal_time_s_ += dt_s;
  }
  if (e.residual_static) {
    slow_speed_ = speed + (slow_speed_ - speed) * std::exp(-dt_s / ResidualStaticEffect::kSpeedFilterS);
    // z_h follows z while the drum moves and holds the state it stopped with: frozen once the rest
    // weight w = exp(−(s̃/v_rest)²) reaches 1/2 (a soft gate would let z_h creep after z at rest).
    const double q = slow_speed_ / ResidualStaticEffect::kRestSpeedInPerS;
    const double w = std::exp(-q * q);
    if (w < 0.5) held_z_in_ = z_in_;
    // Stretched settling: at rest the step's rate is (L(x(t_r + dt)) − L(x(t_r))) / dt, x = (t_r/τ_r)^β,
    // L = −ln of the share left ((1 + c x)^(−1/c); exp(−x) at c = 0): the exact mean rate over the
    // step; the rest clock t_r restarts at each stop.
    const ResidualStaticEffect& rs = *e.residual_static;
    rest_rate_per_s_ = -1.0;
    if (w < 0.5) {
      rest_time_s_ = 0.0;
    } else if ((rs.relaxation_exponent != 1.0 || rs.relaxation_tail != 0.0) && dt_s > 0.0) {
      const double tau = rs.time_constant_s, beta = rs.relaxation_exponent;
      rest_rate_per_s_ = (rs.relaxation_progress(std::pow((rest_time_s_ + dt_s) / tau, beta)) -
                          rs.relaxation_progress(std::pow(rest_time_s_ / tau, beta))) / dt_s;
      rest_time_s_ += dt_s;
    }
  }
  if (e.velocity && e.velocity->stribeck_lag_s > 0.0) {  // lagged speed (Stribeck) and velocity: exact
    const double keep = std::exp(-dt_s / e.velocity->stribeck_lag_s);
    stribeck_speed_ = speed + (stribeck_speed_ - speed) * keep;
    lagged_velocity_ = v + (lagged_velocity_ - v) * keep;
  }
  if (e.velocity) {
    // Aging law dθ/dt = 1 − ṽ θ/D with the speed held over the step: exact.
    const double d = e.velocity->memory_in;
    if (d > 0.0) {
      const double vs = speed + VelocityEffect::kSpeedFloorInPerS;
      const double steady = d / vs;
      rate_state_s_ = steady + (rate_state_s_ - steady) * std::exp(-vs * dt_s / d);
    }
  }
  const Frame f = frame(in);
  if (e.transition_shape && e.transition_shape->slow_share > 0.0 && v != 0.0) {
    // The slow contact element: its own LuGre law, exact over the step (v, g held).
    const double length = f.g / (f.tension * params_.lugre.sigma0_kip_per_in * e.transition_shape->slow_stiffness_ratio);
    const double steady = std::copysign(length, v);
    slow_z_in_ = steady + (slow_z_in_ - steady) * std::exp(-speed * dt_s / length);
  }
  if (e.transition_shape && e.transition_shape->overshoot_share > 0.0 && v != 0.0) {
    // The overshoot's slow element: towards −θ g sgn v over ℓ2 of travel, exact over the step.
    const double steady = -std::copysign(e.transition_shape->overshoot_share * f.g, v);
    overshoot_kip_ = steady + (overshoot_kip_ - steady) * std::exp(-speed * dt_s / e.transition_shape->overshoot_length_in);
  }
  if (e.transition_shape && e.transition_shape->bank_share > 0.0) {
    // The Iwan bank: each element elastic at κ_b σ0/N, slipping at ± w_k g (exact with v and g held).
    const double stretch = e.transition_shape->bank_stiffness_ratio * params_.lugre.sigma0_kip_per_in /
                           TransitionShapeEffect::kBankElements * v * dt_s;
    for (int k = 0; k < TransitionShapeEffect::kBankElements; ++k) {
      const double limit = bank_limit_[k] * f.g;
      bank_kip_[k] = std::clamp(bank_kip_[k] + stretch, -limit, limit);
    }
  }
  if (e.transition_shape && e.transition_shape->travel_pulse_share > 0.0) {
    // The travel pulse's memories: towards sgn v over ε1 and ε2 of travel, exact over the step.
    const TransitionShapeEffect& ts = *e.transition_shape;
    const double direction = v >= 0.0 ? 1.0 : -1.0;
    const double eps2 = ts.travel_pulse_length_in, eps1 = ts.travel_pulse_rise_share * eps2;
    pulse_fast_ = direction + (pulse_fast_ - direction) * std::exp(-speed * dt_s / eps1);
    pulse_slow_ = direction + (pulse_slow_ - direction) * std::exp(-speed * dt_s / eps2);
    const Levels level = levels(in, v >= 0.0);
    pulse_kip_ = ts.travel_pulse_share * level.tension * level.fc * (pulse_fast_ - pulse_slow_) / (2.0 * ts.travel_pulse_peak());
  }
  const double relax = f.relax;  // w / τ_r of residual_static, 1/s
  const double target_pos = f.target_pos, target_neg = f.target_neg;
  if (v == 0.0 && relax == 0.0) return force_in_frame(z_in_, v, f);

  const double slack = slack_now_in();
  const double k = speed / f.g;  // |v| / g(v)
  const double sp = f.tension * stiffness(true), sn = f.tension * stiffness(false);  // N_λ σ0±
  const bool shaped = e.transition_shape && e.transition_shape->nonlinear();
  const bool soft = e.backlash && (e.backlash->retension_in > 0.0 || e.backlash->release_ratio != 1.0);
  if (shaped || soft || f.servo_on) {
    // Nonlinear bristle law (Dahl exponent, the soft re-tensioning spring, the self-servo): RK4
    // sub-steps, enough to keep h × (largest rate constant) <= 0.25. With α < 1 the rate constant
    // α |y|^(α−1) is largest at small |y|: bounded with |y| >= 0.05.
    const double alpha = shaped ? e.transition_shape->exponent : 1.0;
    const double band0 = f.tension * spring_force_kip(z_in_);
    const double y0 = std::abs(band0 / f.g);
    const double release = e.backlash ? e.backlash->release_ratio : 1.0;
    const double servo0 = f.servo_on ? std::clamp(1.0 - f.servo_share + f.servo * servo_feedback_kip(band0, f), 0.2, 3.0) : 1.0;
    // The shaped law's slope: its largest value between the step's start and the steady state
    // (slope_to_steady_), or, off that grid, the bound over every |y| below max(1, |y0|).
    double slope = shaped ? shape_slope_to_steady((v >= 0.0 ? 1.0 : -1.0) * band0 / servo_level_kip(band0, f)) : 1.0;
    if (slope < 0.0) {
      slope = alpha >= 1.0 ? alpha * std::pow(std::max(1.0, y0), alpha - 1.0) : alpha * std::pow(0.05, alpha - 1.0);
      // The breakaway's half-sine rises with slope π/(2(y_m − β)) in y.
      if (e.transition_shape->breakaway_ratio > 0.0)
        slope *= 1.0 + M_PI / (2.0 * (e.transition_shape->breakaway_full_slip_ratio() - e.transition_shape->breakaway_ratio));
      // Dahl's n: d|u|^n/du = n |u|^(n−1), u in [0, 2]; bounded with |u| >= 0.05 for n < 1.
      const double dahl = e.transition_shape->dahl_exponent;
      if (dahl != 1.0) slope *= dahl >= 1.0 ? dahl * std::pow(2.0, dahl - 1.0) : dahl * std::pow(0.05, dahl - 1.0);
    }
    // Self-servo: g φ_s with φ_s at the step's start (it changes little over one step), twice.
    const double servo = f.servo_on ? 2.0 / servo0 : 1.0;
    const double stiff = k * std::max(sp, sn) * slope * servo * 1.5 * release * f.motion + relax;
    const int n = std::clamp(static_cast<int>(std::ceil(stiff * dt_s / 0.25)), 1, 2000);
    const double h = dt_s / n;
    double z = z_in_;
    for (int i = 0; i < n; ++i) {
      const double k1 = rate_in_frame(z, v, f), k2 = rate_in_frame(z + 0.5 * h * k1, v, f);
      const double k3 = rate_in_frame(z + 0.5 * h * k2, v, f), k4 = rate_in_frame(z + h * k3, v, f);
      z += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    z_in_ = z;
    return force_in_frame(z_in_, v, f);
  }
  // dz/dt = c - a z on each piece: z > δ (band + loaded), 0 <= z <= δ, -δ <= z < 0 (slack),
  // z < -δ (band - loaded). Exact solution per piece, chained at the boundaries ±δ and 0.
  constexpr double inf = std::numeric_limits<double>::infinity();
  // piece 0: z < -δ, 1: -δ <= z < 0, 2: 0 <= z <= δ, 3: z > δ (pieces 1, 2 empty when δ = 0).
  auto piece_of = [slack](double z) { return z < -slack ? 0 : z < 0.0 ? 1 : z <= slack ? 2 : 3; };
  int piece = piece_of(z_in_);
  double z = z_in_;
  double t_left = dt_s;
  for (int segment = 0; segment < 8 && t_left > 0.0; ++segment) {
    // The drum-driven part of the rate (× asymmetry's motion factor) and the rest relaxation.
    double a_drum = 0.0, c_drum = v, target = 0.0, lo = -inf, hi = inf;
    switch (piece) {
      case 0: a_drum = k * sn; c_drum += -k * sn * slack; target = target_neg; hi = -slack; break;
      case 1: target = target_neg; lo = -slack; hi = 0.0; break;
      case 2: target = target_pos; lo = 0.0; hi = slack; break;
      default: a_drum = k * sp; c_drum += k * sp * slack; target = target_pos; lo = slack; break;
    }
    const double a = relax + f.motion * a_drum, c = f.motion * c_drum + relax * target;
    const double u = c - a * z;  // dz/dt at the start of the piece
    if (u == 0.0) break;
    const double bound = u > 0.0 ? hi : lo;
    double t_hit = inf;
    if (std::isfinite(bound)) {
      const double q = a * (bound - z) / u;  // z reaches the bound before its asymptote if q < 1
      if (q < 1.0) t_hit = q < 1e-8 ? (bound - z) / u * (1.0 + 0.5 * q) : -std::log1p(-q) / a;
    }
    if (t_hit >= t_left) {
      const double phi = a * t_left < 1e-12 ? t_left : -std::expm1(-a * t_left) / a;
      z += u * phi;
      t_left = 0.0;
    } else {
      z = bound;
      t_left -= t_hit;
      piece += u > 0.0 ? 1 : -1;
      if (slack == 0.0 && (piece == 1 || piece == 2)) piece = u > 0.0 ? 3 : 0;
    }
  }
  z_in_ = z;
  return force_in_frame(z_in_, v, f);
}

std::string to_string(DamperKind kind) {
  switch (kind) {
    case DamperKind::passive_lugre: return "passive_lugre";
    case DamperKind::band_brake: return "band_brake";
    default: return "semiactive";
  }
}

DamperKind damper_kind_from_string(const std::string& name) {
  if (name == "passive_lugre") return DamperKind::passive_lugre;
  if (name == "semiactive" || name == "paper_semiactive") return DamperKind::semiactive;
  if (name == "band_brake") return DamperKind::band_brake;
  throw std::invalid_argument("unknown damper model '" + name +
                              "' (expected passive_lugre, semiactive, paper_semiactive or band_brake)");
}

}  // namespace damper
