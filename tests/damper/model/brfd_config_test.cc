// The shipped damper configs load strictly and carry the paper's Tables 1-2; every shipped
// config is smoke-run over a short sinusoid.
#include "damper/model/brfd_config.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace damper {
namespace {

const std::string kRoot = BRFD_SOURCE_DIR;

TEST(BrfdConfig, SemiactiveConfigHoldsTables1And2) {
  const BrfdParams p = load_brfd_params(kRoot + "/configs/brfd-semiactive.yaml");
  EXPECT_EQ(p.kind, DamperKind::semiactive);
  const double m[4][2] = {{-0.14, -0.15}, {-15.29, -13.00}, {-16.66, -15.77}, {-0.13, -0.15}};
  const double c[4] = {119.68, 2.10, 1.94, 123.31};
  for (int i = 0; i < 4; ++i) {
    EXPECT_DOUBLE_EQ(p.semiactive.scaling[i], c[i]);
    for (int j = 0; j < 2; ++j) EXPECT_DOUBLE_EQ(p.semiactive.slopes_kip_per_in[i][j], m[i][j]);
  }
  EXPECT_DOUBLE_EQ(p.semiactive.actuator1_initial_in, 0.655);
  EXPECT_DOUBLE_EQ(p.semiactive.actuator2_initial_in, 0.8559);
}

TEST(BrfdConfig, DefaultConfigIsPassiveLugre) {
  const BrfdParams p = load_brfd_params(kRoot + "/configs/brfd-default.yaml");
  EXPECT_EQ(p.kind, DamperKind::passive_lugre);
  EXPECT_GT(p.lugre.fs_fwd_kip, 0.0);
}

TEST(BrfdConfig, ShippedConfigsSmokeRun) {
  for (const char* name : {"brfd-default.yaml", "brfd-semiactive.yaml"}) {
    BrfdModel m(load_brfd_params(kRoot + "/configs/" + name));
    double peak = 0.0;
    for (int k = 0; k < 2048; ++k) {
      const double t = k / 1024.0;
      DamperInput in;
      in.drum_disp_in = std::sin(M_PI * t);
      in.drum_vel_in_per_s = M_PI * std::cos(M_PI * t);
      in.actuator1_in = m.params().semiactive.actuator1_initial_in;
      in.actuator2_in = m.params().semiactive.actuator2_initial_in;
      const double f = m.step(in, 1.0 / 1024.0);
      ASSERT_TRUE(std::isfinite(f)) << name;
      peak = std::max(peak, std::abs(f));
    }
    EXPECT_GT(peak, 1.0) << name;
    EXPECT_LT(peak, 20.0) << name;
  }
}

TEST(BrfdConfig, RoundTripsThroughYamlIncludingBOfVelocity) {
  BrfdParams p = load_brfd_params(kRoot + "/configs/brfd-semiactive.yaml");
  p.b_of_velocity.speed_in_per_s = {0.0, 2.0};
  p.b_of_velocity.fwd_kip = {2.0, 2.5};
  p.b_of_velocity.bwd_kip = {1.0, 1.5};
  const std::string path = std::string(BRFD_TEST_OUT_DIR) + "/roundtrip.yaml";
  std::filesystem::create_directories(BRFD_TEST_OUT_DIR);
  std::ofstream(path) << brfd_params_to_yaml(p);
  const BrfdParams q = load_brfd_params(path);
  EXPECT_DOUBLE_EQ(q.lugre.sigma2_kip_s_per_in, p.lugre.sigma2_kip_s_per_in);
  EXPECT_EQ(q.b_of_velocity.fwd_kip, p.b_of_velocity.fwd_kip);
  EXPECT_EQ(q.semiactive.scaling, p.semiactive.scaling);
}

TEST(BrfdConfig, BadBOfVelocityIsAnErrorNamingTheKey) {
  const std::string path = std::string(BRFD_TEST_OUT_DIR) + "/bad_b.yaml";
  std::filesystem::create_directories(BRFD_TEST_OUT_DIR);
  std::ofstream(path) << "model: semiactive\nlugre:\n  sigma0_kip_per_in: 10\n  sigma1_kip_s_per_in: 0\n"
                         "  sigma2_kip_s_per_in: 0\n  fs_fwd_kip: 2\n  fs_bwd_kip: 2\n  fc_fwd_kip: 1\n"
                         "  fc_bwd_kip: 1\n  vs_in_per_s: 1\nb_of_velocity:\n  speed_in_per_s: [0, 1]\n"
                         "  fwd_kip: [1]\n  bwd_kip: [1, 1]\n";
  try {
    load_brfd_params(path);
    FAIL() << "expected ConfigError";
  } catch (const common::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("b_of_velocity.fwd_kip"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace damper
