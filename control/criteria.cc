#include "control/criteria.h"

#include <cmath>

namespace control {

ResponseStats::ResponseStats(int stories, const Eigen::VectorXd& floor_mass)
    : mass_(floor_mass), sum_d2_(Eigen::VectorXd::Zero(stories)), sum_a2_(Eigen::VectorXd::Zero(stories)) {}

void ResponseStats::add(const Eigen::VectorXd& d, const Eigen::VectorXd& a) {
  double shear = 0.0;
  for (Eigen::Index i = 0; i < d.size(); ++i) {
    sum_d2_[i] += d[i] * d[i];
    sum_a2_[i] += a[i] * a[i];
    peak_drift_ = std::max(peak_drift_, std::abs(d[i]));
    peak_accel_ = std::max(peak_accel_, std::abs(a[i]));
    shear += mass_[i] * a[i];
  }
  sum_v2_ += shear * shear;
  peak_shear_ = std::max(peak_shear_, std::abs(shear));
  ++count_;
}

double ResponseStats::rms_drift_in() const { return count_ ? std::sqrt(sum_d2_.maxCoeff() / count_) : 0.0; }
double ResponseStats::rms_accel_in_per_s2() const { return count_ ? std::sqrt(sum_a2_.maxCoeff() / count_) : 0.0; }
double ResponseStats::rms_base_shear_kip() const { return count_ ? std::sqrt(sum_v2_ / count_) : 0.0; }

Criteria evaluate_criteria(const ResponseStats& c, const ResponseStats& u) {
  auto ratio = [](double a, double b) { return b > 0.0 ? a / b : 0.0; };
  Criteria j;
  j.j1 = ratio(c.peak_drift_in(), u.peak_drift_in());
  j.j2 = ratio(c.peak_accel_in_per_s2(), u.peak_accel_in_per_s2());
  j.j3 = ratio(c.peak_base_shear_kip(), u.peak_base_shear_kip());
  j.j1_rms = ratio(c.rms_drift_in(), u.rms_drift_in());
  j.j2_rms = ratio(c.rms_accel_in_per_s2(), u.rms_accel_in_per_s2());
  j.j3_rms = ratio(c.rms_base_shear_kip(), u.rms_base_shear_kip());
  return j;
}

}  // namespace control
