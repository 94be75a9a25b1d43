// Scaling and amplification factors (paper Figs. 6-10, Table 2) re-derived from the data.
#include "damper/fit/relationships.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>

namespace damper {
namespace {

const std::string kData = std::string(BRFD_SHARED_DIR) + "/data/brfd";

TEST(Relationships, FitLineAgainstClosedForm) {
  const std::vector<double> x = {1, 2, 3, 4};
  const std::vector<double> y = {-3, -5, -7, -9};  // |y| = 2x + 1
  const LineFit f = fit_line(x, y);
  EXPECT_NEAR(f.slope, 2.0, 1e-12);
  EXPECT_NEAR(f.intercept_kip, 1.0, 1e-12);
  EXPECT_NEAR(f.r2, 1.0, 1e-12);
  EXPECT_NEAR(f.slope_origin, (3 + 10 + 21 + 36) / 30.0, 1e-12);  // Σxy/Σx²
}

TEST(Relationships, TautScalingFactorsAndAmplificationIncreaseFromTheData) {
  if (!std::filesystem::exists(kData)) GTEST_SKIP() << "BRFD data not found at " << kData;
  const RelationshipsReport r = derive_relationships(kData, {});
  std::cout << format_relationships(r);
  // Taut actuators: friction ≈ C × actuator force with C2 ≈ 2.10 and C3 ≈ 1.94 (Table 2).
  EXPECT_NEAR(r.mean_slope_origin[1], 2.10, 0.25);
  EXPECT_NEAR(r.mean_slope_origin[2], 1.94, 0.25);
  EXPECT_NEAR(r.semiactive_mean_slope_origin[1], 2.10, 0.3);
  EXPECT_NEAR(r.semiactive_mean_slope_origin[2], 1.94, 0.3);
  // Slack actuators on the semi-active tests (slack load cells read 30-40 lb there): friction is
  // of order 100x the slack force (Table 2: C1 119.68, C4 123.31).
  EXPECT_GT(r.semiactive_mean_slope_origin[0], 50.0);
  EXPECT_GT(r.semiactive_mean_slope_origin[3], 50.0);
  // Actuated cycles raise the damping force (paper: ~33% increase of amplification).
  ASSERT_EQ(r.semiactive.size(), 6u);
  for (const auto& s : r.semiactive) {
    EXPECT_GT(s.peak_force.increase, 0.15) << s.name;
    EXPECT_GT(s.af_peak.increase, 0.0) << s.name;
    EXPECT_EQ(s.forward_actuated, s.name.find("forward") != std::string::npos) << s.name;
  }
  EXPECT_NEAR(r.mean_increase_peak_force, 0.33, 0.08);
}

}  // namespace
}  // namespace damper
