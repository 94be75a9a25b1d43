// Band-brake identification and validation on the measured BRFD data (CI-sized subset of
// configs/brfd-validate.yaml; skipped with a message when ../shared is absent).
// Identification on passive data only: two 36 lb characterization tests for the earthquake
// rows, the pre-actuation cycles for the semi-active row.
#include "common/strict_yaml.h"
#include "damper/fit/validate.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>

namespace damper {
namespace {

const std::string kData = std::string(BRFD_SHARED_DIR) + "/data/brfd/";

const ValidationRow* find(const ValidationResult& r, const std::string& test, const std::string& model, bool window) {
  for (const ValidationRow& w : r.rows)
    if (w.test == test && w.model == model && (w.span != "whole") == window) return &w;
  return nullptr;
}

TEST(BandBrakeValidation, EarthquakeAndSemiactiveOnACiSubset) {
  const std::string probe = kData + "earthquake-profiles/KocaeliMCE.json";
  if (!std::filesystem::exists(probe)) GTEST_SKIP() << "BRFD data not found: " << probe;
  ValidationConfig c;
  c.identification_files = {kData + "characterization/1Hz36lbtension1amplitude.json",
                            kData + "characterization/0.5Hz36lbtension0.5amplitude.json"};
  c.identification_scales = {1.0, 1.0};
  c.lugre_identification_file = kData + "characterization/1Hz36lbtension1amplitude.json";
  c.tests.push_back({kData + "earthquake-profiles/ImperialValleyDBE.json", "earthquake", std::make_pair(3072, 7680), 1.0});
  c.tests.push_back({kData + "earthquake-profiles/KocaeliMCE.json", "earthquake", std::make_pair(6144, 14336), 1.0});
  c.tests.push_back({kData + "semiactive/harmonic0.015forward.json", "semiactive", std::nullopt, 1.0});
  c.band_brake_fit.global_max_evals = 800;
  // Best of two global runs: with one run the semi-active passive-window fit of seed 1 stopped
  // at a local optimum (RMSE/std 0.131 after a change of the derived velocity in the record's
  // first and last 7 samples; seeds 2-4 gave 0.080-0.087).
  c.band_brake_fit.global_runs = 2;
  c.band_brake_fit.local_max_evals = 800;
  c.lugre_global_max_evals = 600;
  c.lugre_global_runs = 1;
  c.lugre_local_max_evals = 600;
  c.figures = false;
  const ValidationResult r = run_validation(c);
  std::cout << format_validation_table(r);

  // Issue 13's target on Imperial Valley: NRMSE(range) <= 0.05 on the strong-motion window.
  const ValidationRow* iv = find(r, "ImperialValleyDBE", "band_brake", true);
  ASSERT_NE(iv, nullptr);
  EXPECT_LE(iv->force.nrmse_range, 0.05);
  // Kocaeli: the 0.05 target is NOT met (0.08 in the full table); assert the band brake beats
  // the published standard LuGre (0.094, Coble et al. 2024) and the LuGre baseline identified
  // here on the same characterization data.
  const ValidationRow* koc = find(r, "KocaeliMCE", "band_brake", true);
  const ValidationRow* koc_lugre = find(r, "KocaeliMCE", "paper_semiactive", true);
  ASSERT_NE(koc, nullptr);
  ASSERT_NE(koc_lugre, nullptr);
  EXPECT_LT(koc->force.nrmse_range, 0.094);
  EXPECT_LT(koc->force.nrmse_range, koc_lugre->force.nrmse_range);
  // (d) load cells: the taut end's tension is predicted, not fitted on these tests: the cell
  // error stays well below the cells' own spread.
  EXPECT_LT(koc->cells_nrmse_std, 0.8);
  EXPECT_LT(iv->cells_nrmse_std, 0.8);
  // Semi-active (passive cycles only): issue 13's target 0.10 (0.078 here; the backward tests
  // reach 0.12-0.15, see README), and better than the paper's model on the same window (0.177).
  const ValidationRow* sa = find(r, "harmonic0.015forward", "band_brake", false);
  const ValidationRow* sa_paper = find(r, "harmonic0.015forward", "paper_semiactive", false);
  ASSERT_NE(sa, nullptr);
  ASSERT_NE(sa_paper, nullptr);
  EXPECT_LE(sa->force.nrmse_std, 0.10);
  EXPECT_LT(sa->force.nrmse_std, sa_paper->force.nrmse_std);
}

TEST(BandBrakeValidation, ConfigErrorsNameFileAndKey) {
  const std::string dir = ::testing::TempDir();
  const std::string file = dir + "/validate_bad.yaml";
  std::ofstream(file) << "data_dir: /nonexistent\nidentification:\n  - {test: characterization/none}\n"
                         "lugre_identification: characterization/none\n";
  try {
    load_validation_config(file);
    FAIL() << "missing test file accepted";
  } catch (const common::ConfigError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("validate_bad.yaml"), std::string::npos) << m;
    EXPECT_NE(m.find("test"), std::string::npos) << m;
    EXPECT_NE(m.find("none.json"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace damper
