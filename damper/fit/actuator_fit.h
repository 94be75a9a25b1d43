#pragma once
/// @file actuator_fit.h
/// Identifies the electric actuator response (damper/model/electric_actuator.h) from the
/// measured semi-active tests (../shared/data/brfd/semiactive; Table 3 of the BRFD paper):
/// each test commanded one actuator (or both) through one cycle of a sine of known amplitude
/// (0.03 in, or 0.015 in for "both") during selected drum cycles, and recorded the positions
/// reached. The commanded shape r(t) = x' - A sin(2π (t - t0)/T) on [t0, t0 + T] (retract
/// first, as every recorded cycle does) is not recorded; its start t0 and period T are fitted
/// together with the time constant τ of a first-order lag, by least squares on a grid
/// (the amplitude A is known, so τ is seen in the amplitude loss and the phase of the shape;
/// a pure delay is absorbed in t0 and cannot be told apart). The velocity limit is bounded
/// below by the largest measured speed (position change over 10 ms).

#include "damper/data/brfd_data.h"

#include <vector>

namespace damper {

/// Fit of one actuator's first moving cycle in one test.
struct ActuatorCycleFit {
  int actuator = 1;
  double start_s = 0.0;             ///< fitted command start t0
  double period_s = 0.0;            ///< fitted command period T
  double time_constant_s = 0.0;     ///< fitted τ
  double rms_error_in = 0.0;        ///< RMS(measured - lagged command) over the cycle
  double rms_error_no_lag_in = 0.0; ///< same with τ = 0 (best t0, T): what the lag explains
  double peak_measured_in = 0.0;    ///< max |x - x'| over the cycle
  double peak_speed_in_per_s = 0.0; ///< max |x(t + 10 ms) - x(t)| / 10 ms
};

/// Fits the first moving cycle of each actuator that moves in `test` (amplitude_in per Table 3).
std::vector<ActuatorCycleFit> fit_actuator_cycles(const BrfdTest& test, double amplitude_in);

}  // namespace damper
