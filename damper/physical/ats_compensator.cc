#include "damper/physical/ats_compensator.h"

#include <cmath>
#include <limits>

namespace damper::physical {

Biquad::Biquad(double fc, double fs) {
  const double k = std::tan(M_PI * fc / fs);  // pre-warped
  const double q = 1.0 / std::sqrt(2.0);      // Butterworth
  const double norm = 1.0 / (1.0 + k / q + k * k);
  b0_ = k * k * norm;
  b1_ = 2.0 * b0_;
  b2_ = b0_;
  a1_ = 2.0 * (k * k - 1.0) * norm;
  a2_ = (1.0 - k / q + k * k) * norm;
}

void Biquad::reset(double x) {
  // DC gain is 1: steady state y = x, s1 = y - b0 x, s2 = b2 x - a2 y.
  s2_ = b2_ * x - a2_ * x;
  s1_ = x - b0_ * x;
}

double Biquad::operator()(double x) {
  const double y = b0_ * x + s1_;
  s1_ = b1_ * x - a1_ * y + s2_;
  s2_ = b2_ * x - a2_ * y;
  return y;
}

AtsCompensator::AtsCompensator(const AtsSettings& settings, double dt_s)
    : s_(settings),
      dt_(dt_s),
      lo_(settings.a0_min, settings.a1_min_s, settings.a2_min_s2),
      hi_(settings.a0_max, settings.a1_max_s, settings.a2_max_s2),
      filter_c_(settings.filter_hz, 1.0 / dt_s),
      filter_m_(settings.filter_hz, 1.0 / dt_s) {
  const std::size_t n = static_cast<std::size_t>(std::max(8.0, std::round(settings.window_s / dt_s)));
  phi_.assign(n, Eigen::Vector3d::Zero());
  y_.assign(n, 0.0);
  reset(0.0);
}

void AtsCompensator::reset(double x) {
  const double tau = s_.initial_delay_s;
  current_ = Eigen::Vector3d(1.0, tau, 0.5 * tau * tau).cwiseMax(lo_).cwiseMin(hi_);
  previous_ = target_ = current_;
  blend_step_ = s_.update_every;
  xt1_ = xt2_ = x;
  filter_c_.reset(x);
  filter_m_.reset(x);
  fm1_ = fm2_ = x;
  primed_ = false;
  primed_samples_ = 0;
  head_ = count_ = 0;
  since_update_ = 0;
  updates_ = 0;
}

double AtsCompensator::compensate(double xt) {
  // Blend towards the last identified set over one update period.
  if (blend_step_ < s_.update_every) {
    ++blend_step_;
    const double w = static_cast<double>(blend_step_) / s_.update_every;
    current_ = previous_ + w * (target_ - previous_);
  }
  const double v = (xt - xt1_) / dt_;
  const double a = (xt - 2.0 * xt1_ + xt2_) / (dt_ * dt_);
  xt2_ = xt1_;
  xt1_ = xt;
  if (!s_.enabled) return xt;
  return current_[0] * xt + current_[1] * v + current_[2] * a;
}

void AtsCompensator::observe(double commanded, double measured) {
  const double fc = filter_c_(commanded);
  const double fm = filter_m_(measured);
  const double v = (fm - fm1_) / dt_;
  const double a = (fm - 2.0 * fm1_ + fm2_) / (dt_ * dt_);
  fm2_ = fm1_;
  fm1_ = fm;
  if (!primed_) {  // the differences need two past samples
    if (++primed_samples_ < 3) return;
    primed_ = true;
  }
  phi_[head_] = Eigen::Vector3d(fm, v, a);
  y_[head_] = fc;
  head_ = (head_ + 1) % phi_.size();
  if (count_ < phi_.size()) ++count_;
  if (++since_update_ >= s_.update_every && count_ == phi_.size()) {
    since_update_ = 0;
    identify();
  }
}

void AtsCompensator::identify() {
  Eigen::Matrix3d G = Eigen::Matrix3d::Zero();
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  double sum_x2 = 0.0, sum_x = 0.0;
  for (std::size_t i = 0; i < count_; ++i) {
    const Eigen::Vector3d& p = phi_[i];
    G.noalias() += p * p.transpose();
    g.noalias() += p * y_[i];
    sum_x += p[0];
    sum_x2 += p[0] * p[0];
  }
  const double n = static_cast<double>(count_);
  const double var = sum_x2 / n - (sum_x / n) * (sum_x / n);
  if (!(std::sqrt(std::max(var, 0.0)) >= s_.min_rms_in)) return;  // too little motion to identify
  const Eigen::Vector3d a = bounded_least_squares(G, g, lo_, hi_);
  if (!a.allFinite()) return;
  previous_ = current_;
  target_ = a;
  blend_step_ = 0;
  ++updates_;
}

Eigen::Vector3d AtsCompensator::bounded_least_squares(const Eigen::Matrix3d& G_in, const Eigen::Vector3d& g_in,
                                                      const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  // Scale the columns to unit diagonal: x ~ 1 in, ẋ ~ 10 in/s, ẍ ~ 100 in/s² differ a lot.
  Eigen::Vector3d d;
  for (int i = 0; i < 3; ++i) d[i] = G_in(i, i) > 0.0 ? 1.0 / std::sqrt(G_in(i, i)) : 1.0;
  const Eigen::Matrix3d G = d.asDiagonal() * G_in * d.asDiagonal();
  const Eigen::Vector3d g = d.cwiseProduct(g_in);
  const Eigen::Vector3d slo = lo.cwiseQuotient(d), shi = hi.cwiseQuotient(d);
  // The box-constrained convex QP min ½bᵀGb − gᵀb has its optimum at one of the 27 active
  // sets (each variable free, at its lower or at its upper bound): try them all.
  Eigen::Vector3d best = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  double best_obj = std::numeric_limits<double>::infinity();
  for (int code = 0; code < 27; ++code) {
    int state[3] = {code % 3, (code / 3) % 3, code / 9};  // 0 free, 1 lower, 2 upper
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for (int i = 0; i < 3; ++i)
      if (state[i] != 0) b[i] = state[i] == 1 ? slo[i] : shi[i];
    if (state[0] == 0 || state[1] == 0 || state[2] == 0) {
      // Reduced normal equations, kept 3x3 (fixed variables get identity rows): no allocation.
      Eigen::Matrix3d A = G;
      Eigen::Vector3d rhs = g - G * b;
      for (int i = 0; i < 3; ++i) {
        if (state[i] == 0) continue;
        A.row(i).setZero();
        A.col(i).setZero();
        A(i, i) = 1.0;
        rhs[i] = 0.0;
      }
      const Eigen::LDLT<Eigen::Matrix3d> ldlt(A);
      if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) continue;
      const Eigen::Vector3d sol = ldlt.solve(rhs);
      bool feasible = sol.allFinite();
      for (int i = 0; i < 3 && feasible; ++i) {
        if (state[i] != 0) continue;
        const double tol = 1e-12 * (1.0 + std::abs(shi[i] - slo[i]));
        feasible = sol[i] >= slo[i] - tol && sol[i] <= shi[i] + tol;
        b[i] = std::min(std::max(sol[i], slo[i]), shi[i]);
      }
      if (!feasible) continue;
    }
    const double obj = 0.5 * b.dot(G * b) - g.dot(b);
    if (obj < best_obj) {
      best_obj = obj;
      best = b;
    }
  }
  return best.cwiseProduct(d);
}

}  // namespace damper::physical
