#pragma once
/// @file predict.h
/// `hybridsim damper predict`: replays the measured drum displacement and actuator positions
/// of a test through the BRFD model, after identifying the LuGre parameters and b on PASSIVE
/// data of the same test (the drum cycles before the electric actuators first move), and
/// reports the error. Writes the predicted force as CSV and a gnuplot PNG figure.

#include "damper/data/brfd_data.h"
#include "damper/model/brfd_model.h"
#include "damper/fit/identification.h"
#include "damper/data/replay.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace damper {

/// Options of run_predict() (the CLI flags of `hybridsim damper predict`).
struct PredictOptions {
  std::string config_path;  ///< damper config (configs/brfd-semiactive.yaml); empty: built-in defaults
  std::string test_path;    ///< measured test, JSON (see brfd_data.h)
  bool fit = true;          ///< false (--no-fit): use the config's parameters as they are
  /// --fit-window T0:T1 (s). Unset: [start of test, first actuator motion).
  std::optional<std::pair<double, double>> fit_window_s;
  /// An actuator "moves" when it departs from its t = 0 position by more than this (in). The
  /// position signals' noise is ~1e-4 in at rest.
  double actuator_motion_threshold_in = 0.002;
  /// Take x'_1, x'_2 of Eq. (4) from the test's first row (the data's convention) rather than
  /// from the config.
  bool initial_positions_from_test = true;
  std::string out_dir;      ///< empty: no files written
  bool figure = true;       ///< run gnuplot to make the PNG (needs out_dir)
  IdentificationOptions identification;  ///< window fields are overwritten by the above
  BrfdReadOptions read;
  std::function<void(const std::string&)> log;  ///< progress lines; may be empty
};

/// Result of run_predict().
struct PredictResult {
  std::string test_name;
  BrfdParams params;                ///< parameters used for the prediction (effective config)
  bool fitted = false;
  IdentificationResult identification;  ///< valid when fitted
  double fit_t0_s = 0.0, fit_t1_s = 0.0;
  std::optional<double> first_actuator_motion_s;  ///< unset: actuators never move (or no columns)
  std::vector<double> time_s, measured_kip, predicted_kip;
  ErrorMetrics metrics;             ///< whole test, fit window included
  ErrorMetrics metrics_after_fit;   ///< samples after the fit window (the actuated part)
  std::string csv_path, png_path, config_out_path;
  std::string figure_warning;       ///< set if gnuplot failed; the CSV is still written
};

/// First time (s) at which an actuator position departs from its t = 0 value by more than
/// threshold_in; unset when the file has no actuator positions or they never move.
std::optional<double> first_actuator_motion_s(const BrfdTest& test, double threshold_in);

/// Runs the whole predict command. Throws BrfdDataError / common::ConfigError /
/// std::invalid_argument on bad input, std::runtime_error if files cannot be written.
PredictResult run_predict(const PredictOptions& options);

/// The command's last line: "nrmse=<RMSE/std> rmse_kip=<RMSE> nrmse_range=<RMSE/(max-min)>".
std::string metrics_line(const ErrorMetrics& metrics);

/// Writes a PNG with gnuplot (run as a program): measured vs predicted force over time with the
/// fit window marked, force-displacement loops, and actuator positions. Returns "" on success,
/// else a warning naming the failure.
std::string plot_prediction(const std::string& csv_path, const std::string& png_path,
                            const std::string& title, double fit_t0_s, double fit_t1_s,
                            bool has_actuator_positions);

}  // namespace damper
