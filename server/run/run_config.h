#pragma once
/// @file run_config.h
/// The hybrid-run config (configs/three-story.yaml, configs/ten-story.yaml): plain structs
/// with defaults and one strict loader. Units: kip, in, s. Relative paths in a config are
/// relative to the config file's folder.

#include "control/controller.h"
#include "damper/model/brfd_model.h"
#include "damper/physical/physical_config.h"
#include "structure/shear_building.h"

#include <string>

namespace server {

/// Which ground motion and how much of it.
struct RecordSettings {
  std::string path;          ///< PEER AT2 or two-column (time s, accel g) file
  double scale = 1.0;        ///< multiplies the record's accelerations (g)
  double duration_s = -1.0;  ///< simulated duration; < 0 means the whole record
};

/// How the server talks to the substructure.
struct TransportSettings {
  std::string kind = "lcm";          ///< "lcm" (separate process) or "in_process"
  std::string url;                   ///< LCM URL, required for kind lcm; never defaulted in code
  bool private_netns = true;         ///< enter a private network namespace before opening LCM
  bool lab_network = false;          ///< the URL is a lab network: allow multicast outside a netns
  std::string channel_prefix = "BRFD_";
  double step_timeout_s = 1.0;       ///< max wait for one force feedback
  double start_timeout_s = 10.0;     ///< max wait for the substructure's first heartbeat
  bool write_lcm_log = true;         ///< write the run's traffic as an LCM log (lcm-logplayer)
};

/// Which substructure answers and how it is started.
struct DamperSettings {
  std::string mode = "virtual";      ///< "virtual" (BRFD model) or "physical" (rig / lab)
  std::string model_config;          ///< damper model YAML file, e.g. brfd-default.yaml (or inline `model:`)
  std::string launch = "spawn";      ///< "spawn" the substructure process, or "external" (already running)
  std::string executable = "brfd-substructure";  ///< found beside hybridsim unless a path is given
};

struct OutputSettings {
  std::string dir = "results";       ///< results folder (created)
  int flush_every_steps = 1024;      ///< time-history rows are flushed at least this often
  int every_n_steps = 1;             ///< time-history row every n steps (peaks use every step)
  /// "csv" (time_history.csv, shortest round-trip text) or "hdf5" (time_history.h5, one
  /// float64 dataset per column with units and the effective config as attributes;
  /// hdf5_time_history.h). Same doubles either way.
  std::string format = "csv";
};

struct RunConfig {
  std::string source_file;           ///< the YAML file this came from
  std::string name = "run";
  double dt_s = 1.0 / 1024.0;        ///< integration (and substructure) time step
  RecordSettings record;
  structure::BuildingParams building;
  DamperSettings damper;
  damper::BrfdParams damper_model;   ///< loaded from damper.model_config
  /// `rig:` block, used when damper.mode is physical (docs/physical.md); optional, defaults
  /// = a local brfd-rig with rig-default.yaml beside the run config.
  damper::physical::PhysicalSettings rig;
  TransportSettings transport;
  OutputSettings output;
  /// `control:` block (control/controller.h): the semi-active law driving the electric
  /// actuators. Absent: control.enabled is false and the actuators hold x' (passive run).
  control::ControlConfig control;
};

/// Loads and validates a run config; throws common::ConfigError naming file, line and key.
RunConfig load_run_config(const std::string& path);

/// The effective config (every value used, defaults filled in) as YAML.
std::string run_config_to_yaml(const RunConfig& config);

}  // namespace server
