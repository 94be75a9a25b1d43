// `hybridsim batch worker` (batch.h: batch_worker_command): one run of a batch in its own
// network namespace, written to <label>.partial/ and renamed to <label>/ when durable.
#include "server/batch/batch.h"

#include "common/atomic_file.h"
#include "common/process.h"
#include "messages/lcm_bus.h"
#include "server/batch/batch_files.h"
#include "server/batch/driver.h"
#include "server/run/hybrid_run.h"
#include "server/run/substructure_session.h"
#include "server/run/run_config.h"
#include "structure/ground_motion.h"

#include <fcntl.h>
#include <stdio.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <iostream>
#include <nlohmann/json.hpp>

namespace server {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using nlohmann::json;
using batch_internal::fsync_path;
using batch_internal::unblock_stop_signals;
using batch_internal::utc_now;

int batch_worker_command(const BatchWorkerOptions& w) {
  unblock_stop_signals();  // blocked by the driver around fork/exec; a pending one kills us now
  const auto t0 = Clock::now();
  const fs::path partial = fs::path(w.runs_dir) / (w.label + ".partial");
  const fs::path final_path = fs::path(w.runs_dir) / w.label;
  fs::create_directories(partial);
  const std::string run_id = "batch-" + w.label + "-" + std::to_string(messages::now_utime()) + "-" +
                             std::to_string(getpid());

  RunConfig config;
  RunSummary summary;
  bool infra_failure = false;
  try {
    config = load_run_config(w.config);
  } catch (const std::exception& e) {
    std::cerr << "hybridsim batch worker: " << e.what() << "\n";
    summary.status = "failed";
    summary.error = e.what();
    infra_failure = true;
  }
  config.record.path = w.record;
  config.record.scale = w.scale;
  config.output.dir = partial.string();
  if (w.duration_s != 0.0) config.record.duration_s = w.duration_s;
  config.transport.channel_prefix = w.channel_prefix.empty() ? config.transport.channel_prefix : w.channel_prefix;
  if (!w.transport.empty()) config.transport.kind = w.transport;
  const bool in_process = config.transport.kind == "in_process";

  json info{{"label", w.label},          {"index", w.index},
            {"path", w.record},          {"scale", w.scale},
            {"duration_s", config.record.duration_s},
            {"run_id", run_id},          {"channel_prefix", config.transport.channel_prefix},
            {"transport", config.transport.kind},
            {"network_namespace", in_process ? "none (in_process)" : w.shared_netns ? "shared with the batch" : "own"},
            {"started_utc", utc_now()},  {"worker_pid", getpid()}};

  if (!infra_failure) {
    // The record: a bad one (or record.resample: exact against a step that does not divide
    // the record's) fails this run, with the reason.
    bool record_ok = true;
    std::string record_error;
    try {
      const double record_dt_s = structure::read_ground_motion(config.record.path, config.record.scale).dt_s;
      config.resampling_note = describe_resampling(record_dt_s, config.dt_s, config.record.resample).text;
      check_resampling(config, record_dt_s);
    } catch (const std::exception& e) {
      record_error = e.what();
    }
    std::ofstream(partial / "effective-config.yaml") << run_config_to_yaml(config);
    try {
      if (!record_error.empty()) throw std::runtime_error(record_error);
    } catch (const std::exception& e) {
      summary.status = "failed";
      summary.error = e.what();
      record_ok = false;
    }
    if (record_ok) {
      // The machinery: own network namespace, LCM, the substructure process.
      try {
        if (in_process) {
          // No LCM and no child process: nothing to isolate.
        } else if (!w.shared_netns) messages::enter_private_network_namespace();
        else if (!messages::in_private_network_namespace())
          throw messages::TransportError("--shared-netns: the batch is not in a private network namespace");
      } catch (const std::exception& e) {
        summary.status = "failed";
        summary.error = e.what();
        infra_failure = true;
      }
    }
    if (record_ok && !infra_failure) {
      std::error_code ec;
      info["netns"] = fs::read_symlink("/proc/self/ns/net", ec).string();
      try {
        // One factory for every transport (server/run/substructure_session.h).
        std::unique_ptr<SubstructureSession> session;
        try {
          session = std::make_unique<SubstructureSession>(config, partial.string(), run_id);
        } catch (const SubstructureSetupError&) {
          infra_failure = true;
          throw;
        }
        summary = run_hybrid(config, session->substructure(), run_id);
        for (const std::string& note : session->finish(summary.status == "ok"))
          std::cerr << "hybridsim batch worker: " << note << "\n";
        summary.bad_messages = session->bad_messages();
      } catch (const std::exception& e) {
        summary.status = "failed";
        summary.error = e.what();
      }
    }
  }

  info["status"] = summary.status;
  info["wall_s"] = std::chrono::duration<double>(Clock::now() - t0).count();
  info["finished_utc"] = utc_now();
  try {
    // Plain writes into <label>.partial/ (a full disk throws): the folder becomes a result only
    // by the rename below, after one sync of all its files, so no file needs its own
    // temporary name and fsync (each of those cost a journal commit; docs/batch.md).
    std::ostringstream info_text;
    info_text << std::setw(2) << info << "\n";
    common::write_file((partial / "batch-run.json").string(), info_text.str());
    common::write_file((partial / "summary.json").string(), summary_json_text(summary, config));
  } catch (const std::exception& e) {
    std::cerr << "hybridsim batch worker: cannot write results: " << e.what() << "\n";
    return kWorkerInfraFailed;
  }
  std::cout << format_summary(summary);
  if (infra_failure) {
    std::cerr << "hybridsim batch worker: " << summary.error << " (left in " << partial.string()
              << ", redone on resume)\n";
    return kWorkerInfraFailed;
  }
  // Durable, then visible: every file on disk before the rename makes the run final. A sync
  // that fails (a full disk showing at write-back) leaves the folder .partial: redone on resume.
  std::cout << std::flush;
  try {
    common::sync_folder_files(partial.string());
  } catch (const std::exception& e) {
    std::cerr << "hybridsim batch worker: " << e.what() << " (left in " << partial.string() << ", redone on resume)\n";
    return kWorkerInfraFailed;
  }
  // renameat2(RENAME_NOREPLACE): never replaces a finished result.
  if (::renameat2(AT_FDCWD, partial.c_str(), AT_FDCWD, final_path.c_str(), RENAME_NOREPLACE) != 0) {
    std::cerr << "hybridsim batch worker: cannot rename " << partial.string() << " to " << final_path.string()
              << ": " << std::strerror(errno) << "\n";
    return kWorkerInfraFailed;
  }
  fsync_path(w.runs_dir);
  return summary.status == "ok" ? kWorkerOk : kWorkerRunFailed;
}

}  // namespace server
