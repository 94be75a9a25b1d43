#pragma once
/// @file criteria.h
/// Evaluation criteria of controlled buildings in the terms of the benchmark for seismically
/// excited buildings (Ohtori, Christenson, Spencer & Dyke 2004, J. Eng. Mech. 130(4) 366-385),
/// each relative to the same building without dampers under the same record:
///   J1 = max_t,i |d_i(t)|/h_i  / same uncontrolled   (peak interstory drift ratio)
///   J2 = max_t,i |ẍ_a,i(t)|    / same uncontrolled   (peak floor absolute acceleration)
///   J3 = max_t |Σ m_i ẍ_a,i(t)| / same uncontrolled  (peak base shear)
///   J1_rms, J2_rms, J3_rms: the same with the time RMS in place of the time peak (max over
///   stories/floors of the RMS), the benchmark's normed criteria.
/// Story heights are equal in our buildings (the config has none), so h_i cancels in J1.
/// Plus, per damper: peak force, dissipated energy, and actuator effort (total travel of both
/// electric actuators, in, and their peak speed, in/s).

#include <Eigen/Dense>

#include <string>

namespace control {

/// Peaks and time RMS of one response history, fed step by step (allocation-free).
class ResponseStats {
 public:
  ResponseStats() = default;
  ResponseStats(int stories, const Eigen::VectorXd& floor_mass);
  /// One step: drifts (in), floor absolute accelerations (in/s²).
  void add(const Eigen::VectorXd& drift_in, const Eigen::VectorXd& abs_accel_in_per_s2);
  double peak_drift_in() const { return peak_drift_; }
  double peak_accel_in_per_s2() const { return peak_accel_; }
  double peak_base_shear_kip() const { return peak_shear_; }
  double rms_drift_in() const;          ///< max over stories of the RMS drift
  double rms_accel_in_per_s2() const;   ///< max over floors of the RMS acceleration
  double rms_base_shear_kip() const;
  long samples() const { return count_; }

 private:
  Eigen::VectorXd mass_, sum_d2_, sum_a2_;
  double sum_v2_ = 0.0, peak_drift_ = 0.0, peak_accel_ = 0.0, peak_shear_ = 0.0;
  long count_ = 0;
};

/// The J criteria of a controlled run against the uncontrolled one.
struct Criteria {
  double j1 = 0, j2 = 0, j3 = 0, j1_rms = 0, j2_rms = 0, j3_rms = 0;
};
Criteria evaluate_criteria(const ResponseStats& controlled, const ResponseStats& uncontrolled);

}  // namespace control
