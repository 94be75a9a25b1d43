#include "structure/ground_motion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace structure {
namespace {

const std::string kFixtures = STRUCTURE_FIXTURE_DIR;
const std::string kRecords = PROJECT_RECORDS_DIR;

// Expects a RecordError whose message contains every fragment.
void expect_record_error(const std::string& path, std::initializer_list<std::string> fragments,
                         double scale = 1.0) {
  try {
    read_ground_motion(path, scale);
    ADD_FAILURE() << "no RecordError for " << path;
  } catch (const RecordError& e) {
    const std::string msg = e.what();
    for (const std::string& f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << "'" << f << "' not in: " << msg;
  }
}

TEST(GroundMotion, ReadsNgaWest2Header) {
  const GroundMotion gm = read_ground_motion(kFixtures + "/at2_nga_west2.AT2");
  EXPECT_EQ(gm.dt_s, 0.01);
  ASSERT_EQ(gm.accel_g.size(), 12u);
  const double expected[12] = {1e-3, 2e-3, 3e-3, -4e-3, 5e-3, -6e-3, 7e-3, 8e-3, 9e-3, 1e-2, 1.1e-2, -1.2e-2};
  for (int i = 0; i < 12; ++i) EXPECT_DOUBLE_EQ(gm.accel_g[i], expected[i]) << i;
  EXPECT_DOUBLE_EQ(gm.duration_s(), 0.11);
  EXPECT_DOUBLE_EQ(gm.pga_g(), 0.012);
  EXPECT_EQ(gm.source, kFixtures + "/at2_nga_west2.AT2");
}

TEST(GroundMotion, ReadsHeaderWithSpacesAroundEquals) {
  const GroundMotion gm = read_ground_motion(kFixtures + "/at2_spaced_header.AT2");
  EXPECT_EQ(gm.dt_s, 0.02);
  ASSERT_EQ(gm.accel_g.size(), 7u);
  EXPECT_DOUBLE_EQ(gm.accel_g[1], -0.25);
  EXPECT_DOUBLE_EQ(gm.pga_g(), 0.3);
}

TEST(GroundMotion, ReadsNgaWest1Header) {
  const GroundMotion gm = read_ground_motion(kFixtures + "/at2_nga_west1.AT2");
  EXPECT_EQ(gm.dt_s, 0.005);
  ASSERT_EQ(gm.accel_g.size(), 6u);
  EXPECT_DOUBLE_EQ(gm.accel_g[4], -0.005);
}

TEST(GroundMotion, ReadsCrlfFile) {
  const GroundMotion gm = read_ground_motion(kFixtures + "/at2_crlf.AT2");
  EXPECT_EQ(gm.dt_s, 0.01);
  ASSERT_EQ(gm.accel_g.size(), 8u);
  EXPECT_DOUBLE_EQ(gm.accel_g[4], 0.05);
  EXPECT_DOUBLE_EQ(gm.accel_g[7], -0.03);
}

TEST(GroundMotion, SplitsRunTogetherNegatives) {
  const GroundMotion gm = read_ground_motion(kFixtures + "/at2_run_together.AT2");
  ASSERT_EQ(gm.accel_g.size(), 10u);
  const double expected[10] = {-1.234e-3, -3.616e-3, 5e-3, -7e-2, -0.1, 2e-3, -3e-3, -4e-3, 1e-2, 2e-2};
  for (int i = 0; i < 10; ++i) EXPECT_DOUBLE_EQ(gm.accel_g[i], expected[i]) << i;
}

// The record reader scans numbers by hand (no std::regex): the Fortran forms a PEER file
// may hold, each equal to strtod of its text (D exponent read as E), and what is not a number.
TEST(GroundMotion, FortranNumberFormsReadExactly) {
  const std::string path = ::testing::TempDir() + "/fortran_forms.AT2";
  auto write = [&](const std::string& data, const std::string& npts) {
    std::FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fprintf(f, "PEER\nrecord\nACCELERATION IN UNITS OF G\nnpts=%s, dt=.0100 sec\n%s\n", npts.c_str(), data.c_str());
    std::fclose(f);
  };
  write("1.e-2 +.5 5. -3 .25D+01 7d-3 1.5E2-2.5e-1+4 0.1234567890123456789", "10");
  const GroundMotion gm = read_ground_motion(path);
  ASSERT_EQ(gm.accel_g.size(), 10u);
  const double expected[10] = {std::strtod("1.e-2", nullptr), 0.5, 5.0, -3.0, 2.5, 7e-3, 150.0, -0.25, 4.0,
                               std::strtod("0.1234567890123456789", nullptr)};
  for (int i = 0; i < 10; ++i) EXPECT_EQ(gm.accel_g[i], expected[i]) << i;  // bit for bit
  // An exponent without digits, a lone point, a letter after a number: not numbers.
  for (const char* bad : {"1.0 2e+ 3.0", "1.0 . 3.0", "1.0 2.0x 3.0", "1.0 e5 3.0"}) {
    write(bad, "3");
    expect_record_error(path, {"fortran_forms.AT2:5", "non-numeric token"});
  }
}

TEST(GroundMotion, TruncatedFileNamesFileAndCounts) {
  expect_record_error(kFixtures + "/at2_truncated.AT2", {"at2_truncated.AT2", "NPTS = 10", "7 values", "truncated"});
}

TEST(GroundMotion, NonNumericTokenNamesFileAndLine) {
  expect_record_error(kFixtures + "/at2_bad_token.AT2", {"at2_bad_token.AT2:6", "non-numeric token 'abc'"});
}

TEST(GroundMotion, InfiniteValueIsRejected) {
  expect_record_error(kFixtures + "/at2_overflow.AT2", {"at2_overflow.AT2:5", "not finite"});
}

TEST(GroundMotion, ReadsTwoColumnFile) {
  const GroundMotion gm = read_ground_motion(kFixtures + "/two_column.txt", 2.0);
  EXPECT_NEAR(gm.dt_s, 0.005, 1e-15);
  ASSERT_EQ(gm.accel_g.size(), 5u);
  const double expected[5] = {0.0, 0.02, -0.04, 0.06, -0.08};  // scaled by 2
  for (int i = 0; i < 5; ++i) EXPECT_DOUBLE_EQ(gm.accel_g[i], expected[i]) << i;
  EXPECT_EQ(gm.scale, 2.0);
}

TEST(GroundMotion, NonUniformTwoColumnNamesLine) {
  expect_record_error(kFixtures + "/two_column_nonuniform.txt", {"two_column_nonuniform.txt:6", "non-uniform time step"});
}

TEST(GroundMotion, UnknownFormatAndMissingFile) {
  expect_record_error(kFixtures + "/unknown_format.txt", {"unknown_format.txt", "unknown ground-motion format"});
  expect_record_error(kFixtures + "/does_not_exist.AT2", {"does_not_exist.AT2", "cannot open"});
}

TEST(GroundMotion, ScaleMustBeFinitePositive) {
  expect_record_error(kFixtures + "/at2_crlf.AT2", {"at2_crlf.AT2", "scale"}, 0.0);
  expect_record_error(kFixtures + "/at2_crlf.AT2", {"scale"}, -1.0);
  expect_record_error(kFixtures + "/at2_crlf.AT2", {"scale"}, std::nan(""));
  const GroundMotion gm = read_ground_motion(kFixtures + "/at2_crlf.AT2", 1.5);
  EXPECT_DOUBLE_EQ(gm.accel_g[4], 0.075);
  EXPECT_DOUBLE_EQ(gm.pga_g(), 0.075);
}

TEST(GroundMotion, LinearInterpolationAndZeroAfterEnd) {
  GroundMotion gm;
  gm.dt_s = 0.01;
  gm.accel_g = {0.0, 0.1, -0.1};
  EXPECT_DOUBLE_EQ(gm.accel_in_per_s2(0.0), 0.0);
  EXPECT_NEAR(gm.accel_in_per_s2(0.005), 0.05 * kGravity_in_per_s2, 1e-12);
  EXPECT_NEAR(gm.accel_in_per_s2(0.0125), 0.05 * kGravity_in_per_s2, 1e-12);
  EXPECT_NEAR(gm.accel_in_per_s2(0.02), -0.1 * kGravity_in_per_s2, 1e-12);
  EXPECT_EQ(gm.accel_in_per_s2(0.0201), 0.0);
  EXPECT_EQ(gm.accel_in_per_s2(-0.001), 0.0);
}

// The shipped records: NPTS, DT and PGA as listed in records/README.md (computed there with
// an independent Python reader).
TEST(GroundMotion, ShippedRecordsMatchReadme) {
  struct Expected {
    const char* file;
    double dt;
    std::size_t npts;
    double pga;
  };
  const Expected records[] = {
      {"ImperialValley1940_ElCentroArray9_180_NS_RSN6.AT2", 0.01, 5372, 0.2808},
      {"Northridge1994_RinaldiReceivingSta_228_RSN1063.AT2", 0.01, 1991, 0.8741},
      {"Kocaeli1999_Duzce_270_RSN1158.AT2", 0.005, 5437, 0.3642},
      {"Northridge1994_SylmarConverterSta_142_RSN1084.AT2", 0.005, 8773, 0.9234},
  };
  for (const Expected& r : records) {
    const GroundMotion gm = read_ground_motion(kRecords + "/" + r.file);
    EXPECT_EQ(gm.dt_s, r.dt) << r.file;
    EXPECT_EQ(gm.accel_g.size(), r.npts) << r.file;
    EXPECT_NEAR(gm.pga_g(), r.pga, 0.00005) << r.file;
  }
}

}  // namespace
}  // namespace structure
