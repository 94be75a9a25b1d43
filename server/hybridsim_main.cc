// hybridsim: the hybrid-simulation server. Subcommands:
//   run --config FILE        one hybrid run (server/hybrid_run.h)
//   bench                    LCM and step round trips, in-process speed (server/bench.h)
//   damper ...               damper model tools (server/commands/damper_commands.h)
//   batch ...                many records (server/commands/batch_commands.h)
//   diagnose ...             model-discrepancy workflow (server/commands/diagnose_commands.h)
// Each command group lives in server/commands/<group>_commands.cc; CMake compiles in the
// groups that exist and defines HYBRIDSIM_HAS_<GROUP>.
#include "server/bench.h"
#include "server/hybrid_run.h"
#ifdef HYBRIDSIM_HAS_DAMPER
#include "server/commands/damper_commands.h"
#endif
#ifdef HYBRIDSIM_HAS_BATCH
#include "server/commands/batch_commands.h"
#endif
#ifdef HYBRIDSIM_HAS_DIAGNOSE
#include "server/commands/diagnose_commands.h"
#endif

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

  server::BenchOptions bench_options;
  CLI::App* bench = app.add_subcommand("bench", "print LCM and hybrid-step round trips and in-process speed");
  bench->add_option("--three-story", bench_options.three_story_config, "3-story config");
  bench->add_option("--ten-story", bench_options.ten_story_config, "10-story config");
  bench->add_option("--round-trips", bench_options.round_trips, "LCM round trips to time");

#ifdef HYBRIDSIM_HAS_DAMPER
  add_damper_commands(app);
#endif
#ifdef HYBRIDSIM_HAS_BATCH
  add_batch_commands(app);
#endif
#ifdef HYBRIDSIM_HAS_DIAGNOSE
  add_diagnose_commands(app);
#endif

  int code = 0;
  run->callback([&] { code = server::run_command(config_path, out_dir, quiet); });
  bench->callback([&] { code = server::bench_command(bench_options); });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "hybridsim: " << e.what() << "\n";
    return 2;
  }
  return code;
}
