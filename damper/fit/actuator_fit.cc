#include "damper/fit/actuator_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace damper {

namespace {

// RMS error of a first-order lag (τ) following the one-cycle sine command (t0, T).
double cycle_error(const std::vector<double>& t, const std::vector<double>& x, std::size_t i0, std::size_t i1, double x0,
                   double amp, double t0, double period, double tau, double dt) {
  const double w = tau > 0.0 ? 1.0 - std::exp(-dt / tau) : 1.0;
  double y = x0, sum = 0.0;
  for (std::size_t i = i0; i < i1; ++i) {
    const double s = t[i] - t0;
    const double r = (s >= 0.0 && s <= period) ? x0 - amp * std::sin(2.0 * M_PI * s / period) : x0;
    const double e = x[i] - y;
    sum += e * e;
    y += (r - y) * w;  // exact first-order step with the command held over dt
  }
  return std::sqrt(sum / static_cast<double>(i1 - i0));
}

}  // namespace

std::vector<ActuatorCycleFit> fit_actuator_cycles(const BrfdTest& test, double amp) {
  std::vector<ActuatorCycleFit> fits;
  const double dt = test.dt_s;
  const std::vector<double>& t = test.time_s;
  for (int a = 1; a <= 2; ++a) {
    const std::vector<double>& x = a == 1 ? test.actuator1_in : test.actuator2_in;
    if (x.empty()) continue;
    const double x0 = x.front();
    std::size_t first = x.size();
    for (std::size_t i = 0; i < x.size(); ++i)
      if (std::abs(x[i] - x0) > 0.3 * amp) {
        first = i;
        break;
      }
    if (first == x.size()) continue;  // this actuator holds its position
    // back to where the motion starts (last sample within 1 % of the amplitude)
    std::size_t move = first;
    while (move > 0 && std::abs(x[move] - x0) > 0.01 * amp) --move;
    const std::size_t guard = static_cast<std::size_t>(0.3 / dt);
    const std::size_t i0 = move > guard ? move - guard : 0;
    const std::size_t i1 = std::min(x.size(), move + static_cast<std::size_t>(1.5 / dt));
    ActuatorCycleFit best;
    best.actuator = a;
    double best_err = std::numeric_limits<double>::infinity(), best_err0 = best_err;
    auto search = [&](double t0_lo, double t0_hi, double t0_step, double p_lo, double p_hi, double p_step, double tau_lo,
                      double tau_hi, double tau_step) {
      for (double t0 = t0_lo; t0 <= t0_hi; t0 += t0_step)
        for (double p = p_lo; p <= p_hi; p += p_step)
          for (double tau = tau_lo; tau <= tau_hi + 1e-12; tau += tau_step) {
            const double e = cycle_error(t, x, i0, i1, x0, amp, t0, p, tau, dt);
            if (e < best_err) {
              best_err = e;
              best.start_s = t0;
              best.period_s = p;
              best.time_constant_s = tau;
            }
            if (tau == 0.0 && e < best_err0) best_err0 = e;
          }
    };
    const double tm = t[move];
    search(tm - 0.15, tm + 0.01, 3 * dt, 0.9, 1.1, 0.01, 0.0, 0.08, 0.004);
    const ActuatorCycleFit coarse = best;
    search(coarse.start_s - 4 * dt, coarse.start_s + 4 * dt, dt, coarse.period_s - 0.01, coarse.period_s + 0.01, 0.002,
           std::max(0.0, coarse.time_constant_s - 0.004), coarse.time_constant_s + 0.004, 0.0005);
    best.rms_error_in = best_err;
    best.rms_error_no_lag_in = best_err0;
    const std::size_t w = static_cast<std::size_t>(std::lround(0.01 / dt));
    for (std::size_t i = i0; i < i1; ++i) {
      best.peak_measured_in = std::max(best.peak_measured_in, std::abs(x[i] - x0));
      if (i + w < x.size()) best.peak_speed_in_per_s = std::max(best.peak_speed_in_per_s, std::abs(x[i + w] - x[i]) / (w * dt));
    }
    fits.push_back(best);
  }
  return fits;
}

}  // namespace damper
