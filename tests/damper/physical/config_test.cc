// Configs of the physical mode: the swap is one key (three-story-physical.yaml differs from
// three-story.yaml only in damper.mode and the rig block), the rig block is strict and
// optional, and every shipped rig config loads.
#include "common/strict_yaml.h"
#include "damper/rig/rig_config.h"
#include "run_process.h"
#include "server/run/run_config.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream s(text);
  for (std::string l; std::getline(s, l);) out.push_back(l);
  return out;
}

TEST(PhysicalConfigs, ThreeStoryPhysicalDiffersOnlyInTheModeKeyAndTheRigBlock) {
  const auto virt = lines_of(test_support::read_text(test_paths::source_dir() + "/configs/three-story.yaml"));
  auto phys = lines_of(test_support::read_text(test_paths::source_dir() + "/configs/three-story-physical.yaml"));
  // Drop the appended rig block (from its comment header to the end of the file).
  std::size_t cut = phys.size();
  for (std::size_t i = 0; i < phys.size(); ++i)
    if (phys[i].rfind("# Physical substructure", 0) == 0) {
      cut = i;
      break;
    }
  ASSERT_LT(cut, phys.size()) << "rig block header not found";
  for (std::size_t i = cut; i < phys.size(); ++i) {
    if (!phys[i].empty() && phys[i][0] != ' ' && phys[i][0] != '#') {
      EXPECT_EQ(phys[i], "rig:") << "after the rig block";
    }
  }
  phys.resize(cut);
  ASSERT_EQ(phys.size(), virt.size());
  int differing = 0;
  for (std::size_t i = 0; i < virt.size(); ++i) {
    if (virt[i] == phys[i]) continue;
    ++differing;
    EXPECT_NE(virt[i].find("mode: virtual"), std::string::npos) << virt[i];
    EXPECT_NE(phys[i].find("mode: physical"), std::string::npos) << phys[i];
  }
  EXPECT_EQ(differing, 1);

  const server::RunConfig p = server::load_run_config(test_paths::source_dir() + "/configs/three-story-physical.yaml");
  const server::RunConfig v = server::load_run_config(test_paths::source_dir() + "/configs/three-story.yaml");
  EXPECT_EQ(p.damper.mode, "physical");
  EXPECT_EQ(v.damper.mode, "virtual");
  EXPECT_EQ(p.rig.rig.launch, "local");
  EXPECT_TRUE(std::filesystem::exists(p.rig.rig.config)) << p.rig.rig.config;
  // The rig block's values equal the defaults in code, so three-story.yaml with only the mode
  // switched gets the same physical settings.
  const damper::physical::PhysicalSettings d;
  EXPECT_EQ(p.rig.limits.stroke_in, d.limits.stroke_in);
  EXPECT_EQ(p.rig.limits.actuator_force_lb, d.limits.actuator_force_lb);
  EXPECT_EQ(p.rig.watchdogs.sensor_frame_timeout_s, d.watchdogs.sensor_frame_timeout_s);
  EXPECT_EQ(p.rig.ats.window_s, d.ats.window_s);
  EXPECT_EQ(p.rig.rig.config, v.rig.rig.config);
}

TEST(PhysicalConfigs, RigBlockIsStrict) {
  const std::string dir = test_support::fresh_temp_dir("rigblock");
  std::string text = test_support::read_text(test_paths::source_dir() + "/configs/three-story-physical.yaml");
  const std::string src = test_paths::source_dir() + "/configs/";
  auto absolutize = [&](std::string t) {
    for (const char* rel : {"../records/", "brfd-band-brake.yaml", "rig-default.yaml"}) {
      const auto at = t.find(rel);
      if (at != std::string::npos) t.replace(at, std::string(rel).size(), src + rel);
    }
    return t;
  };
  text = absolutize(text);
  auto with = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    const auto at = t.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    t.replace(at, from.size(), to);
    test_support::write_text(dir + "/c.yaml", t);
    return dir + "/c.yaml";
  };
  try {
    server::load_run_config(with("    stroke_in: 2.0", "    stroke_inch: 2.0"));
    FAIL() << "unknown key accepted";
  } catch (const common::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("rig.limits.stroke_inch"), std::string::npos) << e.what();
  }
  try {
    server::load_run_config(with("    a1_max_s: 0.08", "    a1_max_s: -0.5"));
    FAIL() << "a1 bounds reversed accepted";
  } catch (const common::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("a1_max_s"), std::string::npos) << e.what();
  }
  try {
    server::load_run_config(with("  launch: local ", "  launch: external "));
    FAIL() << "external rig without a key file accepted";
  } catch (const common::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("rig.key_file"), std::string::npos) << e.what();
  }
  try {
    server::load_run_config(with("  dt_s: 0.0009765625", "  dt_s: 0.001"));
    FAIL() << "dt_s off the controller rate accepted in physical mode";
  } catch (const common::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("run.dt_s"), std::string::npos) << e.what();
  }
}

TEST(PhysicalConfigs, EveryShippedRigConfigLoads) {
  for (const auto& entry : std::filesystem::directory_iterator(test_paths::source_dir() + "/configs")) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("rig-", 0) != 0) continue;
    if (name == "rig-replay.yaml" && !test_paths::have_shared()) continue;
    SCOPED_TRACE(name);
    const damper::rig::RigConfig c = damper::rig::load_rig_config(entry.path().string());
    EXPECT_EQ(c.rate_hz, 1024.0);
  }
}

TEST(PhysicalConfigs, RigConfigIsStrict) {
  const std::string dir = test_support::fresh_temp_dir("rigstrict");
  std::string text = test_support::read_text(test_paths::source_dir() + "/configs/rig-default.yaml");
  text.replace(text.find("brfd-default.yaml"), 17, test_paths::source_dir() + "/configs/brfd-default.yaml");
  const auto at = text.find("  delay_s: 0.020");
  ASSERT_NE(at, std::string::npos);
  test_support::write_text(dir + "/r.yaml", text.substr(0, at) + "  delay_ms: 20" + text.substr(at + 16));
  try {
    damper::rig::load_rig_config(dir + "/r.yaml");
    FAIL() << "unknown rig key accepted";
  } catch (const common::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("hydraulic.delay_ms"), std::string::npos) << e.what();
  }
}

}  // namespace
