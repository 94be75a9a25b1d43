#pragma once
/// @file physical_config.h
/// Settings of the physical substructure (`damper: mode: physical`): where the rig is and
/// how it is started, the safety limits, watchdogs and ramps of the safety layer, and the
/// ATS delay compensator. They are the `rig:` block of a run config (configs/
/// three-story-physical.yaml); every key is optional and has the default below.
///
/// Header-only on purpose: the server (run_config.cc) validates the block when it loads the
/// run config, and brfd-substructure reads the same block back from the physical.yaml the
/// server writes next to the results, with the same code and without a link dependency.
/// Units: in, s, lb (electric actuator load cells), kip.

#include "common/strict_yaml.h"
#include "common/number_format.h"

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <string>

namespace damper::physical {

/// Where the lab controller (or its emulator) is.
struct RigLaunch {
  /// "local": `hybridsim run` starts brfd-rig (the emulator) with `config`;
  /// "external": a lab bridge is already running on the transport URL.
  std::string launch = "local";
  std::string config = "rig-default.yaml";   ///< emulator config (launch local), relative to the run config
  /// HMAC key file (64 hex characters, permissions 0600). Empty: with launch local a fresh
  /// per-run key is written to <results>/run.key; with launch external it is required.
  std::string key_file;
  std::string executable = "brfd-rig";       ///< found beside hybridsim unless a path is given
};

/// Limits of the safety layer. A command that would break one is never published: the run
/// trips instead (hold, ramp to the safe state, abort).
struct SafetyLimits {
  double stroke_in = 2.0;              ///< |drum displacement command| (hydraulic actuator stroke)
  double velocity_in_per_s = 20.0;     ///< |change of the drum command| per controller period / period
  double actuator_min_in = 0.30;       ///< electric actuator position commands must stay in
  double actuator_max_in = 1.20;       ///<   [actuator_min_in, actuator_max_in]
  double actuator_force_lb = 4000.0;   ///< |measured electric actuator force| (their safety limit)
  /// |change of an electric actuator command| per controller period / period (semi-active
  /// control moves them; the substructure shapes the controller's targets at the actuator
  /// model's velocity_limit_in_per_s, this is the backstop)
  double actuator_velocity_in_per_s = 1.0;
  double drift_in = 1.5;               ///< |target drum displacement (drift) from the server|
  double tracking_error_in = 0.3;      ///< |measured - target drum displacement| (target blended in over ramp_in_s)
};

struct Watchdogs {
  /// No sensor frame this long -> trip (rig gone). 50 ms: on a busy 2-core VM without a
  /// real-time kernel, frame gaps of 10-15 ms were measured (docs/physical.md); a lab with a
  /// real-time controller link can go down to a few ms.
  double sensor_frame_timeout_s = 0.05;
  double server_command_timeout_s = 0.25;  ///< running and no drift command this long -> trip
  double rig_start_timeout_s = 5.0;        ///< first sensor frame after START must come within
};

/// Ramps of the safety layer (all cosine-shaped, so velocity starts and ends at zero).
struct Ramps {
  double positioning_s = 0.25;          ///< before READY: measured position -> start position
  double ramp_in_s = 0.25;              ///< excitation ramp-in: command blended in over this
  double ramp_out_s = 0.5;              ///< after STOP or a trip: to the safe state, at least this long
  double hold_s = 0.05;                 ///< after a trip: hold the last command this long first
  double ramp_velocity_in_per_s = 2.0;  ///< peak velocity of positioning / ramp-out moves
  double safe_drum_in = 0.0;            ///< safe state of the drum (electric actuators: x'_1, x'_2)
};

/// Adaptive time series (ATS) compensator (Chae, Kazemibidokhti & Ricles 2013).
struct AtsSettings {
  bool enabled = true;
  double window_s = 1.0;          ///< moving least-squares window
  int update_every = 16;          ///< samples between coefficient updates
  double filter_hz = 12.0;        ///< identical low-pass on commanded and measured before the fit
  double initial_delay_s = 0.0;   ///< a1 at start (a0 = 1, a2 = a1^2/2)
  double min_rms_in = 0.005;      ///< no update while the windowed motion is smaller than this
  double a0_min = 0.7, a0_max = 1.3;
  double a1_min_s = 0.0, a1_max_s = 0.08;
  double a2_min_s2 = 0.0, a2_max_s2 = 0.0032;
};

struct PhysicalSettings {
  RigLaunch rig;
  double controller_rate_hz = 1024.0;  ///< the run's dt_s must be 1 / this
  int realtime_priority = 40;          ///< SCHED_FIFO priority of brfd-substructure (0 = none)
  SafetyLimits limits;
  Watchdogs watchdogs;
  Ramps ramp;
  AtsSettings ats;
};

namespace detail {
inline std::string resolve(const std::string& base_file, const std::string& path) {
  if (path.empty() || std::filesystem::path(path).is_absolute()) return path;
  return (std::filesystem::path(base_file).parent_path() / path).lexically_normal().string();
}
}  // namespace detail

/// Reads a `rig:` block strictly. Relative paths are resolved against `s.file()`.
/// Throws common::ConfigError naming file, line and key.
inline PhysicalSettings physical_settings_from_yaml(const common::YamlSection& s) {
  s.allow_only({"launch", "config", "key_file", "executable", "controller_rate_hz", "realtime_priority",
                "limits", "watchdogs", "ramp", "ats"});
  PhysicalSettings p;
  p.rig.launch = s.get_choice("launch", p.rig.launch, {"local", "external"});
  p.rig.config = detail::resolve(s.file(), s.get_string("config", p.rig.config));
  p.rig.key_file = detail::resolve(s.file(), s.get_string("key_file", ""));
  p.rig.executable = s.get_string("executable", p.rig.executable);
  p.controller_rate_hz = s.get_double_in("controller_rate_hz", p.controller_rate_hz, 1.0, 100000.0);
  p.realtime_priority = s.get_int("realtime_priority", p.realtime_priority);
  if (p.realtime_priority < 0 || p.realtime_priority > 99) s.fail("realtime_priority", "must be in [0, 99]");
  if (p.rig.launch == "external" && p.rig.key_file.empty())
    s.fail("key_file", "required when rig.launch is external: the lab bridge must hold the same HMAC key");
  if (s.has("limits")) {
    const common::YamlSection l = s.section("limits");
    l.allow_only({"stroke_in", "velocity_in_per_s", "actuator_min_in", "actuator_max_in", "actuator_force_lb",
                  "actuator_velocity_in_per_s", "drift_in", "tracking_error_in"});
    SafetyLimits& m = p.limits;
    m.stroke_in = l.get_double_in("stroke_in", m.stroke_in, 1e-6, 100.0);
    m.velocity_in_per_s = l.get_double_in("velocity_in_per_s", m.velocity_in_per_s, 1e-6, 1000.0);
    m.actuator_min_in = l.get_double_in("actuator_min_in", m.actuator_min_in, -100.0, 100.0);
    m.actuator_max_in = l.get_double_in("actuator_max_in", m.actuator_max_in, -100.0, 100.0);
    if (m.actuator_max_in <= m.actuator_min_in) l.fail("actuator_max_in", "must be > limits.actuator_min_in");
    m.actuator_force_lb = l.get_double_in("actuator_force_lb", m.actuator_force_lb, 1e-6, 1e6);
    m.actuator_velocity_in_per_s = l.get_double_in("actuator_velocity_in_per_s", m.actuator_velocity_in_per_s, 1e-6, 1000.0);
    m.drift_in = l.get_double_in("drift_in", m.drift_in, 1e-6, 100.0);
    m.tracking_error_in = l.get_double_in("tracking_error_in", m.tracking_error_in, 1e-6, 100.0);
  }
  if (s.has("watchdogs")) {
    const common::YamlSection w = s.section("watchdogs");
    w.allow_only({"sensor_frame_timeout_s", "server_command_timeout_s", "rig_start_timeout_s"});
    Watchdogs& d = p.watchdogs;
    d.sensor_frame_timeout_s = w.get_double_in("sensor_frame_timeout_s", d.sensor_frame_timeout_s, 1e-3, 10.0);
    d.server_command_timeout_s = w.get_double_in("server_command_timeout_s", d.server_command_timeout_s, 1e-3, 60.0);
    d.rig_start_timeout_s = w.get_double_in("rig_start_timeout_s", d.rig_start_timeout_s, 1e-3, 600.0);
  }
  if (s.has("ramp")) {
    const common::YamlSection r = s.section("ramp");
    r.allow_only({"positioning_s", "ramp_in_s", "ramp_out_s", "hold_s", "ramp_velocity_in_per_s", "safe_drum_in"});
    Ramps& m = p.ramp;
    m.positioning_s = r.get_double_in("positioning_s", m.positioning_s, 0.0, 60.0);
    m.ramp_in_s = r.get_double_in("ramp_in_s", m.ramp_in_s, 0.0, 60.0);
    m.ramp_out_s = r.get_double_in("ramp_out_s", m.ramp_out_s, 0.0, 60.0);
    m.hold_s = r.get_double_in("hold_s", m.hold_s, 0.0, 10.0);
    m.ramp_velocity_in_per_s = r.get_double_in("ramp_velocity_in_per_s", m.ramp_velocity_in_per_s, 1e-6, 1000.0);
    m.safe_drum_in = r.get_double_in("safe_drum_in", m.safe_drum_in, -100.0, 100.0);
  }
  if (p.ramp.ramp_velocity_in_per_s > 0.5 * p.limits.velocity_in_per_s)
    s.fail("ramp", "ramp.ramp_velocity_in_per_s must be at most half of limits.velocity_in_per_s");
  if (std::abs(p.ramp.safe_drum_in) > p.limits.stroke_in) s.fail("ramp", "ramp.safe_drum_in is beyond limits.stroke_in");
  if (s.has("ats")) {
    const common::YamlSection a = s.section("ats");
    a.allow_only({"enabled", "window_s", "update_every", "filter_hz", "initial_delay_s", "min_rms_in", "a0_min",
                  "a0_max", "a1_min_s", "a1_max_s", "a2_min_s2", "a2_max_s2"});
    AtsSettings& m = p.ats;
    m.enabled = a.get_bool("enabled", m.enabled);
    m.window_s = a.get_double_in("window_s", m.window_s, 0.01, 60.0);
    m.update_every = a.get_int("update_every", m.update_every);
    if (m.update_every < 1) a.fail("update_every", "must be >= 1");
    m.filter_hz = a.get_double_in("filter_hz", m.filter_hz, 0.1, 0.45 * p.controller_rate_hz);
    m.min_rms_in = a.get_double_in("min_rms_in", m.min_rms_in, 0.0, 100.0);
    m.a0_min = a.get_double_in("a0_min", m.a0_min, 0.0, 10.0);
    m.a0_max = a.get_double_in("a0_max", m.a0_max, 0.0, 10.0);
    m.a1_min_s = a.get_double_in("a1_min_s", m.a1_min_s, -1.0, 1.0);
    m.a1_max_s = a.get_double_in("a1_max_s", m.a1_max_s, -1.0, 1.0);
    m.a2_min_s2 = a.get_double_in("a2_min_s2", m.a2_min_s2, -1.0, 1.0);
    m.a2_max_s2 = a.get_double_in("a2_max_s2", m.a2_max_s2, -1.0, 1.0);
    if (m.a0_min > m.a0_max) a.fail("a0_max", "must be >= a0_min");
    if (m.a1_min_s > m.a1_max_s) a.fail("a1_max_s", "must be >= a1_min_s");
    if (m.a2_min_s2 > m.a2_max_s2) a.fail("a2_max_s2", "must be >= a2_min_s2");
    m.initial_delay_s = a.get_double_in("initial_delay_s", m.initial_delay_s, m.a1_min_s, m.a1_max_s);
  }
  return p;
}

/// Loads a file whose top level is a `rig:` block's contents (the physical.yaml the server
/// writes for brfd-substructure).
inline PhysicalSettings load_physical_settings(const std::string& path) {
  return physical_settings_from_yaml(common::YamlSection::load_file(path));
}

/// The settings as YAML (the contents of a `rig:` block, unindented).
inline std::string physical_settings_to_yaml(const PhysicalSettings& p) {
  std::ostringstream o;
  common::use_shortest_round_trip(o);
  o << std::boolalpha;
  o << "launch: " << p.rig.launch << "\n"
    << "config: \"" << (p.rig.config.empty() ? "" : std::filesystem::absolute(p.rig.config).string()) << "\"\n"
    << "key_file: \"" << (p.rig.key_file.empty() ? "" : std::filesystem::absolute(p.rig.key_file).string()) << "\"\n"
    << "executable: \"" << p.rig.executable << "\"\n"
    << "controller_rate_hz: " << p.controller_rate_hz << "\n"
    << "realtime_priority: " << p.realtime_priority << "\n";
  const SafetyLimits& l = p.limits;
  o << "limits:\n  stroke_in: " << l.stroke_in << "\n  velocity_in_per_s: " << l.velocity_in_per_s
    << "\n  actuator_min_in: " << l.actuator_min_in << "\n  actuator_max_in: " << l.actuator_max_in
    << "\n  actuator_force_lb: " << l.actuator_force_lb << "\n  actuator_velocity_in_per_s: " << l.actuator_velocity_in_per_s
    << "\n  drift_in: " << l.drift_in
    << "\n  tracking_error_in: " << l.tracking_error_in << "\n";
  const Watchdogs& w = p.watchdogs;
  o << "watchdogs:\n  sensor_frame_timeout_s: " << w.sensor_frame_timeout_s
    << "\n  server_command_timeout_s: " << w.server_command_timeout_s
    << "\n  rig_start_timeout_s: " << w.rig_start_timeout_s << "\n";
  const Ramps& r = p.ramp;
  o << "ramp:\n  positioning_s: " << r.positioning_s << "\n  ramp_in_s: " << r.ramp_in_s
    << "\n  ramp_out_s: " << r.ramp_out_s << "\n  hold_s: " << r.hold_s
    << "\n  ramp_velocity_in_per_s: " << r.ramp_velocity_in_per_s << "\n  safe_drum_in: " << r.safe_drum_in << "\n";
  const AtsSettings& a = p.ats;
  o << "ats:\n  enabled: " << a.enabled << "\n  window_s: " << a.window_s << "\n  update_every: " << a.update_every
    << "\n  filter_hz: " << a.filter_hz << "\n  initial_delay_s: " << a.initial_delay_s
    << "\n  min_rms_in: " << a.min_rms_in << "\n  a0_min: " << a.a0_min << "\n  a0_max: " << a.a0_max
    << "\n  a1_min_s: " << a.a1_min_s << "\n  a1_max_s: " << a.a1_max_s << "\n  a2_min_s2: " << a.a2_min_s2
    << "\n  a2_max_s2: " << a.a2_max_s2 << "\n";
  return o.str();
}

}  // namespace damper::physical
