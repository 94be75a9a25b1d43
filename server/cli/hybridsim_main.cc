// hybridsim: the hybrid-simulation server. Subcommands:
//   run --config FILE        one hybrid run (server/run/hybrid_run.h)
//   bench                    LCM and step round trips, in-process speed (server/run/bench.h)
//   damper ...               damper model tools (server/cli/damper_commands.h)
//   batch ...                many records (server/cli/batch_commands.h)
//   ida ...                  incremental dynamic analysis, fragility (server/cli/ida_commands.h)
//   diagnose ...             model-discrepancy workflow (server/cli/diagnose_commands.h)
// Each command group lives in server/cli/<group>_commands.cc.
#include "server/run/bench.h"
#include "server/run/hybrid_run.h"
#include "server/cli/damper_commands.h"
#include "server/cli/batch_commands.h"
#include "server/cli/ida_commands.h"
#include "server/cli/diagnose_commands.h"

#include "common/run_guard.h"

#include <CLI/CLI.hpp>

#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"hybridsim: real-time hybrid simulation of shear buildings with a BRFD damper (units kip, in, s)"};
  app.require_subcommand(1);

  std::string config_path;
  std::string out_dir;
  bool quiet = false;
  CLI::App* run = app.add_subcommand("run", "run one hybrid simulation from a config");
  run->add_option("--config", config_path, "run config YAML (e.g. configs/three-story.yaml)")->required();
  run->add_option("--out", out_dir, "results folder (overrides output.dir)");
  run->add_flag("--quiet", quiet, "print only the results folder");
  double run_duration_s = 0.0;
  run->add_option("--duration", run_duration_s, "simulate only the first S seconds of the record (overrides record.duration_s)")
      ->check(CLI::PositiveNumber);

  server::BenchOptions bench_options;
  CLI::App* bench = app.add_subcommand("bench", "print LCM and hybrid-step round trips and in-process speed");
  bench->add_option("--three-story", bench_options.three_story_config, "3-story config");
  bench->add_option("--ten-story", bench_options.ten_story_config, "10-story config");
  bench->add_option("--round-trips", bench_options.round_trips, "LCM round trips to time");

  add_damper_commands(app);
  add_batch_commands(app);
  add_ida_commands(app);
  add_diagnose_commands(app);

  int code = 0;
  run->callback([&] { code = server::run_command(config_path, out_dir, quiet, run_duration_s); });
  bench->callback([&] { code = server::bench_command(bench_options); });
  // Exit codes (README "Exit codes", common/run_guard.h): 0 ok, 1 run failed, 2 bad input
  // (a command-line error included), 130/143 interrupted by SIGINT/SIGTERM.
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {  // a command's own exit code (0, 1, 2, 130, 143)
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);  // prints the message (or the help)
    return rc == 0 ? common::kExitOk : common::kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "hybridsim: " << e.what() << "\n";
    return common::kExitBadInput;
  }
  return code;
}
