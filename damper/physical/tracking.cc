#include "damper/physical/tracking.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace damper::physical {

double cross_correlation_delay_ms(const std::vector<double>& x, const std::vector<double>& y, double dt_s,
                                  std::size_t begin, std::size_t end, int max_lag) {
  end = std::min({end, x.size(), y.size()});
  if (end <= begin || end - begin <= static_cast<std::size_t>(2 * max_lag) + 2) return 0.0;
  // Means removed; the overlap is the same range [begin + max_lag, end - max_lag) of x for
  // every lag, so correlations of different lags compare fairly.
  double mx = 0.0, my = 0.0;
  for (std::size_t i = begin; i < end; ++i) {
    mx += x[i];
    my += y[i];
  }
  mx /= static_cast<double>(end - begin);
  my /= static_cast<double>(end - begin);
  const std::size_t lo = begin + static_cast<std::size_t>(max_lag), hi = end - static_cast<std::size_t>(max_lag);
  std::vector<double> r(static_cast<std::size_t>(2 * max_lag + 1), 0.0);
  for (int lag = -max_lag; lag <= max_lag; ++lag) {
    double s = 0.0, sy = 0.0;
    for (std::size_t i = lo; i < hi; ++i) {
      const double yi = y[static_cast<std::size_t>(static_cast<long>(i) + lag)] - my;
      s += (x[i] - mx) * yi;
      sy += yi * yi;
    }
    r[static_cast<std::size_t>(lag + max_lag)] = sy > 0.0 ? s / std::sqrt(sy) : 0.0;
  }
  const auto best = std::max_element(r.begin(), r.end());
  const long k = best - r.begin();
  double frac = 0.0;
  if (k > 0 && k + 1 < static_cast<long>(r.size())) {
    const double a = r[static_cast<std::size_t>(k - 1)], b = r[static_cast<std::size_t>(k)],
                 c = r[static_cast<std::size_t>(k + 1)];
    const double den = a - 2.0 * b + c;
    if (den < 0.0) frac = 0.5 * (a - c) / den;
  }
  return (static_cast<double>(k - max_lag) + frac) * dt_s * 1e3;
}

TrackingIndicators tracking_indicators(const std::vector<double>& target, const std::vector<double>& measured,
                                       double dt_s, std::size_t begin, std::size_t end, int max_lag) {
  TrackingIndicators t;
  end = std::min({end, target.size(), measured.size()});
  if (end <= begin) return t;
  double sum2 = 0.0;
  for (std::size_t i = begin; i < end; ++i) {
    const double e = measured[i] - target[i];
    sum2 += e * e;
    t.peak_error_in = std::max(t.peak_error_in, std::abs(e));
    t.peak_target_in = std::max(t.peak_target_in, std::abs(target[i]));
  }
  t.samples = end - begin;
  t.rms_error_in = std::sqrt(sum2 / static_cast<double>(t.samples));
  t.nrms_error_pct = t.peak_target_in > 0.0 ? 100.0 * t.rms_error_in / t.peak_target_in : 0.0;
  t.delay_ms = cross_correlation_delay_ms(target, measured, dt_s, begin, end, max_lag);
  return t;
}

ControllerTimeSeries controller_time_series(const std::vector<FrameSample>& frames,
                                            const std::vector<double>& target_by_command,
                                            int64_t first_command_sequence) {
  ControllerTimeSeries s;
  const int64_t last_command = first_command_sequence + static_cast<int64_t>(target_by_command.size());
  int64_t previous = -1;
  for (const FrameSample& f : frames) {
    if (f.command_sequence < first_command_sequence || f.command_sequence >= last_command) continue;
    if (previous >= 0 && f.frame_sequence <= previous) continue;  // out of order
    const double target = target_by_command[static_cast<std::size_t>(f.command_sequence - first_command_sequence)];
    if (previous >= 0 && f.frame_sequence > previous + 1) {
      const int64_t gap = f.frame_sequence - previous;
      const double m0 = s.measured_in.back(), t0 = s.target_in.back();
      for (int64_t j = 1; j < gap; ++j) {
        s.target_in.push_back(t0);
        s.measured_in.push_back(m0 + (f.measured_in - m0) * static_cast<double>(j) / static_cast<double>(gap));
        ++s.missing_frames;
      }
    }
    s.target_in.push_back(target);
    s.measured_in.push_back(f.measured_in);
    previous = f.frame_sequence;
  }
  return s;
}

std::string format_tracking(const TrackingIndicators& t) {
  char b[200];
  std::snprintf(b, sizeof b, "delay %.2f ms, NRMS error %.2f %%, RMS error %.4f in, peak error %.4f in (%zu samples)",
                t.delay_ms, t.nrms_error_pct, t.rms_error_in, t.peak_error_in, t.samples);
  return b;
}

}  // namespace damper::physical
