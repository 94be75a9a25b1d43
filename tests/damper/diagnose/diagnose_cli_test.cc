// `hybridsim diagnose` as a user runs it: a synthetic record with hidden backlash, the model
// without it; the last line, the updated config (loads with the damper loader and holds the
// effect), the report and the figures; a bad data file gives exit code 1 and a clear message.
#include "damper/diagnose/diagnose_bench.h"
#include "damper/model/brfd_config.h"
#include "run_configs.h"
#include "run_process.h"
#include "synthetic.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <regex>

namespace {

using test_support::fresh_temp_dir;
using test_support::read_text;
using test_support::run_process;
using test_support::write_text;

// Two records with hidden backlash, diagnosed from the model without it by the default path (bases
// identified on the passive windows), against its closest confusable (residual_static; the whole
// library runs in the benchmark), with 150 evaluations per start (at the
// default 60 the 4-parameter backlash fit improves 12 of the 14 held-out parts, confidence 0.62). The written model-updated.yaml reproduces the printed
// "after" NRMSE of each record with `hybridsim damper predict` (the command named in the file).
TEST(DiagnoseCli, NamesHiddenBacklashAndTheWrittenModelReproducesTheReport) {
  const std::string dir = fresh_temp_dir("diagnose_cli");
  const damper::BrfdParams base = damper::bench_base_model();
  write_text(dir + "/model.yaml", damper::brfd_params_to_yaml(base));
  damper::BrfdParams truth = base;
  truth.effects.backlash = damper::BacklashEffect{0.06, 0.0, 1.0};
  std::vector<std::string> files;
  unsigned seed = 21;
  for (damper::BrfdTest t : damper::bench_drives(base, 256.0)) {
    damper::BrfdParams p = truth;
    p.semiactive.actuator1_initial_in = t.actuator1_in[0];
    p.semiactive.actuator2_initial_in = t.actuator2_in[0];
    damper::BrfdModel m(p);
    std::mt19937 rng(seed++);
    std::normal_distribution<double> noise(0.0, 0.03);
    for (std::size_t i = 0; i < t.size(); ++i) {
      const damper::DamperInput in{t.drum_disp_in[i], t.drum_vel_in_per_s[i], t.actuator1_in[i], t.actuator2_in[i]};
      t.force_kip.push_back((i == 0 ? m.force_kip(0.0, in) : m.step(in, t.dt_s)) + noise(rng));
    }
    files.push_back(dir + "/" + std::filesystem::path(t.path).filename().string());
    diagnose_test::write_json(t, files.back());
  }
  const auto r = run_process({test_paths::bin_dir() + "/hybridsim", "diagnose", "--model", dir + "/model.yaml",
                              "--measured", files[0], files[1], "--effects", "backlash", "residual_static",
                              "--effect-evals", "150", "--out", dir + "/out"});
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const std::regex last(
      "confidence: backlash=[0-9.]+ [^\n]*\neffects=backlash nrmse_before=[0-9.e-]+ nrmse_after=[0-9.e-]+ "
      "nrmse_after_max=[0-9.e-]+\n$");
  EXPECT_TRUE(std::regex_search(r.out, last)) << r.out;
  EXPECT_NE(r.out.find("== Where the model disagrees"), std::string::npos);
  EXPECT_NE(r.out.find("validation: leave-one-record-out over 2 records"), std::string::npos);
  EXPECT_NE(r.out.find("added backlash"), std::string::npos);
  const std::string yaml = read_text(dir + "/out/model-updated.yaml");
  const damper::BrfdParams updated = damper::load_brfd_params(dir + "/out/model-updated.yaml");
  ASSERT_TRUE(updated.effects.backlash.has_value());
  EXPECT_NEAR(updated.effects.backlash->slack_in, 0.06, 0.02);
  EXPECT_NE(yaml.find("re-identified on its passive window"), std::string::npos) << yaml;
  // The file names the predict command per record and the NRMSE it must give.
  for (const std::string& f : files) {
    std::smatch m;
    ASSERT_TRUE(std::regex_search(yaml, m, std::regex("--test " + f + " *# nrmse=([0-9.]+)"))) << yaml;
    const double printed = std::stod(m[1].str());
    const auto p = run_process({test_paths::bin_dir() + "/hybridsim", "damper", "predict", "--config",
                                dir + "/out/model-updated.yaml", "--test", f});
    ASSERT_EQ(p.exit_code, 0) << p.err << p.out;
    std::smatch q;
    ASSERT_TRUE(std::regex_search(p.out, q, std::regex("(^|\\n)nrmse=([0-9.e-]+) rmse_kip=[^\\n]*\\n?$"))) << p.out;
    EXPECT_NEAR(std::stod(q[2].str()), printed, 1e-4) << f;  // the file prints 4 decimals
  }
  EXPECT_FALSE(read_text(dir + "/out/report.txt").empty());
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/gap.png"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/records/driveA.png"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/candidates.csv"));
}

// `hybridsim diagnose bench` runs (one case) and ends with its summary line.
TEST(DiagnoseCli, BenchPrintsItsSummaryLine) {
  const auto r = run_process({test_paths::bin_dir() + "/hybridsim", "diagnose", "bench", "--quick", "--only", "none/"});
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("confusion matrix"), std::string::npos) << r.out;
  EXPECT_TRUE(std::regex_search(r.out, std::regex("trials=1 correct=1 wrong=0 false_positive=0\n$"))) << r.out;
}

// Issue 11 item 7 on the shipped result: configs/brfd-diagnosed-semiactive.yaml is diagnose's
// model-updated.yaml for the six semi-active tests; the `damper predict` command it lists for a record
// gives the NRMSE it states (the per-record "after" diagnose printed). Two records (CI time).
TEST(DiagnoseCli, ShippedDiagnosedConfigReproducesItsStatedNrmse) {
  if (!test_paths::have_shared()) GTEST_SKIP() << test_paths::shared_dir() << " is absent: real records not replayed";
  const std::string config = test_paths::source_dir() + "/configs/brfd-diagnosed-semiactive.yaml";
  const std::string yaml = read_text(config);
  const std::regex line("damper predict --config model-updated\\.yaml --test ([^ \n]+)( --fit-window [0-9.:]+)? +# nrmse=([0-9.]+)");
  int checked = 0;
  for (auto it = std::sregex_iterator(yaml.begin(), yaml.end(), line); it != std::sregex_iterator() && checked < 2;
       ++it, ++checked) {
    const std::string record =
        test_paths::shared_dir() + "/data/brfd/semiactive/" + std::filesystem::path((*it)[1].str()).filename().string();
    std::vector<std::string> args{test_paths::bin_dir() + "/hybridsim", "damper", "predict", "--config", config,
                                  "--test", record};
    if ((*it)[2].matched) {
      args.push_back("--fit-window");
      args.push_back((*it)[2].str().substr(std::string(" --fit-window ").size()));
    }
    const auto p = run_process(args);
    ASSERT_EQ(p.exit_code, 0) << p.err << p.out;
    std::smatch q;
    ASSERT_TRUE(std::regex_search(p.out, q, std::regex("(^|\\n)nrmse=([0-9.e-]+) rmse_kip=[^\\n]*\\n?$"))) << p.out;
    EXPECT_NEAR(std::stod(q[2].str()), std::stod((*it)[3].str()), 1e-4) << record;  // 4 decimals in the file
  }
  EXPECT_EQ(checked, 2) << "the config lists no per-record predict commands:\n" << yaml;
}

TEST(DiagnoseCli, BadDataIsAUserError) {
  const std::string dir = fresh_temp_dir("diagnose_cli_bad");
  write_text(dir + "/model.yaml", damper::brfd_params_to_yaml(diagnose_test::synthetic_base()));
  write_text(dir + "/broken.json", "{\"dt\": 0.001, \"data\": [[0, 1, 2]]}");
  const auto r = run_process({test_paths::bin_dir() + "/hybridsim", "diagnose", "--model", dir + "/model.yaml",
                              "--measured", dir + "/broken.json", "--out", dir + "/out"});
  EXPECT_EQ(r.exit_code, 2);  // bad input (README "Exit codes")
  EXPECT_NE(r.err.find("error: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("broken.json"), std::string::npos) << r.err;

  // A fit rate that is neither 0 (the records' own rate) nor in [16, 100000] Hz is named.
  const auto rate = run_process({test_paths::bin_dir() + "/hybridsim", "diagnose", "--model", dir + "/model.yaml",
                                 "--measured", dir + "/broken.json", "--out", dir + "/out", "--fit-rate", "5"});
  EXPECT_NE(rate.exit_code, 0);
  EXPECT_NE(rate.err.find("--fit-rate: 5 Hz must be 0"), std::string::npos) << rate.err;
}

}  // namespace

namespace {

// The shipped diagnosed config, with effects switched on, drives a hybrid run: hybridsim spawns
// brfd-substructure, whose virtual damper steps the extended model (2 s of El Centro over LCM). The
// diagnosed config holds pretension (with wear) and self_energizing (with the self-servo); the test
// adds backlash with re-tensioning and release, transition_shape and the velocity effect with its
// slip memory to exercise the rest of the extended model in the substructure.
TEST(DiagnoseCli, ShippedDiagnosedConfigRunsInAHybridRun) {
  const std::string dir = fresh_temp_dir("diagnose_cli_run");
  damper::BrfdParams model = damper::load_brfd_params(test_paths::source_dir() + "/configs/brfd-diagnosed-semiactive.yaml");
  // As shipped it holds pretension and self_energizing (with the self-servo); the others are added.
  ASSERT_TRUE(model.effects.pretension && model.effects.self_energizing) << "the diagnosed config changed: update this test";
  model.effects.backlash = damper::BacklashEffect{0.04, 0.02, 1.0, 3.0};
  model.effects.velocity = damper::VelocityEffect{2.0, 0.0, 0.0, -0.05, 1.0, 0.05};
  model.effects.transition_shape = damper::TransitionShapeEffect{3.0};
  write_text(dir + "/model.yaml", damper::brfd_params_to_yaml(model));
  server::RunConfig run = test_support::short_three_story(2.0, dir + "/results");
  run.damper.model_config = dir + "/model.yaml";
  run.damper_model = damper::load_brfd_params(run.damper.model_config);
  test_support::write_run_config(dir + "/run.yaml", run);
  const auto r = run_process({test_paths::bin_dir() + "/hybridsim", "run", "--config", dir + "/run.yaml"});
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const std::string used = read_text(dir + "/results/damper-model.yaml");
  EXPECT_NE(used.find("transition_shape:"), std::string::npos) << used;
  EXPECT_NE(used.find("release_ratio: 3"), std::string::npos) << used;
  EXPECT_NE(used.find("memory_in: 0.05"), std::string::npos) << used;
  EXPECT_NE(used.find("band_force_share:"), std::string::npos) << used;
  EXPECT_NE(used.find("wear_per_kip_in:"), std::string::npos) << used;
  const std::smatch m = [&] {
    std::smatch x;
    std::regex_search(r.out, x, std::regex("damper 1: peak force ([0-9.]+) kip"));
    return x;
  }();
  ASSERT_EQ(m.size(), 2u) << r.out;
  const double peak = std::stod(m[1].str());
  EXPECT_GT(peak, 0.5);
  EXPECT_LT(peak, 10.0);
}

}  // namespace
