#pragma once
/// @file diagnose_types.h
/// Options and results of `hybridsim diagnose` (docs/diagnose.md), shared by the workflow
/// (diagnose.h), its fit/selection engine (diagnose_fit.h, diagnose_select.h) and its report
/// (diagnose_report.h). Holding them here keeps the report from including the workflow.

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
  std::vector<BrfdTest> measured_tests;  ///< records in memory (benchmark, tests), after `measured`
  std::string out_dir;                   ///< --out ("" = write nothing)
  BaseSource base = BaseSource::identify;
  std::vector<std::string> candidates;   ///< --effects: subset of the library (empty = all)
  SegmentationOptions segmentation;
  /// Centred moving average over the actuator position signals before use, s. 0 (default): as
  /// measured, exactly what `damper predict` replays, so the written model reproduces "after".
  double actuator_smoothing_s = 0.0;
  /// Budget of the identification of each record's base on its passive window, for "before" and
  /// "after" (window overwritten). The defaults are `damper predict`'s.
  IdentificationOptions base_identification;
  /// LN_BOBYQA evaluations of each base re-identification step inside a fit (identify mode). The
  /// model without a candidate gets exactly the same base steps as the model with it.
  int base_refit_evals = 100;
  int effect_evals = 60;                 ///< LN_BOBYQA evaluations per start of an effect fit
  int fit_iterations = 2;                ///< alternations effect step / base step per fit
  /// Effect fits and scores run on records decimated to at least this rate (every k-th sample),
  /// Hz; 0 (the default): the records' own rate, nothing decimated. Decimating leaves a structured
  /// discretization residual that flexible families fit (docs/diagnose.md, "Fits at the record
  /// rate"); the before/after numbers always use the full rate.
  double fit_rate_hz = 0.0;
  /// A candidate must remove at least this share of the held-out mean square residual of the
  /// refitted model without it ...
  double min_improvement = 0.05;
  /// ... and at least this share of its excess over the noise floor (σ²) ...
  double min_excess_share = 0.1;
  /// ... improve at least this share of the held-out parts it changes (records / cycles) ...
  double consistency = 0.8;
  /// ... take at least this share of its held-out gain in its own regimes (physics signature),
  /// or concentrate it there: a gain per held-out sample in its own regimes at least
  /// signature_density times the gain per sample elsewhere. The refitted model without the effect
  /// bends its base to take part of the effect in sliding, so adding the effect also gains there:
  /// a right backlash on a twelfth-set record removed 95 % of the excess with 47 % of its gain in
  /// the 34 % of the samples that are its regimes (density 1.7), a wrong one 21 % in 27 % (0.7) ...
  /// (and the floor keeps a rare regime from passing on a sliver: at most twice the gain elsewhere)
  double signature_share = 0.5;
  double signature_density = 1.5;
  double signature_share_floor = 1.0 / 3.0;
  /// ... unless it explains the whole discrepancy: a held-out mean square within
  /// signature_waiver_floor σ² where the model without it is at least signature_waiver_excess σ².
  /// Where the effect also sits in a record's passive window, the base identified there has
  /// absorbed it and errs everywhere; where that base errs (sliding, rest) is then no sign of the
  /// effect's physics, and adding the effect (the base re-identified with it) gains there most
  /// (blind set 30 t17: a load-dependent slack, the model without it at 0.345 kip RMS for a noise
  /// of 0.0275, backlash at 0.0262 with 10 % of its gain at reversals, named transition_shape at
  /// 0.0894). A family that leaves nothing but noise has no residual left for another one.
  /// Or it leaves at most signature_waiver_near_floor σ² having removed at least
  /// signature_waiver_share of the excess: a close shape of the right family, not the author's own
  /// (twenty-seventh session: set 38 t05, a dead zone re-engaging as a Hertz contact, backlash
  /// 0.459 → 0.0463 kip at a noise of 0.0294, 2.5 σ², 99 % of the excess with 24 % of its gain at the
  /// reversals; set 37 t19, an Andrade creep at rest, residual_static 0.518 → 0.0688, 2.3 σ², 99 %,
  /// 44 % at rest: both records' bases identified on passive windows that held the effect). A wrong
  /// family that only mimics leaves more (set 30 t17's transition_shape: 10.6 σ²).
  double signature_waiver_floor = 1.2;
  double signature_waiver_near_floor = 3.0;
  double signature_waiver_share = 0.9;
  double signature_waiver_excess = 4.0;
  /// ... take at most this share of its held-out gain from the change of the force at the final
  /// rest when it does not act at rest (every effect but residual_static, and those acting through
  /// the actuators where they move): with the drum and the actuators still, a law of the moving
  /// drum leaves the held force as it is, so a gain there is another effect mimicked (blind set
  /// 17 t07: a rate-and-state law whose capacity fell at the noise speed of the rest let the held
  /// force creep, took 41 % of its gain there and was named velocity for a creep at rest) ...
  double max_rest_share = 0.25;
  /// ... and be chosen in at least this share of bootstrap resamples of the held-out parts.
  double confidence = 0.8;
  /// The winner is NAMED only when it explains most of what is missing: at least this share of
  /// the held-out excess over the noise floor. A family that passes every gate but leaves more
  /// than 40 % of the excess is a partial surrogate of an effect outside the library (a speed law
  /// fitted to a band stiffness that differs by direction takes 21-30 % of it): reported as
  /// "something is missing that no library effect explains", not named (docs/diagnose.md, step 7).
  double min_explained_share = 0.6;
  int resamples = 200;                   ///< bootstrap resamples per round
  /// Threads for the fits of one round (the candidates x folds are independent; the verdict does
  /// not depend on the count). 0: the machine's hardware threads.
  int threads = 0;
  unsigned seed = 7;                     ///< bootstrap seed (reproducible verdicts)
  int max_effects = 4;                   ///< at most this many effects are added
  bool figures = true;                   ///< run gnuplot (needs out_dir)
  BrfdReadOptions read;
  std::function<void(const std::string&)> log;  ///< report lines (may be empty)
};

/// Fit and score of one candidate in one round of the selection.
struct CandidateScore {
  int round = 0;
  std::string effect;
  std::vector<std::string> parameter_names;
  std::vector<double> theta;                 ///< fitted on all fitting data of the round
  double heldout_rmse_null_kip = 0.0;        ///< refitted model without the candidate, held-out parts
  double heldout_rmse_kip = 0.0;             ///< with the candidate, held-out parts
  double heldout_gain = 0.0;                 ///< share of the held-out mean square removed (vs the null refit)
  double excess_share = 0.0;                 ///< share of the held-out excess over σ² removed
  int parts_total = 0, parts_changed = 0, parts_improved = 0;
  double signature_share = 0.0;              ///< share of the held-out gain in its own regimes
  double own_time_share = 0.0;               ///< share of the held-out samples in its own regimes
  double own_residual_share = 0.0;           ///< share of the null model's held-out residual there
  double rest_share = 0.0;                   ///< share of the held-out gain from the change at the final rest (effects not acting there)
  /// The regime gate waived on all held-out parts (DiagnoseOptions::signature_waiver_*): kept in
  /// every bootstrap resample.
  bool whole_explanation = false;
  double confidence = 0.0;                   ///< share of bootstrap resamples choosing it
  std::vector<double> part_gain_kip2;        ///< per held-out part: SSE(null) − SSE(candidate), kip²
  std::vector<double> part_null_kip2;        ///< per held-out part: SSE(null), kip²
  std::vector<std::size_t> part_samples;
  std::vector<double> part_noise_kip2;       ///< per part: noise sd of the gain, 2 σ √Σ(Δprediction)², kip²
  RegimeEnergy heldout_energy;               ///< held-out residual energy per regime with it
  bool passes = false;                       ///< passes every gate except confidence
  std::string verdict;                       ///< why it passes / fails, one phrase
  bool accepted = false;
  int evaluations = 0;
  /// The sub-family scored when the data identify only part of the family (EffectSpec::subfamily,
  /// e.g. "ratio free; relaxed_share=1 offset_kip=0 fixed"); empty: the whole family.
  std::string subfamily;
  /// Parameters held at a fixed value by the sub-family (not searched, so never "at a bound").
  std::vector<std::string> fixed_parameters;
};

/// Noise floor and residual structure of a model's residual (diagnose_noise.h).
struct NoiseReport {
  double sigma_kip = 0.0;        ///< measurement-noise estimate (high-frequency residual, MAD)
  double mse_kip2 = 0.0;         ///< mean square residual (held-out samples)
  double excess_ratio = 0.0;     ///< mse / σ²
  double lowfreq_ratio = 0.0;    ///< low-frequency residual power / what white noise at σ gives
  double lowfreq_limit = 0.0;    ///< 3-sigma limit of that ratio under white noise
  double lag_autocorrelation = 0.0;  ///< autocorrelation of the residual at the 0.1 s lag
  double autocorrelation_limit = 0.0;  ///< 3/√n
  std::vector<std::string> significant_regimes;  ///< regimes whose low-frequency residual exceeds noise
  bool structured = true;        ///< false: indistinguishable from noise
  std::string summary;           ///< one line
};

/// One measured record in the report.
struct RecordReport {
  std::string name, path;
  double dt_s = 0.0;
  double passive_end_s = 0.0;
  double train_s = 0.0, heldout_s = 0.0;
  BrfdParams base_params;   ///< base before any effect (passive data)
  BrfdParams final_params;  ///< base (re-identified on passive data with the effects) + effects
  ErrorMetrics before, after;                  ///< whole record
  ErrorMetrics before_heldout, after_heldout;  ///< held-out samples only
  ErrorMetrics updated_config;                 ///< model-updated.yaml's LuGre block as is, whole record
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
  std::vector<NoiseReport> noise;          ///< per round: the current model's residual
  ModelEffects initial_effects;            ///< effects already in the --model file
  ModelEffects effects;                    ///< effects of the updated model
  std::vector<std::string> added;          ///< effects added by this run, in order
  std::vector<double> added_confidence;    ///< bootstrap confidence of each added effect
  std::vector<std::string> notes;          ///< indistinguishable pairs, reverted additions, ...
  std::string validation;                  ///< "leave-one-record-out (N records)" or "held-out cycles"
  std::string stop_reason;
  double nrmse_before_mean = 0.0, nrmse_after_mean = 0.0, nrmse_after_max = 0.0;
  BrfdParams updated_params;               ///< what model-updated.yaml holds
  std::string updated_config_path, report_path, gap_png_path;
  std::vector<ResidualWindow> top_windows; ///< where the residual concentrates (before)
};

}  // namespace damper
