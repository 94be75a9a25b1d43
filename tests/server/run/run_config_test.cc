// The run config loader is strict: every error names the file, the line and the key.
#include "common/strict_yaml.h"
#include "messages/lcm_bus.h"
#include "run_configs.h"
#include "run_process.h"
#include "server/run/run_config.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <regex>

namespace {

/// configs/three-story.yaml as the config serializer writes it (absolute paths, every key).
std::string three_story_text(const server::RunConfig& c = test_support::shipped_run_config("three-story.yaml")) {
  return server::run_config_to_yaml(c);
}

std::string load_error(const std::string& text) {
  const std::string path = test_support::fresh_temp_dir("cfg") + "/bad.yaml";
  test_support::write_text(path, text);
  try {
    server::load_run_config(path);
  } catch (const common::ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(RunConfig, ShippedConfigsLoad) {
  for (const char* name : {"three-story.yaml", "ten-story.yaml", "twenty-story.yaml"}) {
    const server::RunConfig c = server::load_run_config(test_paths::source_dir() + "/configs/" + name);
    EXPECT_FALSE(c.transport.url.empty()) << name;
    EXPECT_GE(c.building.dampers.size(), 1u) << name;
  }
  const server::RunConfig twenty = server::load_run_config(test_paths::source_dir() + "/configs/twenty-story.yaml");
  EXPECT_EQ(twenty.integrator.kind, "kr_alpha");
  EXPECT_EQ(twenty.integrator.rho_inf, 0.5);
  EXPECT_EQ(twenty.building.story_mass_kip_s2_per_in.size(), 20u);
  EXPECT_EQ(server::load_run_config(test_paths::source_dir() + "/configs/three-story.yaml").integrator.kind, "cr");
}

TEST(RunConfig, IntegratorKeys) {
  server::RunConfig with_kr = test_support::shipped_run_config("three-story.yaml");
  with_kr.integrator = {"kr_alpha", 0.25};
  const std::string kr = three_story_text(with_kr);
  const std::string path = test_support::fresh_temp_dir("cfg") + "/kr.yaml";
  test_support::write_text(path, kr);
  const server::RunConfig c = server::load_run_config(path);
  EXPECT_EQ(c.integrator.kind, "kr_alpha");
  EXPECT_EQ(c.integrator.rho_inf, 0.25);
  // The effective config keeps both keys.
  const std::string eff = test_support::fresh_temp_dir("eff") + "/effective.yaml";
  test_support::write_text(eff, server::run_config_to_yaml(c));
  EXPECT_EQ(server::load_run_config(eff).integrator.rho_inf, 0.25);

  std::string err = load_error(std::regex_replace(kr, std::regex("rho_inf: 0.25"), "rho_inf: 1.5"));
  EXPECT_NE(err.find("run.rho_inf"), std::string::npos) << err;
  err = load_error(std::regex_replace(kr, std::regex("integrator: kr_alpha"), "integrator: newmark"));
  EXPECT_NE(err.find("run.integrator"), std::string::npos) << err;
  err = load_error(std::regex_replace(kr, std::regex("integrator: kr_alpha"), "integrator: cr"));
  EXPECT_NE(err.find("run.rho_inf"), std::string::npos) << err;  // rho_inf means nothing to CR
  err = load_error(std::regex_replace(three_story_text(), std::regex("  resample: linear\n"), "  resample: cubic\n"));
  EXPECT_NE(err.find("record.resample"), std::string::npos) << err;
}

// A building without dampers needs neither a damper block nor a transport block.
TEST(RunConfig, NoDampersNeedNoDamperBlock) {
  std::string text = three_story_text();
  text = std::regex_replace(text, std::regex("  dampers:\n(    [^\n]*\n)+"), "");
  text = std::regex_replace(text, std::regex("\ndamper:\n(  [^\n]*\n)+"), "\n");
  text = std::regex_replace(text, std::regex("\ntransport:\n(  [^\n]*\n)+"), "\n");
  ASSERT_EQ(text.find("damper:"), std::string::npos) << text;
  const std::string path = test_support::fresh_temp_dir("cfg") + "/bare.yaml";
  test_support::write_text(path, text);
  const server::RunConfig c = server::load_run_config(path);
  EXPECT_TRUE(c.building.dampers.empty());
  EXPECT_FALSE(c.has_damper_block);
  EXPECT_EQ(c.transport.kind, "in_process");
  const std::string eff = test_support::fresh_temp_dir("eff") + "/effective.yaml";
  test_support::write_text(eff, server::run_config_to_yaml(c));
  EXPECT_FALSE(server::load_run_config(eff).has_damper_block);
  // With dampers the block is still required.
  const std::string err = load_error(std::regex_replace(three_story_text(), std::regex("\ndamper:\n(  [^\n]*\n)+"), "\n"));
  EXPECT_NE(err.find("damper"), std::string::npos) << err;
}

// record.resample: exact only where the run step divides the record step.
TEST(RunConfig, ResampleExactNeedsAWholeNumberOfStepsPerSample) {
  server::RunConfig c = server::load_run_config(test_paths::source_dir() + "/configs/three-story.yaml");
  EXPECT_NO_THROW(server::check_resampling(c, 0.01));  // linear: anything goes
  c.record.resample = "exact";
  try {
    server::check_resampling(c, 0.01);
    ADD_FAILURE() << "1/1024 s does not divide 0.01 s";
  } catch (const common::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("record.resample"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("0.01"), std::string::npos) << e.what();
  }
  c.dt_s = 0.0025;
  EXPECT_NO_THROW(server::check_resampling(c, 0.01));
  EXPECT_EQ(server::describe_resampling(0.01, 0.0025, "exact").steps_per_sample, 4);
  EXPECT_EQ(server::describe_resampling(0.01, 1.0 / 1024, "linear").steps_per_sample, 0);
  EXPECT_NE(server::describe_resampling(0.01, 1.0 / 1024, "linear").text.find("does not divide"), std::string::npos);
}

TEST(RunConfig, UnknownKeyIsNamed) {
  const std::string err = load_error(std::regex_replace(three_story_text(), std::regex("  scale: 1\n"), "  scael: 1\n"));
  EXPECT_NE(err.find("bad.yaml:"), std::string::npos) << err;
  EXPECT_NE(err.find("record.scael: unknown key"), std::string::npos) << err;
}

TEST(RunConfig, MissingKeyIsNamed) {
  const std::string err = load_error(std::regex_replace(three_story_text(), std::regex("  story_stiffness_kip_per_in:[^\n]*\n"), ""));
  EXPECT_NE(err.find("story_stiffness_kip_per_in"), std::string::npos) << err;
  EXPECT_NE(err.find("missing"), std::string::npos) << err;
}

TEST(RunConfig, NegativeMassIsRefused) {
  server::RunConfig c = test_support::shipped_run_config("three-story.yaml");
  c.building.story_mass_kip_s2_per_in[1] = -0.02;
  const std::string err = load_error(three_story_text(c));
  EXPECT_NE(err.find("story_mass_kip_s2_per_in"), std::string::npos) << err;
}

TEST(RunConfig, LcmTransportNeedsAUrl) {
  server::RunConfig c = test_support::shipped_run_config("three-story.yaml");
  c.transport.url = "";
  const std::string err = load_error(three_story_text(c));
  EXPECT_NE(err.find("transport.url"), std::string::npos) << err;
}

TEST(RunConfig, BadMessagePolicyAndRunKeyRulesAreStrict) {
  const server::RunConfig shipped = test_support::shipped_run_config("three-story.yaml");
  // Default drop; stop accepted; anything else refused naming the key.
  server::RunConfig c = shipped;
  c.transport.on_bad_message = "stop";
  const std::string ok_path = test_support::fresh_temp_dir("cfg") + "/ok.yaml";
  test_support::write_text(ok_path, three_story_text(c));
  EXPECT_EQ(server::load_run_config(ok_path).transport.on_bad_message, "stop");
  EXPECT_EQ(shipped.transport.on_bad_message, "drop");
  std::string err = load_error(std::regex_replace(three_story_text(), std::regex("  on_bad_message: drop\n"),
                                                  "  on_bad_message: ignore\n"));
  EXPECT_NE(err.find("transport.on_bad_message"), std::string::npos) << err;
  EXPECT_NE(err.find("ignore"), std::string::npos) << err;
  // A substructure started by hand must be given the run's key.
  c = shipped;
  c.damper.launch = "external";
  err = load_error(three_story_text(c));
  EXPECT_NE(err.find("transport.key_file"), std::string::npos) << err;
  EXPECT_NE(err.find("damper.launch is external"), std::string::npos) << err;
  c = shipped;
  c.transport.key_file = "/nonexistent/run.key";
  err = load_error(three_story_text(c));
  EXPECT_NE(err.find("transport.key_file"), std::string::npos) << err;
  EXPECT_NE(err.find("/nonexistent/run.key"), std::string::npos) << err;
}

TEST(RunConfig, EffectiveConfigLoadsBackToTheSameRun) {
  const server::RunConfig a = server::load_run_config(test_paths::source_dir() + "/configs/three-story.yaml");
  const std::string path = test_support::fresh_temp_dir("eff") + "/effective.yaml";
  test_support::write_text(path, server::run_config_to_yaml(a));
  const server::RunConfig b = server::load_run_config(path);
  EXPECT_EQ(b.building.story_mass_kip_s2_per_in, a.building.story_mass_kip_s2_per_in);
  EXPECT_EQ(b.damper_model.lugre.sigma0_kip_per_in, a.damper_model.lugre.sigma0_kip_per_in);
  EXPECT_EQ(b.damper_model.lugre.fc_bwd_kip, a.damper_model.lugre.fc_bwd_kip);
  EXPECT_EQ(b.damper_model.kind, a.damper_model.kind);
  EXPECT_EQ(b.damper_model.band_brake.wrap_angle_fwd_rad, a.damper_model.band_brake.wrap_angle_fwd_rad);
  EXPECT_EQ(b.damper_model.band_brake.backlash_in, a.damper_model.band_brake.backlash_in);
  EXPECT_EQ(b.damper_model.band_brake.actuator_tension_kip_per_in, a.damper_model.band_brake.actuator_tension_kip_per_in);
  EXPECT_EQ(b.record.duration_s, a.record.duration_s);
  EXPECT_EQ(b.transport.url, a.transport.url);
}

TEST(Transport, MulticastIsRefusedOutsideAPrivateNetworkNamespace) {
  if (messages::in_private_network_namespace()) GTEST_SKIP() << "this test already runs in a private netns";
  try {
    messages::open_lcm("udpm://239.255.76.67:7667?ttl=0", false);
    FAIL() << "multicast LCM opened in the machine's network namespace";
  } catch (const messages::TransportError& e) {
    EXPECT_NE(std::string(e.what()).find("private network namespace"), std::string::npos) << e.what();
  }
}

}  // namespace
