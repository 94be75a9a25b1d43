// One serializer per config, used for reading and writing: what a writer prints, the strict
// loader reads back to the same values, to the last bit (17 significant digits). For every
// shipped run config (found by globbing configs/): load -> run_config_to_yaml -> load ->
// run_config_to_yaml gives the same text, and the damper model block alone round-trips
// through brfd_params_to_yaml the same way. This is what makes effective-config.yaml re-runnable
// and damper-model.yaml (read by the LCM substructure) the in-process model.
#include "damper/model/brfd_config.h"
#include "run_process.h"
#include "server/run/run_config.h"
#include "test_paths.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>

namespace fs = std::filesystem;

namespace {

// The YAML without its comment lines (they say where the first load read things from).
std::string without_source_line(const std::string& yaml) {
  std::string out;
  std::istringstream in(yaml);
  for (std::string line; std::getline(in, line);)
    if (line.find_first_not_of(' ') == std::string::npos || line[line.find_first_not_of(' ')] != '#') out += line + "\n";
  return out;
}

TEST(ConfigRoundTrip, EveryShippedRunConfigIsAFixedPointOfItsSerializer) {
  const std::string dir = test_support::fresh_temp_dir("round-trip");
  int checked = 0;
  for (const auto& e : fs::directory_iterator(test_paths::source_dir() + "/configs")) {
    if (e.path().extension() != ".yaml" || !YAML::LoadFile(e.path().string())["building"]) continue;
    const server::RunConfig first = server::load_run_config(e.path().string());
    const std::string text1 = server::run_config_to_yaml(first);
    const std::string path = dir + "/" + e.path().filename().string();
    test_support::write_text(path, text1);
    const server::RunConfig second = server::load_run_config(path);
    EXPECT_EQ(without_source_line(server::run_config_to_yaml(second)), without_source_line(text1)) << e.path();
    EXPECT_EQ(second.dt_s, first.dt_s) << e.path();
    EXPECT_EQ(second.building.story_stiffness_kip_per_in, first.building.story_stiffness_kip_per_in) << e.path();
    EXPECT_EQ(second.damper_model.lugre.sigma0_kip_per_in, first.damper_model.lugre.sigma0_kip_per_in) << e.path();
    ++checked;
  }
  EXPECT_GE(checked, 3);
}

TEST(ConfigRoundTrip, DamperModelSurvivesItsYamlToTheLastBit) {
  damper::BrfdParams p = damper::load_brfd_params(test_paths::source_dir() + "/configs/brfd-default.yaml");
  p.lugre.sigma0_kip_per_in = std::nextafter(p.lugre.sigma0_kip_per_in, 1e9);  // needs all 17 digits
  p.lugre.fc_fwd_kip = 1.0 / 3.0;
  p.semiactive.actuator2_initial_in = std::nextafter(0.8559, 1.0);
  const std::string path = test_support::fresh_temp_dir("round-trip-damper") + "/damper.yaml";
  test_support::write_text(path, damper::brfd_params_to_yaml(p));
  const damper::BrfdParams q = damper::load_brfd_params(path);
  EXPECT_EQ(q.lugre.sigma0_kip_per_in, p.lugre.sigma0_kip_per_in);
  EXPECT_EQ(q.lugre.fc_fwd_kip, p.lugre.fc_fwd_kip);
  EXPECT_EQ(q.semiactive.actuator2_initial_in, p.semiactive.actuator2_initial_in);
  EXPECT_EQ(damper::brfd_params_to_yaml(q), damper::brfd_params_to_yaml(p));
}

}  // namespace
