// Every file shipped in configs/ works as a user would use it, found by globbing the folder
// (a new config is covered without editing this test):
//  - run configs (a `building:` block): `hybridsim run --config F --duration 0.5` exits 0 with
//    status ok (LCM, physical with the rig emulator, ... as the file says);
//  - damper model configs (a `model:` key): built by the factory, stepped through a 1 in,
//    0.5 Hz cycle; the force stays finite and of BRFD size;
//  - `damper validate` configs (data_dir + semiactive): the data folder exists;
//  - rig emulator configs (a `rate_hz:` key): `brfd-rig --check-config` exits 0;
//  - IDA configs (an `ida:` block): the strict IDA loader (which loads every case config);
//  - record lists (*.txt): every record they name is read; scripts (*.sbatch): `bash -n` passes.
#include "damper/model/brfd_config.h"
#include "damper/model/brfd_model.h"
#include "run_process.h"
#include "server/batch/batch.h"
#include "server/ida/ida_config.h"
#include "test_paths.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

namespace fs = std::filesystem;

namespace {

std::vector<std::string> shipped_configs() {
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(test_paths::source_dir() + "/configs"))
    if (e.is_regular_file()) files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

std::string name_of(const testing::TestParamInfo<std::string>& info) {
  std::string n = fs::path(info.param).filename().string();
  for (char& c : n)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return n;
}

class ShippedConfig : public testing::TestWithParam<std::string> {};

TEST_P(ShippedConfig, WorksAsShipped) {
  const fs::path file = GetParam();
  const std::string ext = file.extension().string();
  if (ext == ".txt") {
    const auto records = server::load_record_set(file.string());
    EXPECT_FALSE(records.empty()) << file;
    return;
  }
  if (ext == ".sbatch") {
    const auto r = test_support::run_process({"/bin/bash", "-n", file.string()});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return;
  }
  ASSERT_EQ(ext, ".yaml") << file << ": a config of a kind this test does not know; teach it";
  const YAML::Node root = YAML::LoadFile(file.string());
  if (root["building"]) {
    const std::string out = test_support::fresh_temp_dir("smoke-" + file.stem().string());
    const auto r = test_support::run_process({test_paths::bin_dir() + "/hybridsim", "run", "--config", file.string(),
                                              "--out", out, "--duration", "0.5"});
    ASSERT_EQ(r.exit_code, 0) << file << "\n" << r.out << r.err;
    nlohmann::json summary;
    std::ifstream(out + "/summary.json") >> summary;
    EXPECT_EQ(summary.value("status", ""), "ok") << file;
    EXPECT_GE(summary.value("steps", 0L), 500L) << file;
  } else if (root["model"]) {
    // A damper model config (any model kind): the factory builds it and it steps through a
    // 1 in, 0.5 Hz cycle with a finite force of BRFD size (the device slips at 1-5 kip).
    const damper::BrfdParams p = damper::load_brfd_params(file.string());
    const std::unique_ptr<damper::DamperModel> model = damper::make_damper_model(p);
    const double dt = 1.0 / 1024, w = 2 * 3.14159265358979 * 0.5;
    double peak = 0.0;
    for (int i = 1; i <= 2048; ++i) {
      damper::DamperInput in;
      in.drum_disp_in = std::sin(w * i * dt);
      in.drum_vel_in_per_s = w * std::cos(w * i * dt);
      in.actuator1_in = model->actuator1_rest_in();
      in.actuator2_in = model->actuator2_rest_in();
      const double f = model->step(in, dt);
      ASSERT_TRUE(std::isfinite(f)) << file << " step " << i;
      peak = std::max(peak, std::abs(f));
    }
    EXPECT_GT(peak, 0.2) << file;
    EXPECT_LT(peak, 20.0) << file;
  } else if (root["data_dir"] && root["semiactive"]) {
    // `damper validate` config: the data folder it names exists (where ../shared is present).
    if (!test_paths::have_shared()) GTEST_SKIP() << "../shared absent";
    EXPECT_TRUE(fs::exists(file.parent_path() / root["data_dir"].as<std::string>())) << file;
  } else if (root["ida"]) {
    // IDA configs: the strict loader accepts it and every case config it names loads.
    EXPECT_NO_THROW(server::ida::load_ida_config(file.string())) << file;
  } else if (root["rate_hz"]) {
    // A rig that replays a measured test reads it from ../shared.
    if (root["replay"] && !test_paths::have_shared()) GTEST_SKIP() << "replays a record of ../shared, absent";
    const auto r = test_support::run_process({test_paths::bin_dir() + "/brfd-rig", "--config", file.string(),
                                              "--check-config"});
    EXPECT_EQ(r.exit_code, 0) << file << "\n" << r.out << r.err;
  } else {
    FAIL() << file << ": a YAML config of a kind this test does not know; teach it";
  }
}

INSTANTIATE_TEST_SUITE_P(Configs, ShippedConfig, testing::ValuesIn(shipped_configs()), name_of);

}  // namespace
