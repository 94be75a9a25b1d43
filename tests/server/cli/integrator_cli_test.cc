// hybridsim run with the integrator, resampling and no-damper keys of issue 15: what the user
// sees (printed summary, summary.json, effective-config.yaml, exit codes).
#include "run_configs.h"
#include "run_process.h"
#include "test_paths.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <functional>

namespace {

std::string hybridsim() { return test_paths::bin_dir() + "/hybridsim"; }

// configs/three-story.yaml, in-process, `seconds` of El Centro, results in `dir`/results, with
// `edit` applied to the RunConfig; written by the config serializer to `dir`/run.yaml.
std::string write_config(const std::string& dir, double seconds,
                         const std::function<void(server::RunConfig&)>& edit = {}) {
  server::RunConfig c = test_support::shipped_run_config("three-story.yaml");
  c.record.duration_s = seconds;
  c.transport.kind = "in_process";
  c.output.dir = dir + "/results";
  if (edit) edit(c);
  return test_support::write_run_config(dir + "/run.yaml", c);
}

nlohmann::json summary(const std::string& dir) {
  nlohmann::json j;
  std::ifstream(dir + "/results/summary.json") >> j;
  return j;
}

// KR-α selected in the config: the printed summary names it and the record resampling, the
// energy balance closes (< 1e-8) and says which ledger; summary.json and the effective config
// carry the integrator, ρ∞, the record's step, the run's step and the interpolation.
TEST(HybridsimRun, KrAlphaRunStatesIntegratorResamplingAndLedger) {
  const std::string dir = test_support::fresh_temp_dir("cli-kr");
  const auto r = test_support::run_process(
      {hybridsim(), "run", "--config",
       write_config(dir, 3.0, [](server::RunConfig& c) { c.integrator = {"kr_alpha", 0.3}; })});
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("integrator: KR-alpha (Kolay & Ricles 2014), rho_inf = 0.3"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("record: record step 0.01 s, run step 0.0009765625 s: linear interpolation"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("centred-difference ledger"), std::string::npos) << r.out;
  const nlohmann::json j = summary(dir);
  EXPECT_EQ(j["integrator"]["kind"], "kr_alpha");
  EXPECT_EQ(j["integrator"]["rho_inf"], 0.3);
  EXPECT_EQ(j["record_dt_s"], 0.01);
  EXPECT_EQ(j["resampling"]["run_dt_s"], 1.0 / 1024);
  EXPECT_EQ(j["resampling"]["mode"], "linear");
  EXPECT_EQ(j["resampling"]["steps_per_record_sample"], 0);
  EXPECT_LT(j["energy_kip_in"]["balance_error"].get<double>(), 1e-8);
  EXPECT_GT(j["energy_kip_in"]["damper"].get<double>(), 0.0);
  const std::string eff = test_support::read_text(dir + "/results/effective-config.yaml");
  EXPECT_NE(eff.find("integrator: kr_alpha"), std::string::npos) << eff;
  EXPECT_NE(eff.find("rho_inf: 0.3\n"), std::string::npos) << eff;
  EXPECT_NE(eff.find("resample: linear"), std::string::npos) << eff;
  EXPECT_NE(eff.find("# record step 0.01 s, run step 0.0009765625 s"), std::string::npos) << eff;
}

// record.resample: exact refuses 1/1024 s against a 0.01 s record (exit 2, nothing run) and
// accepts 0.0025 s (4 steps per record sample).
TEST(HybridsimRun, ResampleExactNeedsTheRunStepToDivideTheRecordStep) {
  const std::string dir = test_support::fresh_temp_dir("cli-exact");
  auto r = test_support::run_process(
      {hybridsim(), "run", "--config", write_config(dir, 1.0, [](server::RunConfig& c) { c.record.resample = "exact"; })});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("record.resample: exact"), std::string::npos) << r.err;
  r = test_support::run_process({hybridsim(), "run", "--config",
                                 write_config(dir, 1.0, [](server::RunConfig& c) {
                                   c.record.resample = "exact";
                                   c.dt_s = 0.0025;
                                 })});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(summary(dir)["resampling"]["steps_per_record_sample"], 4);
  EXPECT_NE(r.out.find("4 steps per record sample"), std::string::npos) << r.out;
}

// A building without dampers runs without a damper block (the loader's acceptance of a config
// without damper and transport blocks: RunConfig.NoDampersNeedNoDamperBlock).
TEST(HybridsimRun, NoDampersNeedNoDamperBlock) {
  const std::string dir = test_support::fresh_temp_dir("cli-bare");
  const auto r = test_support::run_process(
      {hybridsim(), "run", "--config",
       write_config(dir, 2.0, [](server::RunConfig& c) {
         c.building.dampers.clear();
         c.has_damper_block = false;
       })});
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_EQ(test_support::read_text(dir + "/run.yaml").find("\ndamper:"), std::string::npos);
  const nlohmann::json j = summary(dir);
  EXPECT_EQ(j["status"], "ok");
  EXPECT_TRUE(j["peak_damper_force_kip"].empty());
  EXPECT_LT(j["energy_kip_in"]["balance_error"].get<double>(), 1e-8);
}

}  // namespace
