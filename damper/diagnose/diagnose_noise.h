#pragma once
/// @file diagnose_noise.h
/// Noise floor and residual-structure tests of `hybridsim diagnose` (docs/diagnose.md, "Is
/// anything missing?"). The residual r = model − measured is split, as in localize(), into its
/// low-frequency part l = MA_W(r) (centred moving average over W = chatter_window_s) and the
/// high-frequency rest h = r − l.
///  - Noise floor: σ = 1.4826 · MAD(h) / √(1 − 1/W), the robust scale of the high-frequency
///    residual (white noise of std σ gives var(h) = σ² (1 − 1/W)); model error is smooth and the
///    MAD ignores the few sharp features at reversals.
///  - Structure: white noise at σ gives E[l²] = σ²/W, with about n/W independent values, so the
///    ratio R = mean(l²) / (σ²/W) is 1 ± √(2W/n). The residual is "structured" when R exceeds
///    1 + 3√(2W/n) over all scored samples or in any regime (concentration in a regime: after a
///    reversal, while the actuators move, ...). Also reported: the autocorrelation of r at the
///    lag W (white noise: |ρ| < 3/√n).
/// "Nothing significant is missing" when no test finds structure.

#include "damper/diagnose/diagnose_types.h"

#include <cstdint>
#include <vector>

namespace damper {

/// One record's residual with the samples to test (mask[i] != 0) and its regimes.
struct ResidualSample {
  const std::vector<double>* residual = nullptr;
  const std::vector<std::uint8_t>* mask = nullptr;  ///< nullptr: all samples
  const Segmentation* seg = nullptr;
  double dt_s = 0.0;
};

/// Robust noise floor σ (kip) of one residual (all samples).
double noise_floor_kip(const std::vector<double>& residual, double dt_s, const SegmentationOptions& options);

/// Noise floor (pooled over the records: root mean of the σ²) and structure tests of the masked
/// samples (file comment).
NoiseReport residual_structure(const std::vector<ResidualSample>& records, const SegmentationOptions& options);

}  // namespace damper
