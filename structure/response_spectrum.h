#pragma once
/// @file response_spectrum.h
/// Elastic response of a linear SDOF oscillator to a ground-motion record, for the intensity
/// measure of incremental dynamic analysis: the pseudo-spectral acceleration
///   Sa(T, ζ) = ω²·max_t |u(t)|,   ü + 2ζω u̇ + ω² u = −ü_g(t),   ω = 2π/T,
/// in g (the record's unit). The oscillator starts at rest and is integrated with the exact
/// recurrence for piecewise-linear excitation (Nigam & Jennings 1969; Chopra, "Dynamics of
/// Structures", 4th ed., §5.2, Table 5.2.1): between samples the record is linear, as
/// GroundMotion::accel_in_per_s2 interpolates it, and the recurrence is exact for that
/// excitation, so no time-step error is added to the record's own sampling. Each sample
/// interval is split into sub-steps so that |u| is sampled at least 100 times per period
/// (peak missed by at most 1 − cos(π/100) = 0.05 %); the peak is taken over the record's
/// duration (no free-vibration tail).
///
/// Units: T in s, ζ dimensionless, accelerations in g, u in g·s².

#include "structure/ground_motion.h"

namespace structure {

/// Peak response of the SDOF oscillator to a record.
struct SdofPeak {
  double peak_disp_g_s2 = 0.0;      ///< max |u|, g·s² (× 386.09 for inches)
  double pseudo_accel_g = 0.0;      ///< Sa = ω²·max|u|, g
  double peak_time_s = 0.0;         ///< when |u| peaked
};

/// Response of the oscillator (period_s > 0, 0 ≤ damping_ratio < 1) to `record` (its scale
/// already applied). @throws std::invalid_argument on a bad period, damping ratio or record.
SdofPeak sdof_peak_response(const GroundMotion& record, double period_s, double damping_ratio);

/// Sa(T, ζ) of `record` in g: sdof_peak_response(...).pseudo_accel_g.
double spectral_accel_g(const GroundMotion& record, double period_s, double damping_ratio = 0.05);

}  // namespace structure
