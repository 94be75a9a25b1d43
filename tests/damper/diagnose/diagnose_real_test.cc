// diagnose on the real semi-active tests of ../shared/data/brfd/semiactive (skipped with a message
// when absent): base LuGre identified on each test's passive window only (before the electric
// actuators first move), effects fitted on training drum cycles. Reports what it finds and the
// NRMSE before/after per test; fails if the workflow stops improving the model.
// Smaller optimizer budgets than the CLI defaults, to keep the test short.
#include "damper/diagnose/diagnose.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>

namespace damper {
namespace {

TEST(DiagnoseRealData, SemiActiveTests) {
  const std::string data = test_paths::shared_dir() + "/data/brfd/semiactive";
  if (!std::filesystem::exists(data)) GTEST_SKIP() << data << " is absent: real-data diagnose not run";
  DiagnoseOptions o;
  o.model_path = test_paths::source_dir() + "/configs/brfd-semiactive.yaml";
  o.measured = {data};
  o.out_dir = (std::filesystem::temp_directory_path() / "diagnose_real_test").string();
  o.base = BaseSource::identify;
  o.figures = false;
  o.base_identification.global_runs = 1;
  o.base_identification.global_max_evals = 2000;
  o.base_identification.local_max_evals = 1000;
  o.base_refit_evals = 80;
  o.effect_evals = 40;
  o.polish_evals = 40;
  o.fit_rate_hz = 128.0;
  o.max_effects = 3;
  const DiagnoseResult r = run_diagnose(o);
  std::cout << "real semi-active tests, effects added in order:";
  for (const std::string& e : r.added) std::cout << " " << e;
  std::cout << "\n  test                       NRMSE before  after   (held-out before  after)\n";
  for (const RecordReport& rec : r.records) {
    std::cout << "  " << rec.name << "  " << rec.before.nrmse_std << "  " << rec.after.nrmse_std << "   ("
              << rec.before_heldout.nrmse_std << "  " << rec.after_heldout.nrmse_std << ")\n";
    EXPECT_LT(rec.after.nrmse_std, rec.before.nrmse_std) << rec.name;
    EXPECT_LT(rec.after_heldout.nrmse_std, rec.before_heldout.nrmse_std) << rec.name;
  }
  std::cout << diagnose_final_line(r) << "\n";
  ASSERT_EQ(r.records.size(), 6u);
  EXPECT_GT(r.nrmse_before_mean, 0.17);  // the paper's model: about 0.2
  EXPECT_LT(r.nrmse_after_mean, 0.16);
  EXPECT_GE(r.added.size(), 2u);
}

}  // namespace
}  // namespace damper
