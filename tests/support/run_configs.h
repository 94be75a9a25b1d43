#pragma once
// Run configs for tests, made in code (issue 10, item 3): a shipped config read by the strict
// loader (server::load_run_config), the fields a test needs changed on the RunConfig struct,
// and the file written by the one serializer (server::run_config_to_yaml, full precision).
// No test edits valid YAML text; only error tests break the written text on purpose.
// Needs the test target to link server_run.
#include "damper/model/brfd_config.h"
#include "run_process.h"
#include "server/run/run_config.h"
#include "test_paths.h"

#include <string>

namespace test_support {

/// configs/<file> as `hybridsim run` reads it (relative paths resolved against configs/).
inline server::RunConfig shipped_run_config(const std::string& file) {
  return server::load_run_config(test_paths::source_dir() + "/configs/" + file);
}

/// The damper of `c` becomes the model of configs/<damper_file> (e.g. brfd-default.yaml, the
/// LuGre model identified on the passive tests), as `damper.model_config: <that file>` loads it.
inline void use_damper_config(server::RunConfig& c, const std::string& damper_file) {
  c.damper.model_config = test_paths::source_dir() + "/configs/" + damper_file;
  c.damper_model = damper::load_brfd_params(c.damper.model_config);
}

/// configs/three-story.yaml made short for a test: `duration_s` of shaking, the LuGre damper of
/// configs/brfd-default.yaml, results in `results_dir`, and (if not "") another record.
inline server::RunConfig short_three_story(double duration_s, const std::string& results_dir,
                                           const std::string& record_path = "") {
  server::RunConfig c = shipped_run_config("three-story.yaml");
  use_damper_config(c, "brfd-default.yaml");
  c.record.duration_s = duration_s;
  if (!record_path.empty()) c.record.path = record_path;
  c.output.dir = results_dir;
  return c;
}

/// Writes `c` to `path` with server::run_config_to_yaml (creating the folder); returns `path`.
inline std::string write_run_config(const std::string& path, const server::RunConfig& c) {
  write_text(path, server::run_config_to_yaml(c));
  return path;
}

}  // namespace test_support
