#pragma once
/// @file replay.h
/// Replays a measured BRFD test through the model (drum displacement/velocity and actuator
/// positions as measured) and compares predicted with measured force.

#include "damper/data/brfd_data.h"
#include "damper/model/brfd_model.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace damper {

/// Model input at sample i of a test. Files without actuator positions (characterization:
/// actuators hold) get the config's initial positions x'_1, x'_2, so Eq. (4) reduces to b.
DamperInput input_at(const BrfdTest& test, std::size_t i, const BrfdParams& params);
/// The same with the actuator positions x'_1, x'_2 (in) given (the band-brake model's).
DamperInput input_at(const BrfdTest& test, std::size_t i, double actuator1_initial_in, double actuator2_initial_in);

/// Options of replay_force_kip().
struct ReplayOptions {
  /// Start the bristle state from the measured force at the first sample, z0 = F0/σ0 (clamped
  /// to the steady deflection max(Fs)/σ0): the test starts with a residual force in the bands
  /// that a zero bristle state would miss. False: z0 = 0.
  bool initial_bristle_from_force = true;
};

/// Predicted force (kip) at samples [begin, end) of `test`: the bristle state starts at sample
/// `begin` and is advanced with BrfdModel::step() over each sample period.
std::vector<double> replay_force_kip(const BrfdParams& params, const BrfdTest& test,
                                     std::size_t begin, std::size_t end,
                                     const ReplayOptions& options = {});

/// Error of a prediction against the measured force over [begin, end).
struct ErrorMetrics {
  double rmse_kip = 0.0;
  double nrmse_std = 0.0;    ///< RMSE / standard deviation of the measured force
  double nrmse_range = 0.0;  ///< RMSE / (max - min) of the measured force
  std::size_t samples = 0;
};
/// `predicted` is indexed like `measured` (same length). Requires begin < end <= size.
ErrorMetrics force_error(const std::vector<double>& measured, const std::vector<double>& predicted,
                         std::size_t begin, std::size_t end);
/// The same over the samples with mask[i] == want (all zero when there is none).
ErrorMetrics masked_error(const std::vector<double>& measured, const std::vector<double>& predicted,
                          const std::vector<std::uint8_t>& mask, std::uint8_t want);

/// Sample index of time t (s) in the test, clamped to [0, size].
std::size_t index_at_time(const BrfdTest& test, double t_s);

}  // namespace damper
