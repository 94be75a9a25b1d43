#include "damper/rig/rig_config.h"
#include "common/number_format.h"

#include "common/strict_yaml.h"
#include "damper/model/brfd_config.h"

#include <filesystem>
#include <iomanip>
#include <sstream>

namespace damper::rig {

namespace {
std::string resolve(const std::string& base_file, const std::string& path) {
  if (path.empty() || std::filesystem::path(path).is_absolute()) return path;
  return (std::filesystem::path(base_file).parent_path() / path).lexically_normal().string();
}
}  // namespace

RigConfig load_rig_config(const std::string& path) {
  const common::YamlSection top = common::YamlSection::load_file(path);
  top.allow_only({"rate_hz", "damper_model", "hydraulic", "electric", "noise", "backlash", "residual_force",
                  "limits", "auth", "replay", "initial", "idle_exit_s", "start_timeout_s", "realtime_priority"});
  RigConfig c;
  c.source_file = path;
  c.rate_hz = top.get_double_in("rate_hz", c.rate_hz, 1.0, 100000.0);
  c.damper_model_file = resolve(path, top.get_string("damper_model"));
  try {
    c.model = damper::load_brfd_params(c.damper_model_file);
  } catch (const common::ConfigError& e) {
    throw common::ConfigError(std::string(e.what()) + " (from " + path + ": damper_model)");
  }
  if (top.has("hydraulic")) {
    const common::YamlSection s = top.section("hydraulic");
    s.allow_only({"enabled", "delay_s", "lag_time_constant_s", "gain"});
    HydraulicSettings& h = c.hydraulic;
    h.enabled = s.get_bool("enabled", h.enabled);
    h.delay_s = s.get_double_in("delay_s", h.delay_s, 0.0, 1.0);
    h.lag_time_constant_s = s.get_double_in("lag_time_constant_s", h.lag_time_constant_s, 0.0, 1.0);
    h.gain = s.get_double_in("gain", h.gain, 0.5, 1.5);
  }
  if (top.has("electric")) {
    const common::YamlSection s = top.section("electric");
    s.allow_only({"lag_time_constant_s", "band_pretension_lb"});
    c.electric.lag_time_constant_s = s.get_double_in("lag_time_constant_s", c.electric.lag_time_constant_s, 0.0, 10.0);
    c.electric.band_pretension_lb = s.get_double_in("band_pretension_lb", c.electric.band_pretension_lb, 0.0, 1e5);
  }
  if (top.has("noise")) {
    const common::YamlSection s = top.section("noise");
    s.allow_only({"enabled", "seed", "displacement_std_in", "friction_force_std_kip", "actuator_position_std_in",
                  "actuator_force_std_lb"});
    NoiseSettings& n = c.noise;
    n.enabled = s.get_bool("enabled", n.enabled);
    const int seed = s.get_int("seed", static_cast<int>(n.seed));
    if (seed < 0) s.fail("seed", "must be >= 0");
    n.seed = static_cast<unsigned>(seed);
    n.displacement_std_in = s.get_double_in("displacement_std_in", n.displacement_std_in, 0.0, 1.0);
    n.friction_force_std_kip = s.get_double_in("friction_force_std_kip", n.friction_force_std_kip, 0.0, 10.0);
    n.actuator_position_std_in = s.get_double_in("actuator_position_std_in", n.actuator_position_std_in, 0.0, 1.0);
    n.actuator_force_std_lb = s.get_double_in("actuator_force_std_lb", n.actuator_force_std_lb, 0.0, 1e4);
  }
  if (top.has("backlash")) {
    const common::YamlSection s = top.section("backlash");
    s.allow_only({"enabled", "reversal_hysteresis_in", "release_travel_in", "gap_travel_in", "engage_travel_in",
                  "gap_force_fraction"});
    BacklashSettings& b = c.backlash;
    b.enabled = s.get_bool("enabled", b.enabled);
    b.reversal_hysteresis_in = s.get_double_in("reversal_hysteresis_in", b.reversal_hysteresis_in, 1e-6, 1.0);
    b.release_travel_in = s.get_double_in("release_travel_in", b.release_travel_in, 1e-6, 1.0);
    b.gap_travel_in = s.get_double_in("gap_travel_in", b.gap_travel_in, 0.0, 1.0);
    b.engage_travel_in = s.get_double_in("engage_travel_in", b.engage_travel_in, 1e-6, 1.0);
    b.gap_force_fraction = s.get_double_in("gap_force_fraction", b.gap_force_fraction, 0.0, 1.0);
  }
  if (top.has("residual_force")) {
    const common::YamlSection s = top.section("residual_force");
    s.allow_only({"enabled", "initial_kip", "rest_velocity_in_per_s", "rest_time_s", "fraction", "time_constant_s",
                  "release_travel_in"});
    ResidualForceSettings& r = c.residual_force;
    r.enabled = s.get_bool("enabled", r.enabled);
    r.initial_kip = s.get_double_in("initial_kip", r.initial_kip, -100.0, 100.0);
    r.rest_velocity_in_per_s = s.get_double_in("rest_velocity_in_per_s", r.rest_velocity_in_per_s, 0.0, 100.0);
    r.rest_time_s = s.get_double_in("rest_time_s", r.rest_time_s, 0.0, 100.0);
    r.fraction = s.get_double_in("fraction", r.fraction, 0.0, 2.0);
    r.time_constant_s = s.get_double_in("time_constant_s", r.time_constant_s, 1e-4, 100.0);
    r.release_travel_in = s.get_double_in("release_travel_in", r.release_travel_in, 1e-6, 10.0);
  }
  if (top.has("limits")) {
    const common::YamlSection s = top.section("limits");
    s.allow_only({"stroke_in", "velocity_in_per_s", "actuator_min_in", "actuator_max_in"});
    RigLimits& l = c.limits;
    l.stroke_in = s.get_double_in("stroke_in", l.stroke_in, 1e-6, 100.0);
    l.velocity_in_per_s = s.get_double_in("velocity_in_per_s", l.velocity_in_per_s, 1e-6, 1e4);
    l.actuator_min_in = s.get_double_in("actuator_min_in", l.actuator_min_in, -100.0, 100.0);
    l.actuator_max_in = s.get_double_in("actuator_max_in", l.actuator_max_in, -100.0, 100.0);
    if (l.actuator_max_in <= l.actuator_min_in) s.fail("actuator_max_in", "must be > actuator_min_in");
  }
  if (top.has("auth")) {
    const common::YamlSection s = top.section("auth");
    s.allow_only({"max_command_age_s", "max_future_s"});
    c.auth.max_command_age_s = s.get_double_in("max_command_age_s", c.auth.max_command_age_s, 1e-4, 60.0);
    c.auth.max_future_s = s.get_double_in("max_future_s", c.auth.max_future_s, 0.0, 60.0);
  }
  if (top.has("replay")) {
    const common::YamlSection s = top.section("replay");
    s.allow_only({"file", "loop"});
    c.replay.file = resolve(path, s.get_string("file", ""));
    c.replay.loop = s.get_bool("loop", c.replay.loop);
    if (!c.replay.file.empty() && !std::filesystem::exists(c.replay.file))
      s.fail("file", "no such file: " + c.replay.file);
  }
  c.initial.actuator1_in = c.model.semiactive.actuator1_initial_in;
  c.initial.actuator2_in = c.model.semiactive.actuator2_initial_in;
  if (top.has("initial")) {
    const common::YamlSection s = top.section("initial");
    s.allow_only({"drum_in", "actuator1_in", "actuator2_in"});
    c.initial.drum_in = s.get_double_in("drum_in", c.initial.drum_in, -c.limits.stroke_in, c.limits.stroke_in);
    c.initial.actuator1_in = s.get_double_in("actuator1_in", c.initial.actuator1_in, -100.0, 100.0);
    c.initial.actuator2_in = s.get_double_in("actuator2_in", c.initial.actuator2_in, -100.0, 100.0);
  }
  c.idle_exit_s = top.get_double_in("idle_exit_s", c.idle_exit_s, 0.01, 3600.0);
  c.start_timeout_s = top.get_double_in("start_timeout_s", c.start_timeout_s, 0.01, 86400.0);
  c.realtime_priority = top.get_int("realtime_priority", c.realtime_priority);
  if (c.realtime_priority < 0 || c.realtime_priority > 99) top.fail("realtime_priority", "must be in [0, 99]");
  return c;
}

std::string rig_config_to_yaml(const RigConfig& c) {
  std::ostringstream o;
  common::use_shortest_round_trip(o);
  o << std::boolalpha;
  o << "# Effective brfd-rig config. source: " << c.source_file << "\n"
    << "rate_hz: " << c.rate_hz << "\n"
    << "damper_model: \"" << std::filesystem::absolute(c.damper_model_file).string() << "\"\n"
    << "hydraulic:\n  enabled: " << c.hydraulic.enabled << "\n  delay_s: " << c.hydraulic.delay_s
    << "\n  lag_time_constant_s: " << c.hydraulic.lag_time_constant_s << "\n  gain: " << c.hydraulic.gain << "\n"
    << "electric:\n  lag_time_constant_s: " << c.electric.lag_time_constant_s
    << "\n  band_pretension_lb: " << c.electric.band_pretension_lb << "\n"
    << "noise:\n  enabled: " << c.noise.enabled << "\n  seed: " << c.noise.seed
    << "\n  displacement_std_in: " << c.noise.displacement_std_in
    << "\n  friction_force_std_kip: " << c.noise.friction_force_std_kip
    << "\n  actuator_position_std_in: " << c.noise.actuator_position_std_in
    << "\n  actuator_force_std_lb: " << c.noise.actuator_force_std_lb << "\n"
    << "backlash:\n  enabled: " << c.backlash.enabled << "\n  reversal_hysteresis_in: " << c.backlash.reversal_hysteresis_in
    << "\n  release_travel_in: " << c.backlash.release_travel_in << "\n  gap_travel_in: " << c.backlash.gap_travel_in
    << "\n  engage_travel_in: " << c.backlash.engage_travel_in
    << "\n  gap_force_fraction: " << c.backlash.gap_force_fraction << "\n"
    << "residual_force:\n  enabled: " << c.residual_force.enabled << "\n  initial_kip: " << c.residual_force.initial_kip
    << "\n  rest_velocity_in_per_s: " << c.residual_force.rest_velocity_in_per_s
    << "\n  rest_time_s: " << c.residual_force.rest_time_s << "\n  fraction: " << c.residual_force.fraction
    << "\n  time_constant_s: " << c.residual_force.time_constant_s
    << "\n  release_travel_in: " << c.residual_force.release_travel_in << "\n"
    << "limits:\n  stroke_in: " << c.limits.stroke_in << "\n  velocity_in_per_s: " << c.limits.velocity_in_per_s
    << "\n  actuator_min_in: " << c.limits.actuator_min_in << "\n  actuator_max_in: " << c.limits.actuator_max_in << "\n"
    << "auth:\n  max_command_age_s: " << c.auth.max_command_age_s << "\n  max_future_s: " << c.auth.max_future_s << "\n"
    << "replay:\n  file: \"" << c.replay.file << "\"\n  loop: " << c.replay.loop << "\n"
    << "initial:\n  drum_in: " << c.initial.drum_in << "\n  actuator1_in: " << c.initial.actuator1_in
    << "\n  actuator2_in: " << c.initial.actuator2_in << "\n"
    << "idle_exit_s: " << c.idle_exit_s << "\nstart_timeout_s: " << c.start_timeout_s
    << "\nrealtime_priority: " << c.realtime_priority << "\n";
  return o.str();
}

}  // namespace damper::rig
