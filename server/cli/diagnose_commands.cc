#include "server/cli/diagnose_commands.h"

#include "damper/diagnose/diagnose.h"

#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

void add_diagnose_commands(CLI::App& app) {
  struct Args {
    damper::DiagnoseOptions o;  // defaults of the workflow
    std::string base = "identify";
    bool no_figures = false;
  };
  auto a = std::make_shared<Args>();
  damper::DiagnoseOptions& o = a->o;
  CLI::App* cmd = app.add_subcommand(
      "diagnose",
      "Find what the BRFD model misses on measured data: simulate it with the measured inputs, localize the "
      "residual force in regimes and time windows, fit candidate effects (backlash, residual_static, "
      "actuator_lag, asymmetry, velocity, pretension) on training drum cycles, score them on held-out cycles "
      "(RMSE, dBIC), add the winners greedily and write out/model-updated.yaml. Last line: effects=<names or "
      "none> nrmse_before=<mean> nrmse_after=<mean> nrmse_after_max=<max>");
  cmd->add_option("--model", o.model_path, "damper model config YAML (e.g. configs/brfd-semiactive.yaml)")
      ->required()->check(CLI::ExistingFile);
  cmd->add_option("--measured", o.measured,
                  "measured records: BRFD test JSON files, folders of them, or a recorded physical run "
                  "(physical.csv or its run folder)")
      ->required()->expected(1, -1);
  cmd->add_option("--out", o.out_dir, "output folder (model-updated.yaml, report.txt, CSVs, figures)")->required();
  cmd->add_option("--base", a->base,
                  "base LuGre parameters: 'identify' on each record's passive window (before the actuators first "
                  "move; default) or 'model' (the --model file as is)")
      ->check(CLI::IsMember({"identify", "model"}))->capture_default_str();
  cmd->add_option("--effects", o.candidates, "candidate effects to consider (default: the whole library)")->expected(1, -1);
  cmd->add_option("--max-effects", o.max_effects, "add at most this many effects")->check(CLI::Range(0, 7))->capture_default_str();
  cmd->add_option("--min-improvement", o.min_improvement,
                  "a candidate must lower the held-out RMSE by at least this fraction")
      ->check(CLI::Range(0.0, 1.0))->capture_default_str();
  cmd->add_option("--bic-threshold", o.bic_threshold, "... and have dBIC at most this")->capture_default_str();
  cmd->add_option("--effect-evals", o.effect_evals, "LN_BOBYQA evaluations per start of an effect fit")
      ->check(CLI::Range(5, 100000))->capture_default_str();
  cmd->add_option("--base-global-evals", o.base_identification.global_max_evals,
                  "GN_CRS2_LM evaluations per run of the first base identification (0: local only)")
      ->check(CLI::Range(0, 1000000))->capture_default_str();
  cmd->add_option("--base-global-runs", o.base_identification.global_runs, "GN_CRS2_LM runs of the first base identification")
      ->check(CLI::Range(0, 20))->capture_default_str();
  cmd->add_option("--base-local-evals", o.base_identification.local_max_evals,
                  "LN_BOBYQA evaluations of the first base identification")
      ->check(CLI::Range(1, 1000000))->capture_default_str();
  cmd->add_option("--base-refit-evals", o.base_refit_evals,
                  "LN_BOBYQA evaluations of each re-identification of the base with trial effects")
      ->check(CLI::Range(1, 1000000))->capture_default_str();
  cmd->add_flag("--no-figures", a->no_figures, "do not run gnuplot");
  cmd->callback([a]() {
    try {
      damper::DiagnoseOptions opt = a->o;
      opt.base = a->base == "model" ? damper::BaseSource::model : damper::BaseSource::identify;
      opt.figures = !a->no_figures;
      opt.log = [](const std::string& s) { std::cout << s << "\n"; };
      const damper::DiagnoseResult r = damper::run_diagnose(opt);
      std::cout << damper::diagnose_final_line(r) << std::endl;
    } catch (const CLI::Error&) {
      throw;
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << std::endl;
      throw CLI::RuntimeError(1);
    }
  });
}
