// The README's main job (`hybridsim run --config configs/three-story.yaml`, over LCM with the
// spawned brfd-substructure) against its answer file, tests/server/cli/default_run_answer.json.
// The answer was written by that command (see "source" in the file); the run is deterministic
// (the LCM run equals the in-process run to 1e-12, tests/server/run), so the tolerance only has
// to absorb floating-point differences between compilers/CPUs: 1e-4 relative, as the file says.
// A deliberate change of the default model or integrator must regenerate the file (and the
// README's printed output) in the same commit, saying why.
#include "run_process.h"
#include "test_paths.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

namespace {

void expect_close(const nlohmann::json& got, const nlohmann::json& want, double rel, double abs_floor,
                  const std::string& key) {
  if (want.is_array()) {
    ASSERT_TRUE(got.is_array()) << key;
    ASSERT_EQ(got.size(), want.size()) << key;
    for (std::size_t i = 0; i < want.size(); ++i)
      expect_close(got[i], want[i], rel, abs_floor, key + "[" + std::to_string(i) + "]");
    return;
  }
  const double g = got.get<double>(), w = want.get<double>();
  EXPECT_NEAR(g, w, std::max(rel * std::abs(w), abs_floor)) << key;
}

TEST(DefaultRun, SummaryMatchesTheAnswerFile) {
  nlohmann::json answer;
  std::ifstream(test_paths::source_dir() + "/tests/server/cli/default_run_answer.json") >> answer;
  const std::string out = test_support::fresh_temp_dir("default-run");
  const auto r = test_support::run_process({test_paths::bin_dir() + "/hybridsim", "run", "--config",
                                            test_paths::source_dir() + "/configs/three-story.yaml", "--out", out});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  nlohmann::json summary;
  std::ifstream(out + "/summary.json") >> summary;
  ASSERT_EQ(summary.value("status", ""), "ok");
  const double rel = answer.at("tolerance_relative").get<double>();
  const double floor = answer.at("tolerance_absolute").get<double>();
  EXPECT_EQ(summary.at("steps"), answer.at("expected").at("steps"));
  for (const auto& [key, want] : answer.at("expected").items()) {
    if (key == "steps") continue;
    // Keys are paths into summary.json, e.g. "energy_kip_in/damper".
    nlohmann::json got = summary;
    std::size_t start = 0;
    while (start <= key.size()) {
      const std::size_t slash = key.find('/', start);
      got = got.at(key.substr(start, slash - start));
      if (slash == std::string::npos) break;
      start = slash + 1;
    }
    expect_close(got, want, rel, floor, key);
  }
}

}  // namespace
