#include "control/motion_fit.h"

#include <Eigen/Dense>

#include <stdexcept>

namespace control {

QuadraticMotionFit::QuadraticMotionFit(int n, double dt) {
  if (n < 3) throw std::invalid_argument("quadratic motion fit needs at least 3 samples");
  if (!(dt > 0.0)) throw std::invalid_argument("quadratic motion fit needs dt > 0");
  Eigen::MatrixXd x(n, 3);
  for (int i = 0; i < n; ++i) {
    const double t = (i - (n - 1)) * dt;
    x(i, 0) = 1.0;
    x(i, 1) = t;
    x(i, 2) = t * t;
  }
  // Least squares c = (XᵀX)⁻¹ Xᵀ d: rows 1 and 2 of the pseudo-inverse are the weights.
  const Eigen::MatrixXd pinv = (x.transpose() * x).ldlt().solve(x.transpose());
  wv_.resize(n);
  wa_.resize(n);
  for (int i = 0; i < n; ++i) {
    wv_[i] = pinv(1, i);
    wa_[i] = 2.0 * pinv(2, i);
  }
}

}  // namespace control
