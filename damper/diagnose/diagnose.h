#pragma once
/// @file diagnose.h
/// `hybridsim diagnose` (docs/diagnose.md): finds what the BRFD model misses on measured data.
///  1. simulates the model on each measured record with the measured inputs (drum displacement,
///     actuator positions) and computes the residual force (model − measured);
///  2. localizes the residual energy in regimes (reversal, sticking, sliding, actuators moving,
///     after the excitation stops, chatter) and time windows (diagnose_data.h), with a figure;
///  3. fits each candidate effect of the library (effects.h) on the training part of the data
///     with NLopt (LN_BOBYQA, bounded, a few starts) and scores it on the held-out part:
///     held-out RMSE and ΔBIC = n_eff ln(SSE_new/SSE_old) + k ln(n_eff), where n_eff is the
///     held-out sample count divided by the residual's integrated autocorrelation time;
///  4. adds the winner if it helps materially (ΔBIC below a threshold and held-out RMSE down by
///     a minimum fraction), refits jointly, repeats (greedy forward selection), and writes the
///     updated model config (model-updated.yaml) and the before/after gap per record.
/// Base LuGre parameters come from passive data only: by default each record's passive window
/// (before the electric actuators first move), re-identified there (never on actuated or
/// held-out samples) whenever effects change; or the --model file as is (BaseSource::model).

#include "damper/data/brfd_data.h"
#include "damper/model/brfd_model.h"
#include "damper/diagnose/diagnose_data.h"
#include "damper/fit/identification.h"
#include "damper/data/replay.h"

#include <functional>
#include <string>
#include <vector>

namespace damper {

/// Where the base model's LuGre parameters come from.
enum class BaseSource {
  identify,  ///< identified on each record's passive window (default, as `damper predict`)
  model,     ///< the --model file's parameters as they are (x'_k still from each record's t = 0)
};

/// Options of run_diagnose() (the CLI flags of `hybridsim diagnose`).
struct DiagnoseOptions {
  std::string model_path;                ///< --model: damper config YAML (may already hold effects)
  std::vector<std::string> measured;     ///< --measured: files or folders (diagnose_data.h)
  std::string out_dir;                   ///< --out ("" = write nothing)
  BaseSource base = BaseSource::identify;
  std::vector<std::string> candidates;   ///< --effects: subset of the library (empty = all)
  SegmentationOptions segmentation;
  /// The actuator position signals of the semi-active files are sample-and-hold staircases
  /// (updated every 10-20 ms); they are smoothed by a centred moving average over this window
  /// before use, s (0: as measured).
  double actuator_smoothing_s = 0.02;
  /// Budget of the first identification of the base on each passive window (window overwritten).
  IdentificationOptions base_identification;
  /// Local LN_BOBYQA re-identification of each record's base with the trial effects, run at every
  /// trial of an effect fit that changes the passive window (identify).
  int base_refit_evals = 150;
  int effect_evals = 80;                 ///< LN_BOBYQA evaluations per start of an effect fit
  int polish_evals = 120;                ///< joint refit of all selected effects after a selection
  /// Effect fits and scores run on records decimated to at least this rate (every k-th sample),
  /// Hz; the before/after numbers use the full rate.
  double fit_rate_hz = 256.0;
  double min_improvement = 0.03;         ///< held-out RMSE must fall by at least this fraction
  double bic_threshold = -2.0;           ///< ... and ΔBIC must be at most this
  int max_effects = 7;                   ///< at most this many effects are added
  bool figures = true;                   ///< run gnuplot (needs out_dir)
  BrfdReadOptions read;
  std::function<void(const std::string&)> log;  ///< report lines (may be empty)
};

/// Fit and score of one candidate in one round of the selection.
struct CandidateScore {
  int round = 0;
  std::string effect;
  std::vector<std::string> parameter_names;
  std::vector<double> theta;
  double train_rmse_kip = 0.0, heldout_rmse_kip = 0.0;
  double heldout_gain = 0.0;  ///< 1 − held-out RMSE / current held-out RMSE
  double delta_bic = 0.0;
  RegimeEnergy heldout_energy;  ///< residual energy per regime on held-out samples with it
  bool accepted = false;
  int evaluations = 0;
};

/// One measured record in the report.
struct RecordReport {
  std::string name, path;
  double dt_s = 0.0;
  double passive_end_s = 0.0;
  double train_s = 0.0, heldout_s = 0.0;
  BrfdParams base_params;   ///< base before any effect (passive data)
  BrfdParams final_params;  ///< base (re-identified on passive data) + effects
  ErrorMetrics before, after;                  ///< whole record
  ErrorMetrics before_heldout, after_heldout;  ///< held-out samples only
  ErrorMetrics updated_config;                 ///< model-updated.yaml as written, whole record
  RegimeEnergy energy_before, energy_after;
  std::vector<double> time_s, disp_in, vel_in_per_s, act1_in, act2_in, measured_kip, model_before_kip,
      model_after_kip;
  Segmentation segmentation;
  std::string csv_path, png_path;
};

/// Everything run_diagnose() found.
struct DiagnoseResult {
  std::vector<RecordReport> records;
  std::vector<CandidateScore> candidates;  ///< all rounds
  ModelEffects initial_effects;            ///< effects already in the --model file
  ModelEffects effects;                    ///< effects of the updated model
  std::vector<std::string> added;          ///< effects added by this run, in order
  std::string stop_reason;
  double effective_samples = 0.0;          ///< n_eff of the first round
  double nrmse_before_mean = 0.0, nrmse_after_mean = 0.0, nrmse_after_max = 0.0;
  BrfdParams updated_params;               ///< what model-updated.yaml holds
  std::string updated_config_path, report_path, gap_png_path;
  std::vector<ResidualWindow> top_windows; ///< where the residual concentrates (before)
};

/// Runs the workflow. Throws BrfdDataError / common::ConfigError / std::invalid_argument on bad
/// input, std::runtime_error if files cannot be written.
DiagnoseResult run_diagnose(const DiagnoseOptions& options);

/// The command's last line:
/// "effects=<comma-separated names, or none> nrmse_before=<mean> nrmse_after=<mean> nrmse_after_max=<max>"
/// (effects of the updated model; NRMSE = RMSE / std of the measured force, whole records).
std::string diagnose_final_line(const DiagnoseResult& result);

/// Error metrics over the samples with mask[i] == want (RMSE, RMSE/std, RMSE/range).
ErrorMetrics masked_error(const std::vector<double>& measured, const std::vector<double>& predicted,
                          const std::vector<std::uint8_t>& mask, std::uint8_t want);

/// Effective number of independent samples of a residual: n / (1 + 2 Σ ρ_k), the sum of its
/// autocorrelation up to the first non-positive lag.
double effective_sample_count(const std::vector<double>& residual);

}  // namespace damper
