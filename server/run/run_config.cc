#include "server/run/run_config.h"
#include "common/number_format.h"

#include "common/resource_limits.h"
#include "common/strict_yaml.h"
#include "damper/model/brfd_config.h"

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace server {

namespace fs = std::filesystem;

namespace {
std::string resolve(const std::string& base_file, const std::string& path) {
  if (path.empty() || fs::path(path).is_absolute()) return path;
  return (fs::path(base_file).parent_path() / path).lexically_normal().string();
}
}  // namespace

RunConfig load_run_config(const std::string& path) {
  const common::YamlSection top = common::YamlSection::load_file(path);
  top.allow_only({"run", "record", "building", "damper", "transport", "output", "rig", "control"});
  RunConfig c;
  c.source_file = path;

  const common::YamlSection run = top.section("run");
  run.allow_only({"name", "dt_s", "max_energy_balance_error", "integrator", "rho_inf"});
  c.name = run.get_string("name", c.name);
  if (c.name.empty()) run.fail("name", "must not be empty (it names the run id and its LCM messages)");
  if (c.name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789._-") !=
          std::string::npos || c.name.size() > 64)
    run.fail("name", "'" + c.name + "': use at most 64 letters, digits, '.', '_' or '-'");
  c.dt_s = run.get_double_in("dt_s", c.dt_s, 1e-6, 0.1);
  c.max_energy_balance_error = run.get_double_in("max_energy_balance_error", c.max_energy_balance_error, 0.0, 10.0);
  c.key_location["run.dt_s"] = run.location("dt_s");
  c.integrator.kind = run.get_choice("integrator", c.integrator.kind, {"cr", "kr_alpha"});
  if (run.has("rho_inf") && c.integrator.kind != "kr_alpha")
    run.fail("rho_inf", "applies to run.integrator kr_alpha only (CR has no numerical dissipation)");
  c.integrator.rho_inf = run.get_double_in("rho_inf", c.integrator.rho_inf, 0.0, 1.0);

  const common::YamlSection rec = top.section("record");
  rec.allow_only({"path", "scale", "duration_s", "resample"});
  c.record.path = resolve(path, rec.get_string("path"));
  c.record.scale = rec.get_double_in("scale", 1.0, 1e-6, 100.0);
  c.record.duration_s = rec.get_double("duration_s", -1.0);
  if (c.record.duration_s == 0.0)
    rec.fail("duration_s", "0 s would run no step: give the seconds to simulate (> 0), or < 0 for the whole record");
  c.key_location["record.duration_s"] = rec.location("duration_s");
  c.record.resample = rec.get_choice("resample", c.record.resample, {"linear", "exact"});
  c.key_location["record.resample"] = rec.location("resample");

  c.building = structure::building_params_from_yaml(top.section("building"));

  // No dampers: the damper block (and its model) may be left out.
  c.has_damper_block = top.has("damper") || !c.building.dampers.empty();
  if (c.has_damper_block) {
    const common::YamlSection d = top.section("damper");
    d.allow_only({"mode", "model_config", "model", "launch", "executable"});
    c.damper.mode = d.get_choice("mode", {"virtual", "physical"});
    if (d.has("model") == d.has("model_config"))
      d.fail("model_config", "give exactly one of damper.model_config (a file) or damper.model (inline)");
    c.damper.launch = d.get_choice("launch", c.damper.launch, {"spawn", "external"});
    c.damper.executable = d.get_string("executable", c.damper.executable);
    if (d.has("model")) {
      c.damper_model = damper::brfd_params_from_yaml(d.section("model"));
    } else {
      c.damper.model_config = resolve(path, d.get_string("model_config"));
      try {
        c.damper_model = damper::load_brfd_params(c.damper.model_config);
      } catch (const common::ConfigError& e) {
        throw common::ConfigError(std::string(e.what()) + " (from " + path + ": damper.model_config)");
      }
    }
  }

  // Without dampers nothing is exchanged: the transport block may be left out too (in-process).
  TransportSettings& tr = c.transport;
  if (!c.has_damper_block && !top.has("transport")) {
    tr.kind = "in_process";
  } else {
    const common::YamlSection t = top.section("transport");
    t.allow_only({"kind", "url", "private_netns", "lab_network", "channel_prefix", "step_timeout_s",
                  "start_timeout_s", "write_lcm_log", "on_bad_message", "key_file"});
    tr.kind = t.get_choice("kind", {"lcm", "in_process"});
    tr.url = t.get_string("url", "");
    if (tr.kind == "lcm" && tr.url.empty()) t.fail("url", "required when transport.kind is lcm");
    tr.private_netns = t.get_bool("private_netns", tr.private_netns);
    tr.lab_network = t.get_bool("lab_network", tr.lab_network);
    tr.channel_prefix = t.get_string("channel_prefix", tr.channel_prefix);
    tr.step_timeout_s = t.get_double_in("step_timeout_s", tr.step_timeout_s, 1e-3, 60.0);
    tr.start_timeout_s = t.get_double_in("start_timeout_s", tr.start_timeout_s, 1e-3, 600.0);
    tr.write_lcm_log = t.get_bool("write_lcm_log", tr.write_lcm_log);
    tr.on_bad_message = t.get_choice("on_bad_message", tr.on_bad_message, {"drop", "stop"});
    if (t.has("key_file")) {
      tr.key_file = resolve(path, t.get_string("key_file"));
      if (tr.key_file.empty() || !fs::is_regular_file(tr.key_file))
        t.fail("key_file", "no such key file: '" + tr.key_file + "' (64 hex characters, mode 0600)");
    }
    if (c.damper.mode == "physical" && tr.kind != "lcm")
      t.fail("kind", "damper.mode physical needs transport.kind lcm (the rig is another process)");
  }

  if (top.has("control")) {
    c.control = control::control_config_from_yaml(top.section("control"));
    if (c.damper_model.kind == damper::DamperKind::passive_lugre)
      top.section("control").fail("law", "control needs a damper model with electric actuators (`model: semiactive` or "
                                         "`model: band_brake`), not passive_lugre");
    if (c.building.dampers.empty()) top.section("control").fail("law", "the building has no dampers to control");
    try {
      control::FrictionInverse check(c.damper_model, c.control.min_kinetic_friction_kip);
    } catch (const std::invalid_argument& e) {
      top.section("control").fail("law", std::string("the damper model cannot be controlled: ") + e.what());
    }
  }
  // Physical mode (docs/physical.md): the rig block; absent = defaults (local emulator).
  c.rig.rig.config = resolve(path, c.rig.rig.config);
  if (top.has("rig")) c.rig = damper::physical::physical_settings_from_yaml(top.section("rig"));
  // One HMAC key per run (messages/run_key.h): a physical run's rig.key_file, else
  // transport.key_file, else a fresh <results>/run.key.
  if (c.damper.mode == "physical" && !c.rig.rig.key_file.empty() && !tr.key_file.empty() &&
      fs::absolute(c.rig.rig.key_file) != fs::absolute(tr.key_file))
    top.section("transport").fail("key_file", "one HMAC key per run: rig.key_file is the run's key, give the same file or only one");
  if (tr.kind == "lcm" && c.damper.launch == "external" && tr.key_file.empty() &&
      (c.damper.mode != "physical" || c.rig.rig.key_file.empty()))
    top.section("transport").fail("key_file", "required when damper.launch is external: the substructure started by hand must hold the "
                       "run's HMAC key (brfd-substructure --key-file)");
  if (c.damper.mode == "physical") {
    if (std::abs(c.dt_s * c.rig.controller_rate_hz - 1.0) > 1e-9)
      run.fail("dt_s", "damper.mode physical sends one actuator command per step: dt_s must be 1 / "
                       "rig.controller_rate_hz (" + std::to_string(1.0 / c.rig.controller_rate_hz) + " s)");
    if (c.rig.rig.launch == "local" && !fs::exists(c.rig.rig.config))
      throw common::ConfigError(path + ": rig.config: no such rig emulator config: " + c.rig.rig.config);
  }

  if (top.has("output")) {
    const common::YamlSection o = top.section("output");
    o.allow_only({"dir", "flush_every_steps", "every_n_steps", "format"});
    c.output.format = o.get_choice("format", c.output.format, {"csv", "hdf5"});
    c.output.every_n_steps = o.get_int("every_n_steps", c.output.every_n_steps);
    if (c.output.every_n_steps < 1) o.fail("every_n_steps", "must be >= 1");
    c.output.dir = resolve(path, o.get_string("dir", c.output.dir));
    c.output.flush_every_steps = o.get_int("flush_every_steps", c.output.flush_every_steps);
    if (c.output.flush_every_steps < 1) o.fail("flush_every_steps", "must be >= 1");
    c.key_location["output.dir"] = o.location("dir");
  }
  return c;
}

std::string RunConfig::at(const std::string& key) const {
  const auto it = key_location.find(key);
  return (it != key_location.end() ? it->second : source_file) + ": " + key + ": ";
}

long check_run_against_record(const RunConfig& c, double record_dt_s, double record_duration_s,
                              const std::string& record_source) {
  std::ostringstream msg;
  msg << std::setprecision(10);
  const double duration = c.record.duration_s;
  if (duration == 0.0 || !std::isfinite(duration)) {
    msg << c.at("record.duration_s") << duration
        << " s: give the seconds to simulate (> 0), or < 0 for the whole record";
    throw common::ConfigError(msg.str());
  }
  if (duration > record_duration_s * (1.0 + 1e-9) + 1e-12) {
    msg << c.at("record.duration_s") << duration << " s is longer than the record " << record_source << " ("
        << record_duration_s << " s); give at most " << record_duration_s << " s, or < 0 for the whole record";
    throw common::ConfigError(msg.str());
  }
  if (c.dt_s > record_dt_s * (1.0 + 1e-9)) {
    msg << c.at("run.dt_s") << c.dt_s << " s is larger than the sample interval of the record " << record_source
        << " (DT = " << record_dt_s << " s): the step loop would skip record samples; use dt_s <= DT";
    throw common::ConfigError(msg.str());
  }
  const double run_s = duration > 0 ? duration : record_duration_s;
  const double steps = std::floor(run_s / c.dt_s + 1e-9);
  if (steps > static_cast<double>(kMaxRunSteps)) {
    msg << c.at("record.duration_s") << run_s << " s at run.dt_s = " << c.dt_s << " s is " << steps
        << " steps, more than the limit of " << kMaxRunSteps << " steps per run";
    throw common::ConfigError(msg.str());
  }
  // Disk: the time history (≥ 8 characters per value written) and the LCM log (≥ 150 bytes
  // per step: one command and one feedback with their event headers).
  const int stories = static_cast<int>(c.building.story_mass_kip_s2_per_in.size());
  const int dampers = static_cast<int>(c.building.dampers.size());
  const double columns = 2.0 + 3.0 * stories + 2.0 * dampers;
  double bytes = (steps / c.output.every_n_steps + 1.0) * columns * 8.0;
  if (c.transport.kind == "lcm" && c.transport.write_lcm_log) bytes += steps * 150.0;
  const double free_bytes = static_cast<double>(common::free_disk_bytes(c.output.dir));
  if (bytes > free_bytes) {
    msg << c.at("record.duration_s") << run_s << " s (" << steps << " steps) writes at least "
        << common::format_bytes(bytes) << " of results, but the disk of output.dir " << c.output.dir << " has "
        << common::format_bytes(free_bytes) << " free (shorten the run or raise output.every_n_steps)";
    throw common::ConfigError(msg.str());
  }
  return static_cast<long>(steps);
}

std::string run_config_to_yaml(const RunConfig& c) {
  std::ostringstream o;
  common::use_shortest_round_trip(o);
  o << std::boolalpha;
  o << "# Effective config of this run (every value used). Units: kip, in, s.\n"
    << "# source: " << c.source_file << "\n"
    << "run:\n  name: " << c.name << "\n  dt_s: " << c.dt_s
    << "\n  max_energy_balance_error: " << c.max_energy_balance_error
    << "\n  integrator: " << c.integrator.kind << "\n";
  if (c.integrator.kind == "kr_alpha") o << "  rho_inf: " << c.integrator.rho_inf << "\n";
  o << "record:\n  path: " << fs::absolute(c.record.path).string() << "\n  scale: " << c.record.scale
    << "\n  duration_s: " << c.record.duration_s << "\n  resample: " << c.record.resample << "\n";
  if (!c.resampling_note.empty()) o << "  # " << c.resampling_note << "\n";
  o << "building:\n";
  std::istringstream b(structure::building_params_to_yaml(c.building));
  for (std::string line; std::getline(b, line);) o << "  " << line << "\n";
  if (c.has_damper_block) {
    o << "damper:\n  mode: " << c.damper.mode << "\n  launch: " << c.damper.launch
      << "\n  executable: " << c.damper.executable << "\n";
    if (!c.damper.model_config.empty())
      o << "  # model read from " << fs::absolute(c.damper.model_config).string() << "\n";
    o << "  model:\n";
    std::istringstream m(damper::brfd_params_to_yaml(c.damper_model));
    for (std::string line; std::getline(m, line);) o << "    " << line << "\n";
  } else {
    o << "# no dampers: no damper block, no substructure model\n";
  }
  const TransportSettings& t = c.transport;
  o << "transport:\n  kind: " << t.kind << "\n  url: \"" << t.url << "\"\n  private_netns: "
    << t.private_netns << "\n  lab_network: " << t.lab_network << "\n  channel_prefix: "
    << t.channel_prefix << "\n  step_timeout_s: " << t.step_timeout_s
    << "\n  start_timeout_s: " << t.start_timeout_s << "\n  write_lcm_log: " << t.write_lcm_log
    << "\n  on_bad_message: " << t.on_bad_message;
  if (!t.key_file.empty()) o << "\n  key_file: \"" << fs::absolute(t.key_file).string() << "\"";
  o << "\n"
    << "output:\n  dir: " << fs::absolute(c.output.dir).string()
    << "\n  flush_every_steps: " << c.output.flush_every_steps
    << "\n  every_n_steps: " << c.output.every_n_steps
    << "\n  format: " << c.output.format << "\n";
  if (c.damper.mode == "physical") {
    o << "rig:\n";
    std::istringstream r(damper::physical::physical_settings_to_yaml(c.rig));
    for (std::string line; std::getline(r, line);) o << "  " << line << "\n";
  }
  o << control::control_config_to_yaml(c.control);
  return o.str();
}

}  // namespace server

namespace server {

ResampleDescription describe_resampling(double record_dt_s, double run_dt_s, const std::string& mode) {
  ResampleDescription d;
  d.record_dt_s = record_dt_s;
  d.run_dt_s = run_dt_s;
  d.mode = mode;
  const double ratio = record_dt_s / run_dt_s;
  const double whole = std::round(ratio);
  if (whole >= 1.0 && std::abs(ratio - whole) <= 1e-9 * ratio) d.steps_per_sample = static_cast<long>(whole);
  std::ostringstream o;
  o << std::setprecision(10) << "record step " << record_dt_s << " s, run step " << run_dt_s << " s: ";
  if (d.steps_per_sample == 1) {
    o << "one step per record sample, no interpolation";
  } else if (d.steps_per_sample > 1) {
    o << "linear interpolation, " << d.steps_per_sample << " steps per record sample, every sample on a step";
  } else {
    o << "linear interpolation between record samples (the run step does not divide the record step: "
         "samples fall between steps)";
  }
  d.text = o.str();
  return d;
}

void check_resampling(const RunConfig& config, double record_dt_s) {
  if (config.record.resample != "exact") return;
  const ResampleDescription d = describe_resampling(record_dt_s, config.dt_s, "exact");
  if (d.steps_per_sample == 0) {
    std::ostringstream o;
    o << std::setprecision(10) << config.source_file << ": record.resample: exact needs the record step ("
      << record_dt_s << " s) to be a whole number of run steps (run.dt_s " << config.dt_s
      << " s); use resample: linear or a run.dt_s such as " << record_dt_s / std::max(1.0, std::ceil(record_dt_s / config.dt_s))
      << " s";
    throw common::ConfigError(o.str());
  }
}

}  // namespace server
