#pragma once
/// @file band_brake_fit.h
/// Replay of measured BRFD tests through the band-brake model (damper/model/band_brake_model.h)
/// and its identification from PASSIVE data, jointly over several tests (characterization tests
/// and the drum cycles of semi-active tests before their electric actuators first move), with
/// NLopt: seeded bounded global searches (GN_CRS2_LM) and a local polish (LN_BOBYQA).
///
/// Cost (minimised): mean over the windows of (RMSE_F / std_F)² + w (RMSE_cells / std_cells)²,
/// the drum force and both actuator load cells (lb in the files, kip here) of each window.

#include "damper/data/brfd_data.h"
#include "damper/model/band_brake_model.h"
#include "damper/data/replay.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace damper {

/// Replayed force and load cells over [begin, end) of a test (kip).
struct BandBrakeReplay {
  std::vector<double> force_kip;
  std::vector<double> actuator1_kip, actuator2_kip;
};

/// Inputs at sample i; files without actuator positions hold x'_1, x'_2.
BandBrakeInput band_brake_input_at(const BrfdTest& test, std::size_t i, const BandBrakeParams& p);

/// Replays samples [begin, end) of `test`; the band stretch starts from the measured force at
/// `begin` (a test starts with a residual force in the bands).
BandBrakeReplay replay_band_brake(const BandBrakeParams& params, const BrfdTest& test,
                                  std::size_t begin, std::size_t end);

/// Eq. (4) gains (kip of Fc per in of actuator j, per direction: fwd-x1, fwd-x2, bwd-x1,
/// bwd-x2) converted to the slack-end tension sensitivities k_dj of (B2) at x = 0:
/// k_dj = −gain_dj / (L (E_d − 1)).
std::array<double, 4> actuator_tension_from_eq4_gains(const BandBrakeParams& p,
                                                      const std::array<double, 4>& gains_kip_per_in);

/// One identification window.
struct FitWindow {
  const BrfdTest* test = nullptr;
  std::size_t begin = 0, end = 0;
  /// Slack tensions of this window are scaled by this (a test at another band pre-tension).
  double pretension_scale = 1.0;
};

/// Bounds of the identified parameters.
struct BandBrakeBounds {
  double wrap_min_rad = 4.7, wrap_max_rad = 25.0;  ///< with μ = 0.35: E 5..1e3
  double wrap_change_max_rad_per_in = 3.0;                      ///< |κ|
  double lever_min = 1.0, lever_max = 4.0;                      ///< L
  double slack_min_kip = 0.001, slack_max_kip = 0.2;            ///< T_fwd, T_bwd
  double stiffness_min = 0.5, stiffness_max = 200.0;           ///< k_b, kip/in
  double hardening_max_per_in = 20.0;                           ///< h
  double backlash_max_in = 0.3;                                 ///< δ
  double viscous_max = 1.0;                                     ///< c, kip s/in
  double exponent_max = 8.0;                                    ///< n (min 1)
};

struct BandBrakeFitOptions {
  BandBrakeBounds bounds;
  double cell_weight = 0.3;      ///< w of the cost (0: force only)
  bool per_window_slack = false; ///< each window its own T_fwd, T_bwd (semi-active setups)
  /// Eq. (4) gains used to set k_dj after each candidate (unset: k_dj kept from the start).
  std::optional<std::array<double, 4>> eq4_gains_kip_per_in;
  int global_max_evals = 3000;
  int global_runs = 2;
  int local_max_evals = 2000;
  unsigned seed = 1;
};

struct BandBrakeFitResult {
  BandBrakeParams params;                    ///< shared parameters (first window's tensions)
  std::vector<std::array<double, 2>> slack_per_window;  ///< T_fwd, T_bwd per window
  double cost = 0.0;
  int evaluations = 0;
  std::string algorithm;
};

/// Identifies θ_fwd, θ_bwd, κ, L, T_fwd, T_bwd, k_b, h, δ, c on the windows (μ, x' and the
/// actuator terms from `start`). Throws std::invalid_argument on empty/too short windows.
BandBrakeFitResult identify_band_brake(const std::vector<FitWindow>& windows,
                                       const BandBrakeParams& start,
                                       const BandBrakeFitOptions& options);

/// One line per parameter (logs, reports).
std::string describe(const BandBrakeParams& p);

}  // namespace damper
