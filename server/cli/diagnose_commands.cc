#include "server/cli/diagnose_commands.h"
#include "server/cli/guarded.h"

#include "common/run_guard.h"
#include "common/strict_yaml.h"
#include "damper/data/brfd_data.h"
#include "damper/diagnose/diagnose.h"
#include "damper/diagnose/diagnose_bench.h"

#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

namespace {

// --fit-rate: 0 (the records' own rate) or a rate in [16, 100000] Hz.
std::string fit_rate_check(const std::string& text) {
  double hz = -1.0;
  try {
    hz = std::stod(text);
  } catch (const std::exception&) {
    return "'" + text + "' is not a number";
  }
  if (hz == 0.0 || (hz >= 16.0 && hz <= 100000.0)) return "";
  return text + " Hz must be 0 (the records' own rate) or in [16, 100000]";
}

}  // namespace

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
      "residual force in regimes and time windows, test it against its noise floor, fit the candidate effects of "
      "the library and the model without them by the same procedure, score them on unseen data (leave-one-record-"
      "out, or held-out cycles), add an effect only if it helps on nearly every held-out part, in its own regimes "
      "and in >= 80% of bootstrap resamples, and write out/model-updated.yaml. Line before the last: confidence; "
      "last line: effects=<names or none> nrmse_before=<mean> nrmse_after=<mean> nrmse_after_max=<max>. "
      "`diagnose bench`: the hidden-effect benchmark.");
  cmd->add_option("--model", o.model_path, "damper model config YAML (e.g. configs/brfd-semiactive.yaml)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--measured", o.measured,
                  "measured records: BRFD test JSON files, folders of them, or a recorded physical run "
                  "(physical.csv or its run folder)")
      ->expected(1, -1);
  cmd->add_option("--out", o.out_dir, "output folder (model-updated.yaml, report.txt, CSVs, figures)");
  cmd->add_option("--base", a->base,
                  "base LuGre parameters: 'identify' on each record's passive window (before the actuators first "
                  "move; default) or 'model' (the --model file as is)")
      ->check(CLI::IsMember({"identify", "model"}))->capture_default_str();
  cmd->add_option("--effects", o.candidates, "candidate effects to consider (default: the whole library)")->expected(1, -1);
  cmd->add_option("--max-effects", o.max_effects, "add at most this many effects")->check(CLI::Range(0, 8))->capture_default_str();
  cmd->add_option("--min-improvement", o.min_improvement,
                  "a candidate must remove at least this share of the held-out mean square residual")
      ->check(CLI::Range(0.0, 1.0))->capture_default_str();
  cmd->add_option("--min-excess-share", o.min_excess_share,
                  "... and at least this share of the residual above the noise floor")
      ->check(CLI::Range(0.0, 1.0))->capture_default_str();
  cmd->add_option("--consistency", o.consistency, "... improve at least this share of the held-out parts it changes")
      ->check(CLI::Range(0.0, 1.0))->capture_default_str();
  cmd->add_option("--confidence", o.confidence, "... and be chosen in at least this share of bootstrap resamples")
      ->check(CLI::Range(0.0, 1.0))->capture_default_str();
  cmd->add_option("--min-explained-share", o.min_explained_share,
                  "the winner is named only when it removes at least this share of the held-out residual above the "
                  "noise floor (else: something is missing that no library effect explains)")
      ->check(CLI::Range(0.0, 1.0))->capture_default_str();
  cmd->add_option("--resamples", o.resamples, "bootstrap resamples per round")->check(CLI::Range(1, 100000))->capture_default_str();
  cmd->add_option("--effect-evals", o.effect_evals, "LN_BOBYQA evaluations per start of an effect fit")
      ->check(CLI::Range(5, 100000))->capture_default_str();
  cmd->add_option("--fit-rate", o.fit_rate_hz,
                  "effect fits and scores on records decimated to at least this rate, Hz (0: the records' own "
                  "rate, nothing decimated; the record's own rate if lower; before/after always at the full rate)")
      ->check(fit_rate_check)
      ->capture_default_str();
  cmd->add_option("--fit-iterations", o.fit_iterations, "alternations effect step / base step per fit")
      ->check(CLI::Range(1, 10))->capture_default_str();
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
  cmd->add_option("--threads", o.threads,
                  "threads for the candidate fits of a round (0: the machine's hardware threads; the verdict does not "
                  "depend on it)")
      ->check(CLI::Range(0, 1024))->capture_default_str();
  cmd->add_flag("--no-figures", a->no_figures, "do not run gnuplot");
  // `diagnose bench`: the hidden-effect benchmark (damper/diagnose_bench.h).
  struct BenchArgs {
    damper::BenchOptions o;
  };
  auto b = std::make_shared<BenchArgs>();
  CLI::App* bench = cmd->add_subcommand(
      "bench",
      "Hidden-effect benchmark of diagnose with its own generator: every library effect x seeds x 2 noise levels x "
      "2 strengths, shapes that are not library formulas, and 'none' cases from the exact base model. Prints a "
      "confusion matrix and ends with trials=<n> correct=<n> wrong=<n> false_positive=<n>");
  bench->add_flag("--quick", b->o.quick, "the CI subset (one seed, one noise level, strong effects)");
  bench->add_option("--seeds", b->o.seeds, "seeds per case and noise level")->check(CLI::Range(1, 100))->capture_default_str();
  bench->add_option("--only", b->o.only, "run only cases whose name starts with one of these (e.g. backlash own:)");
  bench->add_option("--out", b->o.out_dir, "folder for bench.csv");
  bench->add_option("--effect-evals", b->o.effect_evals, "diagnose's LN_BOBYQA evaluations per start of an effect fit")
      ->check(CLI::Range(5, 100000))->capture_default_str();
  bench->add_option("--threads", b->o.threads, "diagnose's fit threads (0: the machine's hardware threads)")
      ->check(CLI::Range(0, 1024))->capture_default_str();
  bench->add_flag("--hidden-shapes", b->o.hidden_shapes,
                  "also run the shapes of damper/synthetic (written blind by another author)");
  bench->add_flag("--only-hidden-shapes", b->o.only_hidden_shapes, "run only the shapes of damper/synthetic");
  bench->add_option("--fit-rate", b->o.fit_rate_hz,
                    "diagnose's fit rate, Hz (0: the records' own rate, no decimation, as diagnose's default)")
      ->check(fit_rate_check)
      ->capture_default_str();
  bench->add_option("--hidden-motion", b->o.hidden_motion,
                    "drum motion of the damper/synthetic records: harmonic (the paper's tests 1 and 4) or earthquake "
                    "(two broadband records per trial)")
      ->check(CLI::IsMember({"harmonic", "earthquake"}));
  bench->add_option("--base", b->o.base,
                    "model: diagnose from the exact base (the default); identify: every case as a user runs diagnose, "
                    "each record's base identified on its passive window")
      ->check(CLI::IsMember({"model", "identify"}))->capture_default_str();
  bench->add_flag("--verbose", b->o.verbose, "print each trial's diagnose report");
  bench->callback([b, cmd]() {
    damper::BenchOptions bo = b->o;
    bo.log = [](const std::string& s) { std::cout << s << std::endl; };
    (void)cmd;
    damper::run_diagnose_bench(bo);
  });
  cmd->callback([a, cmd]() {
    if (cmd->got_subcommand("bench")) return;
    if (a->o.model_path.empty() || a->o.measured.empty() || a->o.out_dir.empty()) {
      std::cerr << "error: diagnose needs --model, --measured and --out (or the subcommand bench)" << std::endl;
      throw CLI::RuntimeError(2);
    }
    guarded([&] {
      damper::DiagnoseOptions opt = a->o;
      opt.base = a->base == "model" ? damper::BaseSource::model : damper::BaseSource::identify;
      opt.figures = !a->no_figures;
      opt.log = [](const std::string& s) { std::cout << s << "\n"; };
      const damper::DiagnoseResult r = damper::run_diagnose(opt);
      std::cout << damper::diagnose_confidence_line(r) << "\n" << damper::diagnose_final_line(r) << std::endl;
    });
  });
}
