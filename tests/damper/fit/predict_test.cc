// Regression on the measured semi-active tests: LuGre parameters and b identified on each
// test's PASSIVE drum cycles (before the electric actuators first move), then the semi-active
// model, Eq. (4) with Tables 1-2, predicts the whole test. Paper, Table 4: NRMSE 0.19-0.21.
#include "damper/fit/predict.h"

#include "damper/model/brfd_config.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>

namespace damper {
namespace {

const std::string kData = std::string(BRFD_SHARED_DIR) + "/data/brfd";
const std::string kConfig = std::string(BRFD_SOURCE_DIR) + "/configs/brfd-semiactive.yaml";

class SemiactivePredict : public ::testing::TestWithParam<const char*> {};

TEST_P(SemiactivePredict, NrmseWithinPaperBoundUsingPassiveIdentification) {
  const std::string file = kData + "/semiactive/" + GetParam() + ".json";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "BRFD data not found: " << file;
  PredictOptions o;
  o.config_path = kConfig;
  o.test_path = file;
  o.out_dir = std::string(BRFD_TEST_OUT_DIR) + "/predict";
  o.log = [](const std::string& s) { std::cout << "  " << s << "\n"; };
  const PredictResult r = run_predict(o);
  std::cout << GetParam() << ": " << metrics_line(r.metrics) << "\n";

  // The parameters come from passive data only: the fit window ends at the first actuator
  // motion and the actuators sit at their t = 0 positions throughout it.
  ASSERT_TRUE(r.fitted);
  ASSERT_TRUE(r.first_actuator_motion_s.has_value());
  EXPECT_LE(r.fit_t1_s, *r.first_actuator_motion_s + 1e-9);
  EXPECT_GT(*r.first_actuator_motion_s, 3.0);  // the tests actuate from the second full cycle
  const BrfdTest t = read_brfd_test(file);
  for (std::size_t i = 0; i < t.size() && t.time_s[i] < r.fit_t1_s; ++i) {
    ASSERT_LE(std::abs(t.actuator1_in[i] - t.actuator1_in[0]), 0.002) << "t = " << t.time_s[i];
    ASSERT_LE(std::abs(t.actuator2_in[i] - t.actuator2_in[0]), 0.002) << "t = " << t.time_s[i];
  }
  EXPECT_EQ(r.params.kind, DamperKind::semiactive);
  EXPECT_EQ(r.predicted_kip.size(), t.size());  // the whole test, fit window included
  EXPECT_LE(r.metrics.nrmse_std, 0.21);
  EXPECT_LE(r.metrics_after_fit.nrmse_std, 0.23);
  EXPECT_TRUE(std::filesystem::exists(r.csv_path));
  EXPECT_TRUE(r.figure_warning.empty()) << r.figure_warning;
  if (r.figure_warning.empty()) {
    EXPECT_TRUE(std::filesystem::exists(r.png_path));
    std::cout << "  figure: " << r.png_path << "\n";
  }
}

INSTANTIATE_TEST_SUITE_P(PaperValidationTests, SemiactivePredict,
                         ::testing::Values("harmonic0.03ea1forward", "harmonic0.03ea1backward",
                                           "harmonic0.03ea2forward", "harmonic0.03ea2backward",
                                           "harmonic0.015forward", "harmonic0.015backward"));

TEST(Predict, SemiactiveModelBeatsPassiveLugreOnTheActuatedPart) {
  const std::string file = kData + "/semiactive/harmonic0.03ea1forward.json";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "BRFD data not found: " << file;
  PredictOptions o;
  o.config_path = kConfig;
  o.test_path = file;
  const PredictResult semi = run_predict(o);
  // Same identified LuGre parameters, actuators ignored (passive LuGre).
  o.fit = false;
  const std::string passive_cfg = std::string(BRFD_TEST_OUT_DIR) + "/passive_from_fit.yaml";
  std::filesystem::create_directories(BRFD_TEST_OUT_DIR);
  BrfdParams p = semi.params;
  p.kind = DamperKind::passive_lugre;
  std::ofstream(passive_cfg) << brfd_params_to_yaml(p);
  o.config_path = passive_cfg;
  const PredictResult passive = run_predict(o);
  std::cout << "after the fit window: semi-active " << metrics_line(semi.metrics_after_fit)
            << " | passive LuGre " << metrics_line(force_error(passive.measured_kip, passive.predicted_kip,
                                                               index_at_time(read_brfd_test(file), semi.fit_t1_s),
                                                               passive.measured_kip.size()))
            << "\n";
  EXPECT_LT(semi.metrics.rmse_kip, passive.metrics.rmse_kip);
}

TEST(Predict, NoFitUsesTheConfigAsIsAndMetricsLineFormat) {
  const std::string file = kData + "/semiactive/harmonic0.015backward.json";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "BRFD data not found: " << file;
  PredictOptions o;
  o.config_path = kConfig;
  o.test_path = file;
  o.fit = false;
  const PredictResult r = run_predict(o);
  EXPECT_FALSE(r.fitted);
  EXPECT_DOUBLE_EQ(r.params.lugre.sigma0_kip_per_in, 15.36);
  const std::string line = metrics_line(r.metrics);
  std::cout << "--no-fit with configs/brfd-semiactive.yaml on " << file << ": " << line << "\n";
  EXPECT_TRUE(std::regex_match(line, std::regex(R"(nrmse=[0-9.]+ rmse_kip=[0-9.]+ nrmse_range=[0-9.]+)"))) << line;
  EXPECT_LT(r.metrics.nrmse_std, 0.35);
}

TEST(Predict, FitWindowOverrideIsUsed) {
  const std::string file = kData + "/semiactive/harmonic0.015forward.json";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "BRFD data not found: " << file;
  PredictOptions o;
  o.config_path = kConfig;
  o.test_path = file;
  o.fit_window_s = std::make_pair(0.5, 3.0);
  o.identification.global_runs = 1;
  const PredictResult r = run_predict(o);
  EXPECT_NEAR(r.fit_t0_s, 0.5, 1e-3);
  EXPECT_NEAR(r.fit_t1_s, 3.0, 1e-3);
}

}  // namespace
}  // namespace damper
