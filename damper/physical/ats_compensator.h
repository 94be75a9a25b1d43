#pragma once
/// @file ats_compensator.h
/// Adaptive time series (ATS) delay compensator of Chae, Kazemibidokhti and Ricles (2013),
/// "Adaptive time series compensator for delay compensation of servo-hydraulic actuator
/// systems for real-time hybrid simulation", Earthquake Engng Struct. Dyn. 42:1697-1715.
///
/// Compensated command from the target drum displacement x_t (in):
///     x_c = a0·x_t + a1·ẋ_t + a2·ẍ_t
/// The coefficients are the inverse actuator model, identified by moving-window least
/// squares of the commanded displacement on the measured one and its derivatives,
///     x_c(k) ≈ a0·x_m(k) + a1·ẋ_m(k) + a2·ẍ_m(k),   k over the last window_s,
/// updated every `update_every` samples and bounded (a0 in [0.7, 1.3], a1 in [0, 0.08] s,
/// a2 in [0, 0.0032] s² by default): a box-constrained least-squares problem solved exactly.
/// For a pure delay τ, a0 = 1, a1 = τ, a2 = τ²/2; a1/a0 is the delay being compensated.
///
/// Details (ours): derivatives are backward differences, the same operator on the target and
/// on the measurement; before the fit the commanded and measured signals pass the same
/// 2nd-order Butterworth low-pass (filter_hz), which keeps the relation between them (both are
/// filtered alike) while keeping load-cell/LVDT noise out of the differentiated regressors. A
/// new coefficient set is blended in linearly over the next update period, so an update never
/// steps the command. No update while the windowed motion is below min_rms_in.
/// Allocation-free after construction.

#include "damper/physical/physical_config.h"

#include <Eigen/Dense>

#include <vector>

namespace damper::physical {

/// 2nd-order Butterworth low-pass (bilinear transform, pre-warped), direct form II transposed.
class Biquad {
 public:
  Biquad() = default;
  Biquad(double cutoff_hz, double sample_hz);
  /// Sets the state as if `x` had been the input forever (no start transient).
  void reset(double x);
  double operator()(double x);

 private:
  double b0_ = 1, b1_ = 0, b2_ = 0, a1_ = 0, a2_ = 0;
  double s1_ = 0, s2_ = 0;
};

class AtsCompensator {
 public:
  AtsCompensator(const AtsSettings& settings, double dt_s);

  /// Back to the initial coefficients, history at x (in).
  void reset(double x_in);
  /// x_c for target x_t at this sample; call once per sample, before observe(). With
  /// compensation disabled returns x_t (identification still runs, for the report).
  double compensate(double target_in);
  /// The displacement actually commanded at this sample and the one measured for it.
  void observe(double commanded_in, double measured_in);

  /// Coefficients in use at this sample (blended), and the last identified set.
  const Eigen::Vector3d& coefficients() const { return current_; }
  const Eigen::Vector3d& identified() const { return target_; }
  long updates() const { return updates_; }
  /// Solves min ||Φa - y||² with lo <= a <= hi given G = ΦᵀΦ, g = Φᵀy (exact, by active
  /// sets). Exposed for tests.
  static Eigen::Vector3d bounded_least_squares(const Eigen::Matrix3d& G, const Eigen::Vector3d& g,
                                               const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

 private:
  void identify();

  AtsSettings s_;
  double dt_;
  Eigen::Vector3d lo_, hi_;
  Eigen::Vector3d current_, previous_, target_;
  int blend_step_ = 0;
  // Target history for the backward differences.
  double xt1_ = 0, xt2_ = 0;
  // Filtered commanded / measured and the measured history for differences.
  Biquad filter_c_, filter_m_;
  double fm1_ = 0, fm2_ = 0;
  bool primed_ = false;
  int primed_samples_ = 0;
  // Ring buffer of regressors [f_m, ḟ_m, f̈_m] and the filtered command.
  std::vector<Eigen::Vector3d> phi_;
  std::vector<double> y_;
  std::size_t head_ = 0, count_ = 0;
  int since_update_ = 0;
  long updates_ = 0;
};

}  // namespace damper::physical
