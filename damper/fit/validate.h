#pragma once
/// @file validate.h
/// `hybridsim damper validate --config FILE`: one table, model x test, of how well each damper
/// model predicts measured BRFD tests it was NOT fitted on (configs/brfd-validate.yaml):
///  (a) semi-active tests: each model identified on the test's drum cycles before its electric
///      actuators first move (passive data), then predicts the whole test (RMSE/std, the
///      paper's Table 4 measure);
///  (b) earthquake tests: models identified on characterization tests only; NRMSE(range) and
///      RMSE/std over the whole test and its strong-motion window;
///  (c) characterization tests not used in identification (other frequency, amplitude,
///      pre-tension; a pre-tension other than the identification's scales the slack tensions);
///  (d) the actuator load-cell forces for the band-brake model, which predicts them.
/// Models: `paper_semiactive` (LuGre Eqs. 1-3 + Eq. 4, identified with identify_lugre on one
/// window: the standard LuGre baseline) and `band_brake` (damper/model/band_brake_model.h,
/// identified jointly over several windows). A PNG per test (force history and loops).

#include "damper/fit/band_brake_fit.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace damper {

/// A test of the validation set.
struct ValidationTest {
  std::string file;           ///< path of the JSON file (resolved)
  std::string group;          ///< "semiactive", "earthquake", "characterization"
  std::optional<std::pair<std::size_t, std::size_t>> window;  ///< strong-motion samples [b, e)
  double pretension_scale = 1.0;  ///< slack tensions x this (characterization at another pre-tension)
};

/// Parsed configs/brfd-validate.yaml.
struct ValidationConfig {
  std::vector<std::string> identification_files;  ///< band brake: characterization tests (joint)
  std::vector<double> identification_scales;      ///< pre-tension scale of each
  std::string lugre_identification_file;          ///< paper model: one characterization test
  std::vector<ValidationTest> tests;
  BandBrakeParams band_brake_start;
  BandBrakeFitOptions band_brake_fit;
  int lugre_global_max_evals = 3000, lugre_global_runs = 2, lugre_local_max_evals = 2000;
  std::string out_dir;              ///< CSV/PNG/identified configs; empty: none written
  bool figures = true;
};

/// Reads the validation config; paths in it are relative to the config file. Throws
/// common::ConfigError naming file and key.
ValidationConfig load_validation_config(const std::string& path);

/// One row of the table.
struct ValidationRow {
  std::string group, test, model, span;  ///< span: "whole" or "window b-e"
  ErrorMetrics force;
  bool has_cells = false;
  double cell1_rmse_lb = 0.0, cell2_rmse_lb = 0.0, cells_nrmse_std = 0.0;  ///< (d)
};

struct ValidationResult {
  std::vector<ValidationRow> rows;
  BandBrakeParams band_brake_characterization;  ///< identified on the characterization set
  std::vector<std::string> png_paths;
  std::vector<std::string> warnings;
};

/// Runs the whole validation. `log` gets progress lines.
ValidationResult run_validation(const ValidationConfig& config,
                                const std::function<void(const std::string&)>& log = {});

/// The table as text (one line per row, aligned) followed by the target lines.
std::string format_validation_table(const ValidationResult& result);

/// Eq. (4) gains (kip/in; fwd-x1, fwd-x2, bwd-x1, bwd-x2) of the paper's Tables 1-2.
std::array<double, 4> paper_eq4_gains_kip_per_in();

}  // namespace damper
