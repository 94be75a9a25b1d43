#pragma once
/// @file tracking.h
/// Tracking indicators of a physical run: how well the measured drum displacement followed
/// the target the structure asked for.
///  - delay_ms: the lag (ms) that maximises the cross-correlation of measured and target,
///    searched over [-max_lag, +max_lag] and refined to a fraction of a sample by a parabola
///    through the peak; positive = measured lags the target.
///  - nrms_error_pct: RMS(measured - target) / max|target| · 100.
///  - peak_error_in: max |measured - target|.
///
/// Time base of the delay. A lab controller (or brfd-rig) runs its actuator on its own clock,
/// one sensor frame per period; the substructure answers one server step per frame only while
/// the whole loop keeps real time. When it falls behind (a loaded machine), the controller
/// ticks more than once per step, holding the last command, and a delay measured on the
/// per-step series counts steps, not controller periods: a 20 ms delay + 6 ms lag measured
/// 19.8 ms on a loop running at ~78 % of real time (issue 18). The actuator's delay is
/// therefore measured on the controller's clock: controller_time_series() places the target of
/// the command in force at each frame (the frame says which command that is) and the measured
/// displacement at that frame's tick number. On that clock a delay line of D s and a discrete
/// first-order lag of time constant tau (the rig's exact update x += (1 - e^{-T/tau})(u - x),
/// T the period) measure D + phase delay of the lag, ≈ D + tau - T/2 for slow motion,
/// independent of how fast the loop ran.

#include <cstddef>
#include <cstdint>
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

/// One sensor frame as the substructure received it.
struct FrameSample {
  int64_t frame_sequence = 0;    ///< the controller's period counter (sensor_frame_t.sequence)
  int64_t command_sequence = 0;  ///< the actuator command in force at that period
  double measured_in = 0.0;      ///< measured drum displacement
};

/// Target and measured drum displacement on the controller's clock, one sample per period.
struct ControllerTimeSeries {
  std::vector<double> target_in, measured_in;
  long missing_frames = 0;  ///< periods with no frame received: target held, measured interpolated
};

/// Frames whose command in force is one of the commands [first_command_sequence,
/// first_command_sequence + target_by_command.size()) (target_by_command[i] is the target of
/// command first_command_sequence + i), placed at their period number. Frames out of order
/// are dropped; a gap of missing periods is filled (target of the earlier frame held,
/// measured linearly interpolated) and counted.
ControllerTimeSeries controller_time_series(const std::vector<FrameSample>& frames,
                                            const std::vector<double>& target_by_command,
                                            int64_t first_command_sequence);

/// One line: "delay 21.3 ms, NRMS error 4.1 %, peak error 0.052 in (30720 samples)".
std::string format_tracking(const TrackingIndicators& t);

}  // namespace damper::physical
