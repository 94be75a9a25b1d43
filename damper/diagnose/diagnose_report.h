#pragma once
/// @file diagnose_report.h
/// Tables, files and figures of `hybridsim diagnose` (damper/diagnose/diagnose.h): report lines, CSVs,
/// the updated model config and the gnuplot PNGs (gnuplot is run as a program).

#include "damper/diagnose/diagnose_types.h"

#include <functional>
#include <string>
#include <vector>

namespace damper {

/// Residual energy per regime (all records, and per record), before any effect is added.
std::vector<std::string> format_regime_table(const std::vector<RecordReport>& records, const RegimeEnergy& all);
/// The time windows holding the most residual energy.
std::vector<std::string> format_windows(const std::vector<ResidualWindow>& windows, double total_energy);
/// One round of candidates: effect, params, train/held-out RMSE, held-out change, ΔBIC, verdict.
std::vector<std::string> format_candidate_table(const std::vector<CandidateScore>& scores);
/// The round's winner, its parameters and the evidence (held-out gain, parts, signature, confidence).
std::string format_evidence(const CandidateScore& winner);
/// NRMSE and RMSE before/after per record (whole record and held-out samples).
std::vector<std::string> format_gap_table(const std::vector<RecordReport>& records, bool identify);
/// Residual energy per regime before and after, all records.
std::vector<std::string> format_regime_shift(const RegimeEnergy& before, const RegimeEnergy& after);

/// Writes model-updated.yaml, report.txt, candidates.csv, regimes.csv, gap.csv, windows.csv,
/// records/<name>.csv + _model.yaml (+ .png/.gp with figures), gap.png; logs what it wrote.
/// Sets the paths in `result`. Throws std::runtime_error if a file cannot be written.
void write_outputs(const DiagnoseOptions& options, DiagnoseResult& result, std::vector<std::string>& lines,
                   const std::function<void(const std::string&)>& log);

/// The line before the last: "confidence: <effect>=<share of resamples> ..." (or
/// "confidence: none (<why nothing is named>)").
std::string diagnose_confidence_line(const DiagnoseResult& result);

/// The command's last line:
/// "effects=<comma-separated names, or none> nrmse_before=<mean> nrmse_after=<mean> nrmse_after_max=<max>"
/// (effects added by this run; NRMSE = RMSE / std of the measured force, whole records).
std::string diagnose_final_line(const DiagnoseResult& result);

/// gnuplot colour of a regime (e.g. "#ff7f0e").
std::string regime_color(Regime r);

}  // namespace damper
