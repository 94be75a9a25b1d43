#include "server/cli/damper_commands.h"
#include "server/cli/guarded.h"

#include "common/run_guard.h"
#include "common/strict_yaml.h"
#include "damper/model/brfd_config.h"
#include "damper/data/brfd_data.h"
#include "damper/fit/identification.h"
#include "damper/fit/predict.h"
#include "damper/fit/relationships.h"
#include "damper/fit/validate.h"

#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace {

std::pair<double, double> parse_window(const std::string& text) {
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos)
    throw CLI::ValidationError("--fit-window", "expected T0:T1 in seconds, got '" + text + "'");
  try {
    std::size_t used0 = 0, used1 = 0;
    const std::string a = text.substr(0, colon), b = text.substr(colon + 1);
    const double t0 = std::stod(a, &used0), t1 = std::stod(b, &used1);
    if (used0 != a.size() || used1 != b.size()) throw std::invalid_argument(text);
    if (!(t1 > t0)) throw CLI::ValidationError("--fit-window", "T1 must be greater than T0");
    return {t0, t1};
  } catch (const std::logic_error&) {
    throw CLI::ValidationError("--fit-window", "expected T0:T1 in seconds, got '" + text + "'");
  }
}


}  // namespace

void add_damper_commands(CLI::App& app) {
  CLI::App* damper = app.add_subcommand("damper", "BRFD damper model tools (predict, identify, relationships, validate)");
  damper->require_subcommand(1);

  // --- predict -------------------------------------------------------------------------
  struct PredictArgs {
    std::string config, test, window, out;
    bool no_fit = false, no_figure = false;
  };
  auto pa = std::make_shared<PredictArgs>();
  CLI::App* predict = damper->add_subcommand(
      "predict",
      "Replay a measured test through the BRFD model (LuGre parameters and b identified on the "
      "test's drum cycles before the electric actuators first move) and report the error. "
      "Last line: nrmse=<RMSE/std> rmse_kip=<RMSE> nrmse_range=<RMSE/(max-min)>");
  predict->add_option("--config", pa->config, "damper config YAML (e.g. configs/brfd-semiactive.yaml)")
      ->required()->check(CLI::ExistingFile);
  predict->add_option("--test", pa->test, "measured test, JSON (e.g. .../semiactive/harmonic0.015forward.json)")
      ->required()->check(CLI::ExistingFile);
  CLI::Option* window = predict->add_option("--fit-window", pa->window,
                                            "identification window T0:T1 in s (default: before the first actuator motion)");
  predict->add_flag("--no-fit", pa->no_fit, "use the config's parameters as they are")->excludes(window);
  predict->add_option("--out", pa->out, "output directory for the CSV, PNG and effective config");
  predict->add_flag("--no-figure", pa->no_figure, "do not run gnuplot");
  predict->callback([pa]() {
    guarded([&]() {
      damper::PredictOptions o;
      o.config_path = pa->config;
      o.test_path = pa->test;
      o.fit = !pa->no_fit;
      if (!pa->window.empty()) o.fit_window_s = parse_window(pa->window);
      o.out_dir = pa->out;
      o.figure = !pa->no_figure;
      o.log = [](const std::string& s) { std::cout << s << "\n"; };
      const damper::PredictResult r = damper::run_predict(o);
      std::cout << damper::metrics_line(r.metrics) << std::endl;
    });
  });

  // --- identify ------------------------------------------------------------------------
  struct IdentifyArgs {
    std::string config, test, window;
  };
  auto ia = std::make_shared<IdentifyArgs>();
  CLI::App* identify = damper->add_subcommand(
      "identify", "Identify the LuGre parameters (sigma0, sigma1, sigma2, Fc=b and Fs per "
                  "direction, v_s) on passive data and print them as a config");
  identify->add_option("--config", ia->config, "starting damper config YAML")->check(CLI::ExistingFile);
  identify->add_option("--test", ia->test, "passive test JSON (characterization, or semi-active with --window)")
      ->required()->check(CLI::ExistingFile);
  identify->add_option("--window", ia->window,
                       "T0:T1 in s (default: whole test, or before the first actuator motion)");
  identify->callback([ia]() {
    guarded([&]() {
      damper::BrfdParams start = ia->config.empty() ? damper::BrfdParams{} : damper::load_brfd_params(ia->config);
      const damper::BrfdTest test = damper::read_brfd_test(ia->test);
      for (const std::string& n : test.notes) std::cout << n << "\n";
      damper::IdentificationOptions io;
      if (!ia->window.empty()) {
        const auto w = parse_window(ia->window);
        io.t0_s = w.first;
        io.t1_s = w.second;
      } else if (const auto first = damper::first_actuator_motion_s(test, 0.002)) {
        io.t1_s = *first;
      }
      if (test.has_actuator_positions) {
        start.semiactive.actuator1_initial_in = test.actuator1_in[0];
        start.semiactive.actuator2_initial_in = test.actuator2_in[0];
      }
      const damper::IdentificationResult r = damper::identify_lugre(test, start, io);
      std::cout << damper::describe(r) << "\n# effective config:\n"
                << damper::brfd_params_to_yaml(r.params);
    });
  });

  // --- relationships -------------------------------------------------------------------
  auto data_dir = std::make_shared<std::string>();
  CLI::App* rel = damper->add_subcommand(
      "relationships",
      "Re-derive the scaling factors C1..C4 (friction vs actuator force slopes, taut and slack) "
      "and the force amplification factors from the characterization data, beside Table 2, and "
      "the amplification increase of actuated cycles in the semi-active tests");
  rel->add_option("--data", *data_dir, "BRFD data directory (holding characterization/ and semiactive/)")
      ->required()->check(CLI::ExistingDirectory);
  rel->callback([data_dir]() {
    guarded([&]() {
      const damper::RelationshipsReport r = damper::derive_relationships(*data_dir, {});
      std::cout << damper::format_relationships(r);
    });
  });

  // --- validate ------------------------------------------------------------------------
  struct ValidateArgs {
    std::string config, out;
    bool no_figure = false;
  };
  auto va = std::make_shared<ValidateArgs>();
  CLI::App* val = damper->add_subcommand(
      "validate",
      "One table, model x test (paper_semiactive LuGre vs band_brake): semi-active tests "
      "(RMSE/std, identified on their passive cycles), earthquake tests and held-out "
      "characterization tests (identified on characterization data only; NRMSE(range) and "
      "RMSE/std, whole and strong-motion window), actuator load cells; a PNG per test");
  val->add_option("--config", va->config, "validation config YAML (configs/brfd-validate.yaml)")
      ->required()->check(CLI::ExistingFile);
  val->add_option("--out", va->out, "output directory (overrides out_dir of the config)");
  val->add_flag("--no-figure", va->no_figure, "do not run gnuplot");
  val->callback([va]() {
    guarded([&]() {
      damper::ValidationConfig c = damper::load_validation_config(va->config);
      if (!va->out.empty()) c.out_dir = va->out;
      if (va->no_figure) c.figures = false;
      const damper::ValidationResult r =
          damper::run_validation(c, [](const std::string& line) { std::cerr << line << std::endl; });
      for (const std::string& w : r.warnings) std::cerr << "warning: " << w << std::endl;
      for (const std::string& png : r.png_paths) std::cerr << "wrote " << png << std::endl;
      std::cout << damper::format_validation_table(r) << std::flush;
    });
  });
}
