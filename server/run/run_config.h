#pragma once
/// @file run_config.h
/// The hybrid-run config (configs/three-story.yaml, configs/ten-story.yaml): plain structs
/// with defaults and one strict loader. Units: kip, in, s. Relative paths in a config are
/// relative to the config file's folder.

#include "control/controller.h"
#include "damper/model/brfd_model.h"
#include "damper/physical/physical_config.h"
#include "structure/shear_building.h"

#include "structure/integrator.h"

#include <map>
#include <string>

namespace server {

/// Most steps one run may take: 10^9 (11.3 days of simulated time at 1024 Hz). The step loop
/// itself needs no memory per step (rows are streamed to disk).
constexpr long kMaxRunSteps = 1'000'000'000;

/// Which ground motion and how much of it.
struct RecordSettings {
  std::string path;          ///< PEER AT2 or two-column (time s, accel g) file
  double scale = 1.0;        ///< multiplies the record's accelerations (g)
  /// Simulated duration, s: > 0 and at most the record's duration; < 0 means the whole
  /// record; 0 is refused (a run of no step).
  double duration_s = -1.0;
  /// How the record reaches the run's step: "linear" (default) interpolates linearly between
  /// samples at any dt_s; "exact" additionally requires the record's step to be a whole number
  /// of run steps, so every record sample is a step time (nothing between samples is lost).
  std::string resample = "linear";
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
  /// A malformed, foreign-run, forged (bad HMAC), replayed or unbound message on the link:
  /// "drop" (counted in summary.json bad_messages, said once per kind, the run goes on) or
  /// "stop" (the run fails naming the first one). README "Reliability".
  std::string on_bad_message = "drop";
  /// HMAC key file of the run (messages/run_key.h; 64 hex characters, mode 0600). Empty: a
  /// fresh key per run in <results>/run.key. Required with damper.launch external (the
  /// substructure started by hand must hold the same key); a physical run's rig.key_file is
  /// the run's key when given.
  std::string key_file;
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
  std::string name = "run";          ///< letters, digits, '.', '_', '-' (part of the run id)
  double dt_s = 1.0 / 1024.0;        ///< integration (and substructure) time step, <= the record's DT
  /// `run.integrator` (cr | kr_alpha) and `run.rho_inf` (kr_alpha only), structure/integrator.h.
  structure::IntegratorSettings integrator;
  /// Physics check after the run: |input − stored − dissipated| / |input| above this makes
  /// the status "failed". The run's centred-difference ledger closes to round-off for every
  /// integrator (structure/energy.h: 1.6e-15 over 30 s of El Centro), so anything above 1e-6
  /// means overflow or cancellation from implausible values (a 1e300 kip force), not physics.
  double max_energy_balance_error = 1e-6;
  RecordSettings record;
  structure::BuildingParams building;
  /// The `damper:` block may be left out when the building has no dampers; then
  /// has_damper_block is false and damper_model keeps its defaults (never used).
  DamperSettings damper;
  bool has_damper_block = true;
  damper::BrfdParams damper_model;   ///< loaded from damper.model_config
  /// `rig:` block, used when damper.mode is physical (docs/physical.md); optional, defaults
  /// = a local brfd-rig with rig-default.yaml beside the run config.
  damper::physical::PhysicalSettings rig;
  TransportSettings transport;
  OutputSettings output;
  /// `control:` block (control/controller.h): the semi-active law driving the electric
  /// actuators. Absent: control.enabled is false and the actuators hold x' (passive run).
  control::ControlConfig control;
  /// "file:line" of keys checked after loading (against the record, the disk), by key path.
  std::map<std::string, std::string> key_location;
  /// "file:line: key: " prefix for a message about `key` (just the file if unknown).
  std::string at(const std::string& key) const;
  /// Set by the caller once the record is read (describe_resampling().text): written as a
  /// comment under record: in the effective config.
  std::string resampling_note;
};

/// Loads and validates a run config; throws common::ConfigError naming file, line and key.
RunConfig load_run_config(const std::string& path);

/// The record-dependent limits, checked before a run starts (and again by the step loop):
/// record.duration_s != 0 and not longer than the record; run.dt_s not larger than the
/// record's DT (the loop would skip samples); steps <= kMaxRunSteps; the time history and LCM
/// log fit on the output folder's disk. Throws common::ConfigError naming file, line and key.
/// @return the number of steps of the run.
long check_run_against_record(const RunConfig& config, double record_dt_s, double record_duration_s,
                              const std::string& record_source);

/// The effective config (every value used, defaults filled in) as YAML.
std::string run_config_to_yaml(const RunConfig& config);

/// How the record's samples reach the run's steps, stated in summaries and the effective
/// config: the record's own step, the run's step and the interpolation.
struct ResampleDescription {
  double record_dt_s = 0.0;
  double run_dt_s = 0.0;
  std::string mode;           ///< "linear" or "exact" (record.resample)
  long steps_per_sample = 0;  ///< run steps per record sample when whole, else 0
  std::string text;           ///< one line, e.g. "record step 0.01 s, run step 0.0009765625 s: linear interpolation; ..."
};
ResampleDescription describe_resampling(double record_dt_s, double run_dt_s, const std::string& mode);

/// record.resample exact: throws common::ConfigError naming the config file, record.resample
/// and both steps unless the record's step is a whole number of run steps.
void check_resampling(const RunConfig& config, double record_dt_s);

}  // namespace server
