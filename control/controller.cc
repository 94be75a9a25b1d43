#include "control/controller.h"

#include "control/riccati.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace control {

namespace {
constexpr double kGravity_in_per_s2 = 386.08858267716535;  // same g as structure/ (in/s²)
}

std::string to_string(Law law) {
  switch (law) {
    case Law::passive_off: return "passive_off";
    case Law::passive_on: return "passive_on";
    case Law::lyapunov: return "lyapunov";
    case Law::clipped_optimal: return "clipped_optimal";
    case Law::modulated_homogeneous: return "modulated_homogeneous";
  }
  return "?";
}

Law law_from_string(const std::string& name) {
  for (Law l : {Law::passive_off, Law::passive_on, Law::lyapunov, Law::clipped_optimal, Law::modulated_homogeneous})
    if (to_string(l) == name) return l;
  throw std::invalid_argument("unknown control law '" + name +
                              "' (passive_off, passive_on, lyapunov, clipped_optimal, modulated_homogeneous)");
}

ControlConfig control_config_from_yaml(const common::YamlSection& s) {
  s.allow_only({"law", "min_kinetic_friction_kip", "sensors", "lyapunov", "clipped_optimal", "modulated_homogeneous"});
  ControlConfig c;
  c.enabled = true;
  c.law = law_from_string(s.get_choice(
      "law", {"passive_off", "passive_on", "lyapunov", "clipped_optimal", "modulated_homogeneous"}));
  c.min_kinetic_friction_kip = s.get_double_in("min_kinetic_friction_kip", c.min_kinetic_friction_kip, 0.0, 1e3);
  if (s.has("sensors")) {
    const common::YamlSection n = s.section("sensors");
    n.allow_only({"accel_noise_g", "drift_noise_in", "force_noise_kip", "delay_steps", "seed"});
    c.accel_noise_g = n.get_double_in("accel_noise_g", c.accel_noise_g, 0.0, 10.0);
    c.drift_noise_in = n.get_double_in("drift_noise_in", c.drift_noise_in, 0.0, 10.0);
    c.force_noise_kip = n.get_double_in("force_noise_kip", c.force_noise_kip, 0.0, 100.0);
    c.delay_steps = n.get_int("delay_steps", c.delay_steps);
    if (c.delay_steps < 0 || c.delay_steps > 1024) n.fail("delay_steps", "must be in [0, 1024]");
    const int seed = n.get_int("seed", 1);
    if (seed < 0) n.fail("seed", "must be >= 0");
    c.seed = static_cast<unsigned>(seed);
  }
  if (s.has("lyapunov")) {
    const common::YamlSection l = s.section("lyapunov");
    l.allow_only({"reversal_lead", "motion_window_s"});
    c.reversal_lead = l.get_double_in("reversal_lead", c.reversal_lead, 0.0, 100.0);
    c.motion_window_s = l.get_double_in("motion_window_s", c.motion_window_s, 0.0, 10.0);
  }
  if (s.has("clipped_optimal")) {
    const common::YamlSection o = s.section("clipped_optimal");
    o.allow_only({"drift_weight_per_in2", "velocity_weight", "force_weight_per_kip2", "ground_accel_g", "sensor_noise_g",
                  "clipping"});
    c.drift_weight_per_in2 = o.get_double_in("drift_weight_per_in2", c.drift_weight_per_in2, 0.0, 1e9);
    c.velocity_weight = o.get_double_in("velocity_weight", c.velocity_weight, 0.0, 1e9);
    c.force_weight_per_kip2 = o.get_double_in("force_weight_per_kip2", c.force_weight_per_kip2, 1e-12, 1e9);
    c.ground_accel_g = o.get_double_in("ground_accel_g", c.ground_accel_g, 1e-6, 100.0);
    c.sensor_noise_g = o.get_double_in("sensor_noise_g", c.sensor_noise_g, 1e-9, 100.0);
    c.clipping = o.get_choice("clipping", c.clipping, {"continuous", "on_off"});
    if (!(c.drift_weight_per_in2 > 0.0 || c.velocity_weight > 0.0))
      o.fail("drift_weight_per_in2", "drift_weight_per_in2 or velocity_weight must be > 0");
  }
  if (s.has("modulated_homogeneous")) {
    const common::YamlSection h = s.section("modulated_homogeneous");
    h.allow_only({"gain_kip_per_in"});
    c.gain_kip_per_in = h.get_double_in("gain_kip_per_in", c.gain_kip_per_in, 0.0, 1e6);
  }
  return c;
}

std::string control_config_to_yaml(const ControlConfig& c) {
  if (!c.enabled) return "";
  std::ostringstream o;
  o << std::setprecision(17) << "control:\n  law: " << to_string(c.law)
    << "\n  min_kinetic_friction_kip: " << c.min_kinetic_friction_kip << "\n  sensors:\n    accel_noise_g: " << c.accel_noise_g
    << "\n    drift_noise_in: " << c.drift_noise_in << "\n    force_noise_kip: " << c.force_noise_kip
    << "\n    delay_steps: " << c.delay_steps << "\n    seed: " << c.seed << "\n  lyapunov:\n    reversal_lead: " << c.reversal_lead
    << "\n    motion_window_s: " << c.motion_window_s
    << "\n  clipped_optimal:\n    drift_weight_per_in2: " << c.drift_weight_per_in2
    << "\n    velocity_weight: " << c.velocity_weight << "\n    force_weight_per_kip2: " << c.force_weight_per_kip2
    << "\n    ground_accel_g: " << c.ground_accel_g << "\n    sensor_noise_g: " << c.sensor_noise_g
    << "\n    clipping: " << c.clipping << "\n  modulated_homogeneous:\n    gain_kip_per_in: " << c.gain_kip_per_in << "\n";
  return o.str();
}

Controller::Controller(const ControlConfig& config, const BuildingMatrices& b, const damper::BrfdParams& damper,
                       double dt_s)
    : config_(config),
      n_(static_cast<int>(b.mass.rows())),
      nd_(static_cast<int>(b.gamma.cols())),
      dt_(dt_s),
      inverse_(damper, config.min_kinetic_friction_kip) {
  if (b.gamma.rows() != n_ || b.stiffness.rows() != n_ || b.damping.rows() != n_)
    throw std::invalid_argument("controller: building matrix sizes do not match");
  if (!(dt_s > 0.0)) throw std::invalid_argument("controller: dt must be > 0");
  on_off_ = config.clipping == "on_off";
  ring_len_ = config.delay_steps + 1;
  ring_accel_.setZero(n_, ring_len_);
  ring_drift_.setZero(n_, ring_len_);
  ring_force_.setZero(nd_, ring_len_);
  ring_drum_.setZero(nd_, ring_len_);
  accel_.setZero(n_);
  drift_.setZero(n_);
  force_.setZero(nd_);
  drum_.setZero(nd_);
  drum_prev_.setZero(nd_);
  drum_vel_.setZero(nd_);
  desired_fc_.assign(nd_, 0.0);
  desired_force_.assign(nd_, 0.0);
  reversal_disp_.assign(nd_, 0.0);
  last_vel_sign_.assign(nd_, 0.0);
  reversal_release_.assign(nd_, 0);
  // At least 3 samples (a quadratic); motion_window_s rounded to whole steps.
  motion_fit_ = QuadraticMotionFit(std::max(3, static_cast<int>(std::lround(config.motion_window_s / dt_s))), dt_s);
  ring_fit_.setZero(nd_, motion_fit_.samples());
  if (config.law == Law::clipped_optimal) {
    // Continuous model of the building, state z = [x; ẋ], input u = F (damper forces),
    // disturbance ü_g; measured y = absolute floor accelerations = -M⁻¹(K x + C ẋ + Γ F).
    const Eigen::MatrixXd minv = b.mass.inverse();
    const int ns = 2 * n_;
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(ns, ns), bu = Eigen::MatrixXd::Zero(ns, nd_ + 1);
    a.topRightCorner(n_, n_).setIdentity();
    a.bottomLeftCorner(n_, n_) = -minv * b.stiffness;
    a.bottomRightCorner(n_, n_) = -minv * b.damping;
    bu.bottomLeftCorner(n_, nd_) = -minv * b.gamma;
    bu.bottomRightCorner(n_, 1) = -Eigen::VectorXd::Ones(n_);
    Eigen::MatrixXd bde;
    discretize_zoh(a, bu, dt_s, ad_, bde);
    bd_ = bde.leftCols(nd_);
    const Eigen::MatrixXd ed = bde.rightCols(1);
    cy_.resize(n_, ns);
    cy_ << -minv * b.stiffness, -minv * b.damping;
    dy_ = -minv * b.gamma;
    // LQR weights: drifts d = T x and (optionally) kinetic energy, forces.
    Eigen::MatrixXd t = Eigen::MatrixXd::Identity(n_, n_);
    for (int i = 1; i < n_; ++i) t(i, i - 1) = -1.0;
    Eigen::MatrixXd q = Eigen::MatrixXd::Zero(ns, ns);
    q.topLeftCorner(n_, n_) = config.drift_weight_per_in2 * t.transpose() * t;
    q.bottomRightCorner(n_, n_) = config.velocity_weight * b.mass;
    const Eigen::MatrixXd r = config.force_weight_per_kip2 * Eigen::MatrixXd::Identity(nd_, nd_);
    k_lqr_ = control::lqr_gain(ad_, bd_, q, r);
    const double w = config.ground_accel_g * kGravity_in_per_s2;
    const double v = config.sensor_noise_g * kGravity_in_per_s2;
    l_kf_ = control::kalman_gain(ad_, cy_, w * w * ed * ed.transpose(), v * v * Eigen::MatrixXd::Identity(n_, n_));
    xhat_.setZero(ns);
    xpred_.setZero(ns);
    innov_.setZero(n_);
    fd_.setZero(nd_);
  }
  reset();
}

void Controller::reset() {
  ring_pos_ = 0;
  frames_ = 0;
  rng_.seed(config_.seed);
  normal_.reset();
  drum_prev_.setZero();
  std::fill(reversal_disp_.begin(), reversal_disp_.end(), 0.0);
  std::fill(last_vel_sign_.begin(), last_vel_sign_.end(), 0.0);
  std::fill(reversal_release_.begin(), reversal_release_.end(), 0);
  fit_pos_ = 0;
  fit_count_ = 0;
  if (xhat_.size()) {
    xhat_.setZero();
    xpred_.setZero();
  }
}

void Controller::measure(const Measurements& m) {
  // Sensors: true value + white noise, into the delay line; the controller reads the oldest.
  const double an = config_.accel_noise_g * kGravity_in_per_s2, dn = config_.drift_noise_in, fn = config_.force_noise_kip;
  for (int i = 0; i < n_; ++i) {
    ring_accel_(i, ring_pos_) = (*m.floor_abs_accel_in_per_s2)[i] + (an > 0 ? an * normal_(rng_) : 0.0);
    ring_drift_(i, ring_pos_) = (*m.drift_in)[i] + (dn > 0 ? dn * normal_(rng_) : 0.0);
  }
  for (int k = 0; k < nd_; ++k) {
    ring_force_(k, ring_pos_) = (*m.force_kip)[k] + (fn > 0 ? fn * normal_(rng_) : 0.0);
    ring_drum_(k, ring_pos_) = (*m.drum_in)[k] + (dn > 0 ? dn * normal_(rng_) : 0.0);
  }
  ++frames_;
  const int lag = static_cast<int>(std::min<long>(config_.delay_steps, frames_ - 1));
  const int read = (ring_pos_ - lag + ring_len_) % ring_len_;
  ring_pos_ = (ring_pos_ + 1) % ring_len_;
  accel_ = ring_accel_.col(read);
  drift_ = ring_drift_.col(read);
  force_ = ring_force_.col(read);
  drum_prev_ = frames_ == 1 ? ring_drum_.col(read) : drum_;
  drum_ = ring_drum_.col(read);
  drum_vel_ = (drum_ - drum_prev_) / dt_;  // backward difference of the measured drum displacement
  if (config_.law == Law::lyapunov) {
    ring_fit_.col(fit_pos_) = drum_;
    fit_pos_ = (fit_pos_ + 1) % motion_fit_.samples();
    ++fit_count_;
  }
}

void Controller::compute(const Measurements& m, Eigen::MatrixX2d& targets) {
  measure(m);
  if (config_.law == Law::clipped_optimal) {
    // Kalman measurement update with this step's accelerations and forces, then the
    // prediction to the step the targets are for; f_d = -K x̂(i+1|i).
    innov_.noalias() = accel_ - cy_ * xpred_;
    innov_.noalias() -= dy_ * force_;
    xhat_ = xpred_;
    xhat_.noalias() += l_kf_ * innov_;
    xpred_.noalias() = ad_ * xhat_;
    xpred_.noalias() += bd_ * force_;
    fd_.noalias() = -k_lqr_ * xpred_;
  }
  for (int k = 0; k < nd_; ++k) {
    const double v = drum_vel_[k];
    ActuatorTargets t;
    switch (config_.law) {
      case Law::passive_off: t = inverse_.initial(); break;
      case Law::passive_on: t = inverse_.strongest(); break;
      case Law::lyapunov: {
        const FrictionRange r = inverse_.range(v, drum_[k]);
        bool release = force_[k] * v < 0.0;  // the band gives its stored energy back
        reversal_release_[k] = 0;
        const int n_fit = motion_fit_.samples();
        if (!release && config_.reversal_lead > 0.0 && fit_count_ >= n_fit) {
          // Predicted reversal: the drum decelerates and its speed falls to the Stribeck velocity
          // v_c (below it the static level governs, Eq. 5; 0 for the band brake) within
          // lead x T_rel: (|v̂| - v_c) / |â| < lead T_rel.
          double vh = 0.0, ah = 0.0;
          const int oldest = fit_pos_;  // the ring's next write position holds the oldest sample
          motion_fit_.estimate([&](int i) { return ring_fit_(k, (oldest + i) % n_fit); }, vh, ah);
          const double lead_s = config_.reversal_lead * inverse_.release_time_s(v, drum_[k]);
          if (vh * ah < 0.0 && std::abs(vh) < inverse_.stribeck_velocity_in_per_s() + lead_s * std::abs(ah)) {
            release = true;
            reversal_release_[k] = 1;
          }
        }
        t = inverse_.targets(release ? r.min_kip : r.max_kip, v, drum_[k]);
        break;
      }
      case Law::clipped_optimal: {
        const FrictionRange r = inverse_.range(v, drum_[k]);
        const double f = force_[k], fd = fd_[k];
        desired_force_[k] = fd;
        double fc = r.min_kip;
        if (fd * f > 0.0) fc = on_off_ ? (std::abs(fd) > std::abs(f) ? r.max_kip : r.min_kip) : std::abs(fd);
        t = inverse_.targets(fc, v, drum_[k]);
        break;
      }
      case Law::modulated_homogeneous: {
        const double sign = v > 0.0 ? 1.0 : v < 0.0 ? -1.0 : 0.0;
        if (sign != 0.0 && last_vel_sign_[k] != 0.0 && sign != last_vel_sign_[k]) reversal_disp_[k] = drum_prev_[k];
        if (sign != 0.0) last_vel_sign_[k] = sign;
        t = inverse_.targets(config_.gain_kip_per_in * std::abs(reversal_disp_[k]), v, drum_[k]);
        break;
      }
    }
    desired_fc_[k] = t.kinetic_friction_kip;
    targets(k, 0) = t.actuator1_in;
    targets(k, 1) = t.actuator2_in;
  }
}

}  // namespace control
