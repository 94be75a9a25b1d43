// Strict reading of the BRFD data files: small fixtures (tests/damper/fixtures, written by
// make_fixtures.py) for every error, and the real files when ../shared is present.
#include "damper/data/brfd_data.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace damper {
namespace {

const std::string kFixtures = BRFD_FIXTURES_DIR;
const std::string kData = std::string(BRFD_SHARED_DIR) + "/data/brfd";

std::string error_of(const std::string& file) {
  try {
    read_brfd_test(kFixtures + "/" + file);
  } catch (const BrfdDataError& e) {
    return e.what();
  }
  return "";
}

void expect_has(const std::string& msg, const std::string& part) {
  EXPECT_NE(msg.find(part), std::string::npos) << "'" << part << "' not in: " << msg;
}

TEST(BrfdData, ReadsACharacterizationLayoutAndChecksItsVelocity) {
  const BrfdTest t = read_brfd_test(kFixtures + "/good_characterization.json");
  EXPECT_EQ(t.size(), 400u);
  EXPECT_FALSE(t.has_actuator_positions);
  EXPECT_FALSE(t.velocity_derived);
  EXPECT_NEAR(t.velocity_column_ratio, 1.0, 0.01);
  EXPECT_DOUBLE_EQ(t.dt_s, 1.0 / 1024.0);
  EXPECT_DOUBLE_EQ(t.actuator2_force_lb[10], 1500.0);
}

TEST(BrfdData, DerivesVelocityWhenTheColumnHasTheSemiactiveQuirk) {
  const BrfdTest t = read_brfd_test(kFixtures + "/good_semiactive.json");
  EXPECT_TRUE(t.has_actuator_positions);
  EXPECT_TRUE(t.velocity_derived);
  EXPECT_NEAR(1.0 / t.velocity_column_ratio, 125.0, 1.0);
  ASSERT_FALSE(t.notes.empty());
  expect_has(t.notes[0], "derived from the displacement");
  // Derived velocity = d/dt sin(2πt) = 2π cos(2πt), away from the ends.
  for (std::size_t i = 20; i < 380; i += 40)
    EXPECT_NEAR(t.drum_vel_in_per_s[i], 2 * M_PI * std::cos(2 * M_PI * t.time_s[i]), 0.02) << i;
}

// A drum at rest whose displacement reads one quantum higher at the last sample (the encoder's
// least count, 5.86e-5 in at 1024 Hz): the derived velocity there is that quantum spread over the
// smoothing window, as anywhere inside the record, not one quantum per sample (0.06 in/s, a fake
// motion that reversal-triggered effects answered with a force jump). A ramp's velocity stays
// exact to the last sample.
TEST(BrfdData, DerivedVelocityAtTheRecordEndsIsSmoothedLikeInside) {
  const double dt = 1.0 / 1024.0, q = 5.86e-5;
  const int h = 7;
  std::vector<double> rest(200, 0.0);
  rest.back() = q;
  rest.front() = q;
  const std::vector<double> v = derive_velocity(rest, dt, h);
  // Central differences: q/(2 dt) at the second-to-last sample, q/dt one-sided at the last; the
  // clipped window averages the last h + 1 of them.
  EXPECT_NEAR(v.back(), 1.5 * q / dt / (h + 1), 1e-12);
  EXPECT_NEAR(v.front(), -1.5 * q / dt / (h + 1), 1e-12);
  EXPECT_LT(std::abs(v.back()), 0.02);
  std::vector<double> ramp(200);
  for (std::size_t i = 0; i < ramp.size(); ++i) ramp[i] = 0.3 * dt * static_cast<double>(i);
  const std::vector<double> vr = derive_velocity(ramp, dt, h);
  for (std::size_t i = 0; i < vr.size(); ++i) EXPECT_NEAR(vr[i], 0.3, 1e-9) << i;
}

TEST(BrfdData, WrongColumnCountNamesFileAndRow) {
  const std::string m = error_of("wrong_column_count.json");
  expect_has(m, "wrong_column_count.json");
  expect_has(m, "row 123");
  expect_has(m, "7 columns, expected 8");
}

TEST(BrfdData, NanNamesFileRowAndColumn) {
  const std::string m = error_of("nan_force.json");
  expect_has(m, "nan_force.json");
  expect_has(m, "row 200");
  expect_has(m, "column 2 (friction force (kip))");
  expect_has(m, "NaN");
}

TEST(BrfdData, NonUniformTimeStepNamesFileAndRow) {
  const std::string m = error_of("nonuniform_dt.json");
  expect_has(m, "nonuniform_dt.json");
  expect_has(m, "row 250");
  expect_has(m, "column 0 (time (s))");
  expect_has(m, "non-uniform time step");
}

TEST(BrfdData, VelocityDisagreementNamesFileRowAndColumn) {
  const std::string m = error_of("velocity_disagrees.json");
  expect_has(m, "velocity_disagrees.json");
  expect_has(m, "column 3 (velocity (in/s))");
  expect_has(m, "disagrees with the derivative");
  // The sign flips at row 300; the 15-sample smoothing may flag it up to 7 rows early.
  const std::size_t at = m.find("row ");
  ASSERT_NE(at, std::string::npos);
  const int row = std::stoi(m.substr(at + 4));
  EXPECT_GE(row, 292);
  EXPECT_LE(row, 300);
}

TEST(BrfdData, MissingFileIsAnError) {
  EXPECT_THROW(read_brfd_test(kFixtures + "/no_such_file.json"), BrfdDataError);
}

TEST(BrfdData, RealFilesReadWithTheQuirkHandled) {
  if (!std::filesystem::exists(kData)) GTEST_SKIP() << "BRFD data not found at " << kData;
  const BrfdTest s = read_brfd_test(kData + "/semiactive/harmonic0.015forward.json");
  EXPECT_TRUE(s.velocity_derived);
  EXPECT_NEAR(1.0 / s.velocity_column_ratio, 125.0, 3.0);
  EXPECT_EQ(s.size(), 15361u);
  double peak = 0.0;
  for (double v : s.drum_vel_in_per_s) peak = std::max(peak, std::abs(v));
  EXPECT_NEAR(peak, M_PI, 0.2);  // 1 in at 0.5 Hz: 2π·0.5·1 in/s
  for (const auto& e : std::filesystem::directory_iterator(kData + "/characterization")) {
    const BrfdTest c = read_brfd_test(e.path().string());
    EXPECT_FALSE(c.velocity_derived) << e.path();
    EXPECT_NEAR(c.velocity_column_ratio, 1.0, 0.01) << e.path();
  }
}

}  // namespace
}  // namespace damper
