#pragma once
/// @file motion_fit.h
/// Velocity and acceleration of a sampled displacement at its newest sample, by a least-squares
/// quadratic d(t) = c0 + c1 t + c2 t² over the last N samples (t = 0 at the newest, -(N-1) dt at
/// the oldest): v = c1, a = 2 c2 (the Savitzky-Golay end-point derivative filter). Exact for any
/// quadratic motion; white noise of std σ on the samples reaches a as σ sqrt(Σ w_a²): 0.026 σ/dt²
/// with N = 16 (the three-point second difference: 2.45 σ/dt²), and v as 0.21 σ/dt. Used by the
/// Lyapunov law (control/controller.h) to predict the drum's next reversal from the measured
/// drum displacement. Weights computed once (Eigen); estimate() does not allocate.
/// Units: in, s.

#include <vector>

namespace control {

class QuadraticMotionFit {
 public:
  QuadraticMotionFit() = default;
  /// @throws std::invalid_argument if samples < 3 or dt_s <= 0.
  QuadraticMotionFit(int samples, double dt_s);
  int samples() const { return static_cast<int>(wv_.size()); }
  /// Velocity (in/s) and acceleration (in/s²) at the newest of samples() displacements given
  /// oldest first: x(i) for i = 0 .. samples()-1, x a callable (ring buffers, CSV columns).
  template <class Sample>
  void estimate(const Sample& x, double& velocity, double& acceleration) const {
    double v = 0.0, a = 0.0;
    for (int i = 0; i < samples(); ++i) {
      const double d = x(i);
      v += wv_[i] * d;
      a += wa_[i] * d;
    }
    velocity = v;
    acceleration = a;
  }

 private:
  std::vector<double> wv_, wa_;  // oldest first
};

}  // namespace control
