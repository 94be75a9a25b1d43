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
/// substructure, full precision), physical.yaml, run.lcmlog, substructure.log, rig.log, and
/// run.key: the run's HMAC key (mode 0600; messages/run_key.h) unless the config names one
/// (rig.key_file, transport.key_file). Its path, never the key, goes on the command line of
/// brfd-substructure and brfd-rig; the spawned substructure writes its bad-message counts
/// to substructure-messages.json.

#include "common/process.h"
#include "server/run/run_config.h"
#include "server/run/substructure.h"

#include <map>
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

  /// Messages dropped on the run's links, by process and kind (summary.json "bad_messages"):
  /// "hybridsim" (this side) and, after finish(), "brfd-substructure" (its file; a spawned
  /// substructure only: one started by hand says its counts on its own stderr).
  std::map<std::string, std::map<std::string, long>> bad_messages() const;

 private:
  const RunConfig& config_;
  std::unique_ptr<Substructure> substructure_;
  LcmSubstructure* lcm_ = nullptr;
  ChildProcess substructure_process_, rig_process_;
  bool spawned_substructure_ = false, spawned_rig_ = false;
  std::string out_dir_;
  std::map<std::string, long> substructure_bad_messages_;
};

/// Writes `damper-model.yaml` into `out_dir` and starts the substructure process of the
/// config on it, with the config's URL and channel prefix. Child output goes to `log_path`.
/// Passes the key file (run_key_path), the bad-message policy and the results folder;
/// physical mode also writes `physical.yaml` (the rig block) and passes --mode physical.
ChildProcess spawn_substructure(const RunConfig& config, const std::string& out_dir,
                                const std::string& run_id, const std::string& log_path);

/// The HMAC key file of an LCM run (every message of both links): rig.key_file of a physical
/// run if given, else transport.key_file if given, else <out_dir>/run.key (written fresh by
/// SubstructureSession).
std::string run_key_path(const RunConfig& config, const std::string& out_dir);

/// Physical mode with `rig: launch: local`: starts brfd-rig (the lab-controller emulator) with
/// the config's rig.config, URL, channel prefix, run id and key; its logs go to out_dir.
ChildProcess spawn_rig(const RunConfig& config, const std::string& out_dir, const std::string& run_id,
                       const std::string& log_path);

/// True for a physical run whose rig emulator hybridsim starts itself.
bool launches_local_rig(const RunConfig& config);

}  // namespace server
