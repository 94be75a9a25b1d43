#pragma once
/// @file substructure_session.h
/// The one place that turns a run config into the substructure of a run, for `hybridsim run`,
/// `hybridsim batch` and `hybridsim bench` alike:
///  - transport.kind in_process: the damper models called directly (InProcessSubstructure);
///  - transport.kind lcm: the LCM link of the transport block (LcmSubstructure), the private
///    network namespace if the config asks for one, the spawned brfd-substructure
///    (damper.launch spawn; virtual or --mode physical) and, for a physical run with
///    rig.launch local, the spawned brfd-rig.
/// Files it writes into the results folder: damper-model.yaml (the model handed to the
/// substructure, full precision), physical.yaml, run.lcmlog, substructure.log, rig.log.

#include "common/process.h"
#include "server/run/run_config.h"
#include "server/run/substructure.h"

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace server {

/// The machinery of the substructure could not be set up (a process did not start, the
/// namespace could not be entered): not the run's fault, a batch redoes it on resume.
class SubstructureSetupError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// LCM link settings of a run config's transport block; the LCM log goes to out_dir/run.lcmlog
/// when transport.write_lcm_log.
LcmLinkSettings lcm_link_settings(const RunConfig& config, const std::string& out_dir);

class SubstructureSession {
 public:
  /// Sets up the substructure of `config` for run `run_id`, results in out_dir.
  /// @throws SubstructureSetupError (process start, namespace), std::runtime_error (LCM URL).
  SubstructureSession(const RunConfig& config, const std::string& out_dir, const std::string& run_id);
  ~SubstructureSession();
  SubstructureSession(const SubstructureSession&) = delete;
  SubstructureSession& operator=(const SubstructureSession&) = delete;

  Substructure& substructure() { return *substructure_; }
  /// The LCM link, or nullptr for an in-process run (the benchmark reads its round trips).
  LcmSubstructure* lcm() { return lcm_; }

  /// After the run: waits for the spawned processes (a physical substructure first ramps the
  /// rig to its safe state) and returns notes worth printing (non-zero exit codes).
  std::vector<std::string> finish(bool run_ok);

 private:
  const RunConfig& config_;
  std::unique_ptr<Substructure> substructure_;
  LcmSubstructure* lcm_ = nullptr;
  ChildProcess substructure_process_, rig_process_;
  bool spawned_substructure_ = false, spawned_rig_ = false;
};

/// Writes `damper-model.yaml` into `out_dir` and starts the substructure process of the
/// config on it, with the config's URL and channel prefix. Child output goes to `log_path`.
/// Physical mode also writes `physical.yaml` (the rig block) and passes --mode physical, the
/// key file (physical_key_path) and the results folder.
ChildProcess spawn_substructure(const RunConfig& config, const std::string& out_dir,
                                const std::string& run_id, const std::string& log_path);

/// Physical mode: the HMAC key file of the run's actuator commands: rig.key_file if the config
/// gives one, else <out_dir>/run.key (written by run_command for a local rig).
std::string physical_key_path(const RunConfig& config, const std::string& out_dir);

/// Physical mode with `rig: launch: local`: starts brfd-rig (the lab-controller emulator) with
/// the config's rig.config, URL, channel prefix, run id and key; its logs go to out_dir.
ChildProcess spawn_rig(const RunConfig& config, const std::string& out_dir, const std::string& run_id,
                       const std::string& log_path);

/// True for a physical run whose rig emulator hybridsim starts itself.
bool launches_local_rig(const RunConfig& config);

}  // namespace server
