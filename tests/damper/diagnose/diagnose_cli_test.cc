// `hybridsim diagnose` as a user runs it: a synthetic record with hidden backlash, the model
// without it; the last line, the updated config (loads with the damper loader and holds the
// effect), the report and the figures; a bad data file gives exit code 1 and a clear message.
#include "damper/model/brfd_config.h"
#include "run_process.h"
#include "synthetic.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

namespace {

using test_support::fresh_temp_dir;
using test_support::read_text;
using test_support::run_process;
using test_support::write_text;

TEST(DiagnoseCli, NamesHiddenBacklashAndWritesTheUpdatedModel) {
  const std::string dir = fresh_temp_dir("diagnose_cli");
  damper::BrfdParams truth = diagnose_test::synthetic_base();
  write_text(dir + "/model.yaml", damper::brfd_params_to_yaml(truth));
  truth.effects.backlash = damper::BacklashEffect{0.05};
  diagnose_test::SyntheticOptions so;
  so.rate_hz = 256.0;
  diagnose_test::write_json(diagnose_test::make_record(truth, so), dir + "/hidden-backlash.json");
  const auto r = run_process({test_paths::bin_dir() + "/hybridsim", "diagnose", "--model", dir + "/model.yaml",
                              "--measured", dir + "/hidden-backlash.json", "--out", dir + "/out", "--base", "model"});
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const std::regex last(
      "effects=backlash nrmse_before=[0-9.e-]+ nrmse_after=[0-9.e-]+ nrmse_after_max=[0-9.e-]+\n$");
  EXPECT_TRUE(std::regex_search(r.out, last)) << r.out;
  EXPECT_NE(r.out.find("== Where the model disagrees"), std::string::npos);
  EXPECT_NE(r.out.find("winner: backlash"), std::string::npos);
  const damper::BrfdParams updated = damper::load_brfd_params(dir + "/out/model-updated.yaml");
  ASSERT_TRUE(updated.effects.backlash.has_value());
  EXPECT_NEAR(updated.effects.backlash->slack_in, 0.05, 0.01);
  EXPECT_FALSE(read_text(dir + "/out/report.txt").empty());
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/gap.png"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/records/hidden-backlash.png"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/candidates.csv"));
}

TEST(DiagnoseCli, BadDataIsAUserError) {
  const std::string dir = fresh_temp_dir("diagnose_cli_bad");
  write_text(dir + "/model.yaml", damper::brfd_params_to_yaml(diagnose_test::synthetic_base()));
  write_text(dir + "/broken.json", "{\"dt\": 0.001, \"data\": [[0, 1, 2]]}");
  const auto r = run_process({test_paths::bin_dir() + "/hybridsim", "diagnose", "--model", dir + "/model.yaml",
                              "--measured", dir + "/broken.json", "--out", dir + "/out"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("error: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("broken.json"), std::string::npos) << r.err;
}

}  // namespace

namespace {

// The shipped config with effects drives a hybrid run: hybridsim spawns brfd-substructure, whose
// virtual damper steps the extended model (2 s of El Centro over LCM).
TEST(DiagnoseCli, ShippedDiagnosedConfigRunsInAHybridRun) {
  const std::string dir = fresh_temp_dir("diagnose_cli_run");
  std::string text = read_text(test_paths::source_dir() + "/configs/three-story.yaml");
  text = std::regex_replace(text, std::regex("\\.\\./records/"), test_paths::source_dir() + "/records/");
  text = std::regex_replace(text, std::regex("model_config: brfd-band-brake.yaml"),
                            "model_config: " + test_paths::source_dir() + "/configs/brfd-diagnosed-semiactive.yaml");
  text = std::regex_replace(text, std::regex("duration_s: 30.0"), "duration_s: 2.0");
  text = std::regex_replace(text, std::regex("dir: \\.\\./results/three-story"), "dir: " + dir + "/results");
  ASSERT_NE(text.find("brfd-diagnosed-semiactive.yaml"), std::string::npos);
  write_text(dir + "/run.yaml", text);
  const auto r = run_process({test_paths::bin_dir() + "/hybridsim", "run", "--config", dir + "/run.yaml"});
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const std::string model = read_text(dir + "/results/damper-model.yaml");
  EXPECT_NE(model.find("transition_shape:"), std::string::npos) << model;
  EXPECT_NE(model.find("backlash:"), std::string::npos) << model;
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
