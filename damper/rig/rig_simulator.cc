#include "damper/rig/rig_simulator.h"

#include <algorithm>
#include <cmath>

namespace damper::rig {

namespace {
double smooth(double t) { return 0.5 * (1.0 - std::cos(M_PI * std::clamp(t, 0.0, 1.0))); }
int sign(double v) { return v > 0.0 ? 1 : (v < 0.0 ? -1 : 0); }
}  // namespace

RigSimulator::RigSimulator(const RigConfig& config)
    : c_(config), dt_(1.0 / config.rate_hz), model_(config.model), rng_(config.noise.seed) {
  delay_samples_ = c_.hydraulic.delay_s / dt_;
  delay_line_.assign(static_cast<std::size_t>(std::ceil(delay_samples_)) + 2, c_.initial.drum_in);
  drum_ = c_.initial.drum_in;
  electric1_ = c_.initial.actuator1_in;
  electric2_ = c_.initial.actuator2_in;
  extreme_ = direction_origin_ = drum_;
  double force = 0.0;
  if (c_.residual_force.enabled) {
    residual_kip_ = c_.residual_force.initial_kip;  // locked in the bands from the previous test
    force = residual_kip_;
  }
  truth_ = {drum_, force, electric1_, electric2_, 0.0, 0.0};
  set_band_forces(force, truth_);
  reading_ = truth_;
}

void RigSimulator::step(const RigCommand& cmd) {
  // Servo-hydraulic actuator: the command enters a delay line; the drum follows the delayed
  // command through a first-order lag (exact discretisation).
  double x = cmd.drum_in;
  if (c_.hydraulic.enabled) {
    const std::size_t n = delay_line_.size();
    delay_line_[delay_head_] = cmd.drum_in;
    const std::size_t k0 = static_cast<std::size_t>(std::floor(delay_samples_));
    const double f = delay_samples_ - static_cast<double>(k0);
    const double u0 = delay_line_[(delay_head_ + n - k0) % n];
    const double u1 = delay_line_[(delay_head_ + n - k0 - 1) % n];
    delay_head_ = (delay_head_ + 1) % n;
    const double u = c_.hydraulic.gain * ((1.0 - f) * u0 + f * u1);
    const double tau = c_.hydraulic.lag_time_constant_s;
    const double alpha = tau > 0.0 ? 1.0 - std::exp(-dt_ / tau) : 1.0;
    x = drum_ + alpha * (u - drum_);
  }
  velocity_ = (x - drum_) / dt_;
  drum_ = x;
  const double te = c_.electric.lag_time_constant_s;
  const double beta = te > 0.0 ? 1.0 - std::exp(-dt_ / te) : 1.0;
  electric1_ += beta * (cmd.actuator1_in - electric1_);
  electric2_ += beta * (cmd.actuator2_in - electric2_);

  DamperInput in;
  in.drum_disp_in = drum_;
  in.drum_vel_in_per_s = velocity_;
  in.actuator1_in = electric1_;
  in.actuator2_in = electric2_;
  double force = model_.step(in, dt_);
  backlash_weight_ = c_.backlash.enabled ? backlash(drum_) : 1.0;
  force *= backlash_weight_;
  if (c_.residual_force.enabled) force = residual(drum_, velocity_, force);

  truth_.drum_in = drum_;
  truth_.friction_kip = force;
  truth_.actuator1_in = electric1_;
  truth_.actuator2_in = electric2_;
  set_band_forces(force, truth_);
  reading_ = truth_;
  if (c_.noise.enabled) {
    const NoiseSettings& s = c_.noise;
    reading_.drum_in += s.displacement_std_in * normal_(rng_);
    reading_.friction_kip += s.friction_force_std_kip * normal_(rng_);
    reading_.actuator1_in += s.actuator_position_std_in * normal_(rng_);
    reading_.actuator2_in += s.actuator_position_std_in * normal_(rng_);
    reading_.actuator1_force_lb += s.actuator_force_std_lb * normal_(rng_);
    reading_.actuator2_force_lb += s.actuator_force_std_lb * normal_(rng_);
  }
}

double RigSimulator::backlash(double x) {
  const BacklashSettings& b = c_.backlash;
  // Reversal detection with hysteresis on the drum position.
  auto reverse = [&](int d) {
    direction_ = d;
    reversal_at_ = extreme_;
    extreme_ = x;
    reversed_ = true;
    ++reversals_;
  };
  if (direction_ == 0) {
    if (std::abs(x - direction_origin_) > b.reversal_hysteresis_in) {
      direction_ = sign(x - direction_origin_);
      extreme_ = x;
    }
  } else if (direction_ > 0) {
    if (x > extreme_) extreme_ = x;
    else if (extreme_ - x > b.reversal_hysteresis_in) reverse(-1);
  } else {
    if (x < extreme_) extreme_ = x;
    else if (x - extreme_ > b.reversal_hysteresis_in) reverse(+1);
  }
  if (!reversed_) return 1.0;
  const double s = std::abs(x - reversal_at_);  // drum travel since the reversal
  const double r = b.release_travel_in, g = b.gap_travel_in, e = b.engage_travel_in, eps = b.gap_force_fraction;
  if (s < r) return 1.0 - (1.0 - eps) * smooth(s / r);  // the taut band releases its energy
  if (s < r + g) {
    model_.set_bristle_in(0.0);  // neither band taut: nothing stored, force near zero
    return eps;
  }
  if (s < r + g + e) return eps + (1.0 - eps) * smooth((s - r - g) / e);  // the other band engages
  return 1.0;
}

double RigSimulator::residual(double x, double v, double dynamic_force) {
  (void)x;
  const ResidualForceSettings& r = c_.residual_force;
  const double speed = std::abs(v);
  if (speed >= r.rest_velocity_in_per_s) {
    if (at_rest_) {  // motion resumes: the locked force is released over release_travel_in
      at_rest_ = false;
      motion_since_rest_ = 0.0;
      release_from_kip_ = residual_kip_;
    }
    rest_time_ = 0.0;
    motion_since_rest_ += speed * dt_;
    // Only a real stroke re-tensions the bands (not sensor-noise-sized positioning moves).
    if (motion_since_rest_ >= r.release_travel_in) last_motion_sign_ = sign(v);
    residual_kip_ = release_from_kip_ * std::max(0.0, 1.0 - motion_since_rest_ / r.release_travel_in);
  } else {
    rest_time_ += dt_;
    if (rest_time_ >= r.rest_time_s) at_rest_ = true;
    if (at_rest_ && last_motion_sign_ != 0) {
      // The bands lock at a fraction of the kinetic friction of the last motion.
      const double fc = model_.base_kinetic_friction_kip(static_cast<double>(last_motion_sign_));
      const double locked = r.fraction * fc * last_motion_sign_;
      const double a = 1.0 - std::exp(-dt_ / r.time_constant_s);
      residual_kip_ += a * ((locked - dynamic_force) - residual_kip_);
    }
  }
  return dynamic_force + residual_kip_;
}

void RigSimulator::set_band_forces(double friction_kip, RigReading& r) const {
  const auto& c = c_.model.semiactive.scaling;  // C1..C4, kip friction per kip actuator force
  const double p = c_.electric.band_pretension_lb;
  const double f = std::abs(friction_kip) * 1000.0;  // lb
  if (friction_kip >= 0.0) {  // forward: band 2 taut (C2), band 1 slack (C1)
    r.actuator1_force_lb = p + f / c[0];
    r.actuator2_force_lb = p + f / c[1];
  } else {                    // backward: band 1 taut (C3), band 2 slack (C4)
    r.actuator1_force_lb = p + f / c[2];
    r.actuator2_force_lb = p + f / c[3];
  }
}

}  // namespace damper::rig
