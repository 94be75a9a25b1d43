#pragma once
/// @file batch_set.h
/// A batch's record set with its manifest (OUT/batch.json), the folders of its runs, and the
/// result of one run as the summary sees it (finished, failed, not run).

#include "server/batch/batch.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace server::batch_internal {

struct BatchSet {
  std::string config;                 // absolute
  std::string records_spec;           // absolute
  std::string name;                   // config run name
  int stories = 0;
  int dampers = 0;
  double duration_s = 0.0;            // simulated per run (< 0: whole records)
  std::vector<BatchRecord> records;
};

nlohmann::json manifest_json(const BatchSet& b);
BatchSet manifest_from_json(const nlohmann::json& j);

/// OUT/runs, OUT/runs/<label> (finished), OUT/runs/<label>.partial (running or interrupted).
std::filesystem::path runs_dir(const std::string& out);
std::filesystem::path final_dir(const std::string& out, const std::string& label);
std::filesystem::path partial_dir(const std::string& out, const std::string& label);

/// The result of one record as the summary sees it.
struct RunResult {
  std::string state = "not_run";   // "ok", "failed", "not_run"
  bool finished = false;           // in runs/<label>/ (final)
  nlohmann::json summary;                    // summary.json (null if none)
};

/// Reads the result of `label`: the finished folder, else a .partial folder holding a failed
/// summary (machinery failure of this session), else not run.
RunResult read_result(const std::string& out, const std::string& label);

/// Loads and checks the config and the record set. Throws BatchInputError (or the config's
/// common::ConfigError).
BatchSet prepare_set(const BatchOptions& o);

/// True if `summary_path` holds a JSON object with a "status": a finished run. A 0-byte or
/// half-written summary (a disk that filled before atomic writes) is not; `why` says why.
bool readable_summary(const std::filesystem::path& summary_path, std::string* why);

/// Stops with an error if runs/<label>/ holds a different record or scale than the set says
/// (e.g. the list file changed a scale but kept the label): resuming would mix results.
void check_finished_matches(const std::string& out, const BatchRecord& r, double duration_s);

}  // namespace server::batch_internal
