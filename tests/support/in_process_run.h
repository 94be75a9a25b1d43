#pragma once
// The real step loop (server::run_hybrid) with the damper models called in-process, set up
// from a building, a record file and one damper model, for tests that judge the loop against
// an independent reference (validation/: CVODE, closed forms, energy balance).
#include "server/run/hybrid_run.h"
#include "server/run/substructure_session.h"

#include <filesystem>
#include <stdexcept>
#include <string>
#include <unistd.h>

namespace testing_support {

inline server::RunConfig in_process_config(const structure::BuildingParams& building, const std::string& record_path,
                                           const damper::BrfdParams& damper, double dt_s, double duration_s) {
  server::RunConfig c;
  c.name = "in-process-check";
  c.dt_s = dt_s;
  c.record.path = record_path;
  c.record.duration_s = duration_s;
  c.building = building;
  c.damper_model = damper;
  c.transport.kind = "in_process";
  c.output.dir = (std::filesystem::temp_directory_path() /
                  ("hybridsim-in-process-" + std::to_string(getpid()))).string();
  return c;
}

/// Runs the config through run_hybrid (in-process substructure) and returns the history of
/// every committed step. Throws if the run did not finish.
inline structure::ResponseHistory run_in_process(const server::RunConfig& config) {
  server::SubstructureSession session(config, config.output.dir, config.name);
  structure::ResponseHistory history;
  const server::RunSummary s = server::run_hybrid(config, session.substructure(), config.name, &history);
  std::filesystem::remove_all(config.output.dir);
  if (s.status != "ok") throw std::runtime_error("in-process run failed: " + s.error);
  return history;
}

}  // namespace testing_support
