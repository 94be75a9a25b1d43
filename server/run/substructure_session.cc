#include "server/run/substructure_session.h"

#include "damper/model/brfd_config.h"
#include "damper/physical/physical_config.h"
#include "damper/physical/realtime.h"
#include "messages/bad_message_log.h"
#include "messages/lcm_bus.h"
#include "messages/run_key.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace server {

namespace fs = std::filesystem;

LcmLinkSettings lcm_link_settings(const RunConfig& config, const std::string& out_dir) {
  LcmLinkSettings link;
  link.url = config.transport.url;
  link.lab_network = config.transport.lab_network;
  link.channels.prefix = config.transport.channel_prefix;
  link.step_timeout_s = config.transport.step_timeout_s;
  link.start_timeout_s = config.transport.start_timeout_s;
  if (config.transport.write_lcm_log) link.log_path = (fs::path(out_dir) / "run.lcmlog").string();
  link.on_bad_message = messages::parse_bad_message_policy(config.transport.on_bad_message);
  return link;
}

bool launches_local_rig(const RunConfig& config) {
  return config.damper.mode == "physical" && config.rig.rig.launch == "local" && config.transport.kind == "lcm";
}

SubstructureSession::SubstructureSession(const RunConfig& config, const std::string& out_dir,
                                         const std::string& run_id)
    : config_(config), out_dir_(out_dir) {
  if (config.transport.kind == "in_process") {
    substructure_ = std::make_unique<InProcessSubstructure>(config.damper_model);
    return;
  }
  try {
    if (config.transport.private_netns && !messages::in_private_network_namespace())
      messages::enter_private_network_namespace();
  } catch (const std::exception& e) {
    throw SubstructureSetupError(e.what());
  }
  const bool physical = config.damper.mode == "physical";
  // Physical: the step loop is part of the real-time loop with the rig (below the
  // substructure's priority); set before LCM starts its receive thread, which inherits it.
  if (physical) damper::physical::enter_realtime(std::max(0, config.rig.realtime_priority - 10), "hybridsim");
  LcmLinkSettings link = lcm_link_settings(config, out_dir);
  // The run's HMAC key: a fresh one unless the config names a file (a lab's or an external
  // substructure's).
  const std::string key_path = run_key_path(config, out_dir);
  try {
    if (key_path == (fs::path(out_dir) / "run.key").string())
      messages::write_key_file(key_path, messages::generate_run_key());
    link.key = messages::read_key_file(key_path);
  } catch (const std::exception& e) {
    throw SubstructureSetupError(e.what());
  }
  // A spawned substructure that exits (or never starts) ends the link's wait at once, not at
  // the start or step timeout. A dead rig is the substructure's to notice (sensor-frame
  // watchdog, safety trip, ramp to safe): its report says more than an exit code.
  const std::string log_path = (fs::path(out_dir) / "substructure.log").string();
  link.peer_gone = [this, exe = config.damper.executable, log_path]() -> std::string {
    if (spawned_substructure_ && !substructure_process_.running())
      return exe + " exited with code " + std::to_string(substructure_process_.exit_code()) + " (see " + log_path + ")";
    return {};
  };
  auto lcm = std::make_unique<LcmSubstructure>(link);
  lcm_ = lcm.get();
  substructure_ = std::move(lcm);
  const fs::path out(out_dir);
  try {
    if (launches_local_rig(config)) {
      rig_process_ = spawn_rig(config, out_dir, run_id, (out / "rig.log").string());
      spawned_rig_ = true;
    }
    if (config.damper.launch == "spawn") {
      substructure_process_ = spawn_substructure(config, out_dir, run_id, (out / "substructure.log").string());
      spawned_substructure_ = true;
    }
  } catch (const std::exception& e) {
    throw SubstructureSetupError(e.what());
  }
}

SubstructureSession::~SubstructureSession() = default;

std::vector<std::string> SubstructureSession::finish(bool run_ok) {
  std::vector<std::string> notes;
  const bool physical = config_.damper.mode == "physical";
  if (spawned_substructure_) {
    // Physical: the substructure first ramps the rig out to its safe state.
    const int code = substructure_process_.wait_or_kill(physical ? 10.0 : 2.0);
    if (code != 0 && run_ok) notes.push_back("warning: substructure exited with code " + std::to_string(code));
    spawned_substructure_ = false;
  }
  if (spawned_rig_) {
    const int code = rig_process_.wait_or_kill(5.0);
    if (code != 0) notes.push_back("note: brfd-rig exited with code " + std::to_string(code) + " (see rig.log)");
    spawned_rig_ = false;
  }
  if (lcm_ != nullptr && config_.damper.launch == "spawn")
    substructure_bad_messages_ = messages::BadMessageLog::read_json_file(
        (fs::path(out_dir_) / messages::kSubstructureMessagesFile).string());
  return notes;
}

std::map<std::string, std::map<std::string, long>> SubstructureSession::bad_messages() const {
  std::map<std::string, std::map<std::string, long>> out;
  if (lcm_ == nullptr) return out;
  out["hybridsim"] = lcm_->bad_messages().counts();
  // A substructure started by hand keeps its counts in its own log (stderr).
  if (config_.damper.launch == "spawn") out["brfd-substructure"] = substructure_bad_messages_;
  return out;
}

ChildProcess spawn_substructure(const RunConfig& config, const std::string& out_dir,
                                const std::string& run_id, const std::string& log_path) {
  const std::string model_path = (fs::path(out_dir) / "damper-model.yaml").string();
  {
    std::ofstream model(model_path);
    model << "# Damper model handed to the substructure (full precision: the same model as an\n"
          << "# in-process run). Units: kip, in, s.\n"
          << damper::brfd_params_to_yaml(config.damper_model);
  }
  std::vector<std::string> args{"--model-config", model_path, "--url", config.transport.url,
                                "--channel-prefix", config.transport.channel_prefix, "--run-id", run_id};
  if (config.transport.lab_network) args.push_back("--lab-network");
  args.insert(args.end(), {"--key-file", run_key_path(config, out_dir), "--results-dir", out_dir,
                           "--on-bad-message", config.transport.on_bad_message});
  if (config.damper.mode == "physical") {
    const std::string physical_path = (fs::path(out_dir) / "physical.yaml").string();
    std::ofstream(physical_path) << "# rig block of the run config, for brfd-substructure --mode physical\n"
                                 << damper::physical::physical_settings_to_yaml(config.rig);
    args.insert(args.end(), {"--mode", "physical", "--physical-config", physical_path});
  }
  return ChildProcess(sibling_executable(config.damper.executable), args, log_path);
}

std::string run_key_path(const RunConfig& config, const std::string& out_dir) {
  if (config.damper.mode == "physical" && !config.rig.rig.key_file.empty()) return config.rig.rig.key_file;
  if (!config.transport.key_file.empty()) return config.transport.key_file;
  return (fs::path(out_dir) / "run.key").string();
}

ChildProcess spawn_rig(const RunConfig& config, const std::string& out_dir, const std::string& run_id,
                       const std::string& log_path) {
  std::vector<std::string> args{"--config", config.rig.rig.config, "--url", config.transport.url,
                                "--channel-prefix", config.transport.channel_prefix, "--run-id", run_id,
                                "--key-file", run_key_path(config, out_dir), "--log-dir", out_dir};
  if (config.transport.lab_network) args.push_back("--lab-network");
  return ChildProcess(sibling_executable(config.rig.rig.executable), args, log_path);
}

}  // namespace server
