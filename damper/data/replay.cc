#include "damper/data/replay.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace damper {

DamperInput input_at(const BrfdTest& test, std::size_t i, double actuator1_initial_in, double actuator2_initial_in) {
  DamperInput in;
  in.drum_disp_in = test.drum_disp_in[i];
  in.drum_vel_in_per_s = test.drum_vel_in_per_s[i];
  in.actuator1_in = test.has_actuator_positions ? test.actuator1_in[i] : actuator1_initial_in;
  in.actuator2_in = test.has_actuator_positions ? test.actuator2_in[i] : actuator2_initial_in;
  return in;
}

DamperInput input_at(const BrfdTest& test, std::size_t i, const BrfdParams& params) {
  return input_at(test, i, params.semiactive.actuator1_initial_in, params.semiactive.actuator2_initial_in);
}

std::vector<double> replay_force_kip(const BrfdParams& params, const BrfdTest& test,
                                     std::size_t begin, std::size_t end,
                                     const ReplayOptions& options) {
  assert(begin < end && end <= test.size());
  if (params.kind == DamperKind::band_brake) {
    // The band-brake model: stretch state from the measured force at `begin` (clipped to Fc).
    BandBrakeModel band(params.band_brake);
    const DamperInput in0 = input_at(test, begin, params);
    if (options.initial_bristle_from_force) {
      const BandTensions t = band.tensions(in0);
      band.set_stretch_in(band.stretch_for_force(std::clamp(test.force_kip[begin], -t.fc_bwd_kip, t.fc_fwd_kip)));
    }
    std::vector<double> f(end - begin);
    f[0] = band.force_kip(band.stretch_in(), in0);
    for (std::size_t i = begin + 1; i < end; ++i) f[i - begin] = band.step(input_at(test, i, params), test.dt_s);
    return f;
  }
  BrfdModel model(params);
  const LugreParams& g = params.lugre;
  if (options.initial_bristle_from_force) {
    // z0 with spring force F0 (= F0/σ0 without effects; backlash and asymmetry change the spring).
    const double f_max = std::max(g.fs_fwd_kip, g.fs_bwd_kip);
    model.set_bristle_in(model.initial_bristle_for_force(std::clamp(test.force_kip[begin], -f_max, f_max)));
  }
  model.set_drum_start_in(test.drum_disp_in[0]);  // the bands were tensioned where the record starts
  std::vector<double> f(end - begin);
  f[0] = model.force_kip(model.bristle_in(), input_at(test, begin, params));
  for (std::size_t i = begin + 1; i < end; ++i)
    f[i - begin] = model.step(input_at(test, i, params), test.dt_s);
  return f;
}

namespace {

// RMSE, RMSE/std and RMSE/range of the measured force over the samples i with take(i).
template <typename Take>
ErrorMetrics error_over(const std::vector<double>& measured, const std::vector<double>& predicted, std::size_t begin,
                        std::size_t end, Take take) {
  ErrorMetrics m;
  double se = 0.0, sum = 0.0, sum2 = 0.0;
  double lo = INFINITY, hi = -INFINITY;
  std::size_t n = 0;
  for (std::size_t i = begin; i < end; ++i) {
    if (!take(i)) continue;
    const double e = predicted[i] - measured[i];
    se += e * e;
    sum += measured[i];
    sum2 += measured[i] * measured[i];
    lo = std::min(lo, measured[i]);
    hi = std::max(hi, measured[i]);
    ++n;
  }
  m.samples = n;
  if (n == 0) return m;
  const double nn = static_cast<double>(n);
  m.rmse_kip = std::sqrt(se / nn);
  const double mean = sum / nn;
  const double var = std::max(0.0, sum2 / nn - mean * mean);
  m.nrmse_std = var > 0.0 ? m.rmse_kip / std::sqrt(var) : INFINITY;
  m.nrmse_range = hi > lo ? m.rmse_kip / (hi - lo) : INFINITY;
  return m;
}

}  // namespace

ErrorMetrics force_error(const std::vector<double>& measured, const std::vector<double>& predicted,
                         std::size_t begin, std::size_t end) {
  assert(begin < end && end <= measured.size() && predicted.size() == measured.size());
  return error_over(measured, predicted, begin, end, [](std::size_t) { return true; });
}

ErrorMetrics masked_error(const std::vector<double>& measured, const std::vector<double>& predicted,
                          const std::vector<std::uint8_t>& mask, std::uint8_t want) {
  return error_over(measured, predicted, 0, measured.size(), [&](std::size_t i) { return mask[i] == want; });
}

std::size_t index_at_time(const BrfdTest& test, double t_s) {
  if (test.size() == 0) return 0;
  const double k = std::round((t_s - test.time_s.front()) / test.dt_s);
  if (k <= 0.0) return 0;
  return std::min(test.size(), static_cast<std::size_t>(k));
}

}  // namespace damper
