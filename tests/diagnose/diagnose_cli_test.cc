// `hybridsim diagnose` as a user runs it: a synthetic record with hidden backlash, the model
// without it; the last line, the updated config (loads with the damper loader and holds the
// effect), the report and the figures; a bad data file gives exit code 1 and a clear message.
#include "damper/brfd_config.h"
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
