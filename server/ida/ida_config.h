#pragma once
/// @file ida_config.h
/// The IDA config (configs/ida-three-story.yaml): which intensity measure, the hunt-and-fill
/// budget, the drift limits of the fragility curves, and the cases compared side by side
/// (one run config each: a damper config or a control law). Strict loading: an unknown key,
/// a wrong type or an out-of-range value is a common::ConfigError naming file, line and key.
/// Units: IM in g, story height in in, drift limits in % of story height.

#include "server/ida/hunt_fill.h"

#include <string>
#include <vector>

namespace server::ida {

/// One building/damper/controller variant of the comparison.
struct IdaCase {
  std::string label;    ///< letters, digits, '_' or '-'
  std::string config;   ///< run config (absolute path)
};

struct IdaConfig {
  std::string source_file;
  std::string name = "ida";
  std::string intensity_measure = "sa_t1";  ///< "sa_t1": Sa(T1, ζ) at each case's first period; "pga"
  double damping_ratio = 0.05;              ///< ζ of Sa
  double story_height_in = 0.0;             ///< drift ratio = interstory drift / story height
  std::vector<double> drift_limits_pct;     ///< fragility limit states (peak interstory drift ratio, %)
  double collapse_drift_pct = 10.0;         ///< at or above: the run counts as collapse (flatline)
  std::string transport = "in_process";     ///< "in_process" or "lcm" (each case config's own)
  double duration_s = 0.0;                  ///< simulated per run; 0: each case config's, < 0: whole records
  HuntFillSettings hunt;
  std::vector<IdaCase> cases;
};

/// Loads and checks an IDA config (case configs are loaded too, so a bad one is named here).
IdaConfig load_ida_config(const std::string& path);

/// The effective IDA config as YAML (every value used).
std::string ida_config_to_yaml(const IdaConfig& config);

}  // namespace server::ida
