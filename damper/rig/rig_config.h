#pragma once
/// @file rig_config.h
/// Config of brfd-rig, the emulator of the BRFD lab controller (configs/rig-default.yaml).
/// It simulates a physical BRFD with effects the virtual model does not have, each switchable:
/// servo-hydraulic actuator delay and lag, load-cell/LVDT noise, backlash after each reversal,
/// residual static force after motion stops; or it replays a measured test file.
/// Strict loading: unknown keys, wrong types and out-of-range values name file, line and key.
/// Units: in, s, kip; electric actuator load cells in lb.

#include "damper/model/brfd_model.h"

#include <string>

namespace damper::rig {

/// Servo-hydraulic actuator driving the drum: pure time delay, then a first-order lag.
struct HydraulicSettings {
  bool enabled = true;               ///< false: the drum follows each command exactly
  double delay_s = 0.020;            ///< pure transport delay (fractional samples interpolated)
  double lag_time_constant_s = 0.006;///< first-order servo lag
  double gain = 1.0;                 ///< static gain error of the servo loop (ATS a0 compensates)
};

/// Electric (band) actuators: first-order position lag; load cells see band tension.
struct ElectricSettings {
  double lag_time_constant_s = 0.02;
  double band_pretension_lb = 30.0;  ///< load-cell reading of a band with no friction
};

/// Gaussian sensor noise.
struct NoiseSettings {
  bool enabled = true;
  unsigned seed = 1;
  double displacement_std_in = 0.0005;      ///< LVDT of the hydraulic actuator
  double friction_force_std_kip = 0.02;     ///< hydraulic load cell
  double actuator_position_std_in = 0.0002;
  double actuator_force_std_lb = 3.0;       ///< electric actuator load cells
};

/// Backlash after each reversal of the drum: the force is released over `release_travel_in`
/// (the taut band gives back its energy), sits at `gap_force_fraction` of the model force for
/// `gap_travel_in` of drum travel (neither band taut), then the other band engages over
/// `engage_travel_in` and friction builds up from zero in the new direction.
struct BacklashSettings {
  bool enabled = true;
  double reversal_hysteresis_in = 0.003;  ///< travel back from an extreme that counts as a reversal
  double release_travel_in = 0.01;
  double gap_travel_in = 0.05;
  double engage_travel_in = 0.04;
  double gap_force_fraction = 0.05;
};

/// Residual static force: the bands keep tension when the drum stops. After the drum has been
/// at rest (|v| < rest_velocity) for rest_time_s, the force settles (time constant) to
/// `fraction` of the kinetic friction of the last direction of motion, and stays there; when
/// the drum moves again the residual is released over release_travel_in (and only a motion of
/// at least that travel sets a new direction for the next lock). The rig also starts
/// with `initial_kip` locked in the bands (from the previous test).
struct ResidualForceSettings {
  bool enabled = true;
  double initial_kip = 0.3;
  double rest_velocity_in_per_s = 0.02;
  double rest_time_s = 0.1;
  double fraction = 0.8;
  double time_constant_s = 0.05;
  double release_travel_in = 0.02;
};

/// Hardware limits of the rig: commands beyond them are rejected (and logged); a correct
/// substructure never sends one (its safety layer is tighter).
struct RigLimits {
  double stroke_in = 3.0;
  double velocity_in_per_s = 40.0;
  double actuator_min_in = 0.0;
  double actuator_max_in = 2.0;
};

/// Acceptance of commands (damper/physical/command_auth.h).
struct RigAuthSettings {
  double max_command_age_s = 0.05;
  double max_future_s = 0.01;
};

/// Replay of a measured test instead of the simulation: sensor frames are the file's rows.
struct ReplaySettings {
  std::string file;                  ///< /work/shared/data/brfd JSON ("" = simulate)
  bool loop = false;                 ///< at the end: start over (true) or hold the last row
};

/// Where the rig starts (before any command).
struct InitialState {
  double drum_in = 0.0;
  double actuator1_in = 0.0;         ///< default: the damper model's x'_1
  double actuator2_in = 0.0;         ///< default: the damper model's x'_2
};

struct RigConfig {
  std::string source_file;
  double rate_hz = 1024.0;           ///< controller rate: one sensor frame per period
  std::string damper_model_file;     ///< damper model YAML (brfd-default.yaml)
  BrfdParams model;
  HydraulicSettings hydraulic;
  ElectricSettings electric;
  NoiseSettings noise;
  BacklashSettings backlash;
  ResidualForceSettings residual_force;
  RigLimits limits;
  RigAuthSettings auth;
  ReplaySettings replay;
  InitialState initial;
  double idle_exit_s = 2.0;          ///< after the first command: exit when none comes this long
  double start_timeout_s = 300.0;    ///< exit 1 if no command at all comes this long
  int realtime_priority = 45;        ///< SCHED_FIFO priority (0 = none)
};

/// Loads and checks a rig config; throws common::ConfigError naming file, line and key.
RigConfig load_rig_config(const std::string& path);

/// The config as YAML (written next to the rig's log).
std::string rig_config_to_yaml(const RigConfig& config);

}  // namespace damper::rig
