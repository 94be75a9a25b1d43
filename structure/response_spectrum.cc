#include "structure/response_spectrum.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace structure {

SdofPeak sdof_peak_response(const GroundMotion& record, double period_s, double damping_ratio) {
  if (!(std::isfinite(period_s) && period_s > 0.0))
    throw std::invalid_argument("SDOF period must be finite and > 0, got " + std::to_string(period_s));
  if (!(damping_ratio >= 0.0 && damping_ratio < 1.0))
    throw std::invalid_argument("SDOF damping ratio must be in [0, 1), got " + std::to_string(damping_ratio));
  if (!(record.dt_s > 0.0) || record.accel_g.size() < 2)
    throw std::invalid_argument("record " + record.source + " has fewer than two samples or no time step");

  // Chopra Table 5.2.1 with k = ω² (unit mass) and p(t) = −ü_g(t).
  const double pi = 3.14159265358979323846;
  // Sub-steps per record sample so that the peak is sampled at least kStepsPerPeriod times
  // per period (the recurrence itself is exact at any step; sampling a sine N times per
  // period misses its peak by at most 1 − cos(π/N) = 0.05 % for N = 100).
  constexpr double kStepsPerPeriod = 100.0;
  const int sub = std::max(1, static_cast<int>(std::ceil(kStepsPerPeriod * record.dt_s / period_s - 1e-9)));
  const double w = 2.0 * pi / period_s, z = damping_ratio, dt = record.dt_s / sub;
  const double sq = std::sqrt(1.0 - z * z);
  const double wd = w * sq;
  const double e = std::exp(-z * w * dt);
  const double s = std::sin(wd * dt), c = std::cos(wd * dt);
  const double k = w * w;
  const double A = e * (z / sq * s + c);
  const double B = e * (s / wd);
  const double C = (2.0 * z / (w * dt) + e * (((1.0 - 2.0 * z * z) / (wd * dt) - z / sq) * s -
                                             (1.0 + 2.0 * z / (w * dt)) * c)) / k;
  const double D = (1.0 - 2.0 * z / (w * dt) + e * ((2.0 * z * z - 1.0) / (wd * dt) * s + 2.0 * z / (w * dt) * c)) / k;
  const double Ap = -e * (w / sq * s);
  const double Bp = e * (c - z / sq * s);
  const double Cp = (-1.0 / dt + e * ((w / sq + z / (dt * sq)) * s + c / dt)) / k;
  const double Dp = (1.0 - e * (z / sq * s + c)) / (k * dt);

  double u = 0.0, v = 0.0;
  SdofPeak peak;
  const std::size_t n = record.accel_g.size();
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double a0 = record.accel_g[i], a1 = record.accel_g[i + 1];
    for (int j = 0; j < sub; ++j) {
      const double p0 = -(a0 + (a1 - a0) * j / sub), p1 = -(a0 + (a1 - a0) * (j + 1) / sub);
      const double u1 = A * u + B * v + C * p0 + D * p1;
      const double v1 = Ap * u + Bp * v + Cp * p0 + Dp * p1;
      u = u1;
      v = v1;
      if (std::abs(u) > peak.peak_disp_g_s2) {
        peak.peak_disp_g_s2 = std::abs(u);
        peak.peak_time_s = (static_cast<double>(i) + static_cast<double>(j + 1) / sub) * record.dt_s;
      }
    }
  }
  peak.pseudo_accel_g = k * peak.peak_disp_g_s2;
  return peak;
}

double spectral_accel_g(const GroundMotion& record, double period_s, double damping_ratio) {
  return sdof_peak_response(record, period_s, damping_ratio).pseudo_accel_g;
}

}  // namespace structure
