#pragma once
// Closed-form responses of a viscously damped SDOF oscillator m ẍ + c ẋ + k x = −m ü_g,
// written as ẍ + 2ζω ẋ + ω² x = −ü_g (ζ < 1). Independent references for the integrators.

#include <cmath>

namespace structure::testing {

struct Sdof {
  double omega;  // natural circular frequency, rad/s
  double zeta;   // damping ratio
  double omega_d() const { return omega * std::sqrt(1.0 - zeta * zeta); }

  // Free vibration from x(0) = x0, ẋ(0) = v0.
  double free_disp(double t, double x0, double v0) const {
    const double wd = omega_d();
    return std::exp(-zeta * omega * t) * (x0 * std::cos(wd * t) + (v0 + zeta * omega * x0) / wd * std::sin(wd * t));
  }

  // Response from rest to ü_g(t) = a·sin(Ωt): particular + homogeneous part.
  double harmonic_disp(double t, double a, double big_omega) const {
    const double w2 = omega * omega, W = big_omega;
    const double den = (w2 - W * W) * (w2 - W * W) + (2.0 * zeta * omega * W) * (2.0 * zeta * omega * W);
    const double c1 = -a * (w2 - W * W) / den;           // coefficient of sin Ωt
    const double c2 = a * 2.0 * zeta * omega * W / den;  // coefficient of cos Ωt
    const double wd = omega_d();
    const double b1 = -c2;                                      // x(0) = 0
    const double b2 = (zeta * omega * b1 - W * c1) / wd;        // ẋ(0) = 0
    return c1 * std::sin(W * t) + c2 * std::cos(W * t) +
           std::exp(-zeta * omega * t) * (b1 * std::cos(wd * t) + b2 * std::sin(wd * t));
  }
};

}  // namespace structure::testing
