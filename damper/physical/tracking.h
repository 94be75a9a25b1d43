#pragma once
/// @file tracking.h
/// Tracking indicators of a physical run: how well the measured drum displacement followed
/// the target the structure asked for.
///  - delay_ms: the lag (ms) that maximises the cross-correlation of measured and target,
///    searched over [-max_lag, +max_lag] and refined to a fraction of a sample by a parabola
///    through the peak; positive = measured lags the target.
///  - nrms_error_pct: RMS(measured - target) / max|target| · 100.
///  - peak_error_in: max |measured - target|.

#include <cstddef>
#include <string>
#include <vector>

namespace damper::physical {

struct TrackingIndicators {
  double delay_ms = 0.0;
  double rms_error_in = 0.0;
  double nrms_error_pct = 0.0;
  double peak_error_in = 0.0;
  double peak_target_in = 0.0;
  std::size_t samples = 0;
};

/// Indicators over samples [begin, end) of equally long target/measured series sampled every
/// dt_s. Requires end - begin > 2 * max_lag_samples; otherwise delay_ms is 0.
TrackingIndicators tracking_indicators(const std::vector<double>& target_in, const std::vector<double>& measured_in,
                                       double dt_s, std::size_t begin, std::size_t end,
                                       int max_lag_samples = 128);

/// Delay (ms) of `y` behind `x` by cross-correlation (see file comment).
double cross_correlation_delay_ms(const std::vector<double>& x, const std::vector<double>& y, double dt_s,
                                  std::size_t begin, std::size_t end, int max_lag_samples);

/// One line: "delay 21.3 ms, NRMS error 4.1 %, peak error 0.052 in (30720 samples)".
std::string format_tracking(const TrackingIndicators& t);

}  // namespace damper::physical
