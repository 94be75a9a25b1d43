#pragma once
/// @file diagnose.h
/// `hybridsim diagnose` (docs/diagnose.md): finds what the BRFD model misses on measured data,
/// with verdicts meant to hold on data it was not tuned to.
///  1. simulates the model on each measured record with the measured inputs and localizes the
///     residual force (model − measured) in regimes and time windows (diagnose_data.h);
///  2. per round: refits the model without a new effect and with each candidate of the library
///     (effects.h) by the same procedure and budget (diagnose_fit.h), scores both on unseen data
///     (leave-one-record-out, or held-out cycles of a single record), tests the residual against
///     its noise floor (diagnose_noise.h) and adds a candidate only if it helps on (nearly) every
///     held-out part, in its own regimes, and in >= 80 % of bootstrap resamples (diagnose_select.h);
///  3. writes the updated model (model-updated.yaml) and the gap before/after per record, the
///     "after" base of each record identified exactly as `hybridsim damper predict` does.
/// Types: diagnose_types.h; report and files: diagnose_report.h.

#include "damper/diagnose/diagnose_report.h"  // diagnose_final_line(), diagnose_confidence_line()
#include "damper/diagnose/diagnose_types.h"

#include <string>

namespace damper {

/// Runs the workflow. Throws BrfdDataError / common::ConfigError / std::invalid_argument on bad
/// input, std::runtime_error if files cannot be written.
DiagnoseResult run_diagnose(const DiagnoseOptions& options);

}  // namespace damper
