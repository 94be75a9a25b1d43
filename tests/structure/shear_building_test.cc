#include "structure/shear_building.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <string>

namespace structure {
namespace {

constexpr double kPi = 3.14159265358979323846;

BuildingParams uniform(int n, double m, double k) {
  BuildingParams p;
  p.story_mass_kip_s2_per_in.assign(n, m);
  p.story_stiffness_kip_per_in.assign(n, k);
  if (n == 1) p.damping_modes = {1, 1};
  return p;
}

// Closed form for a uniform shear building (fixed base, free top):
// ω_j = 2·sqrt(k/m)·sin((2j−1)π / (2(2N+1))).
void expect_uniform_periods(int n) {
  const double m = 0.2, k = 150.0;
  const ShearBuilding b(uniform(n, m, k));
  ASSERT_EQ(b.modal().omega_rad_per_s.size(), n);
  for (int j = 1; j <= n; ++j) {
    const double exact = 2.0 * std::sqrt(k / m) * std::sin((2 * j - 1) * kPi / (2.0 * (2 * n + 1)));
    EXPECT_NEAR(b.modal().omega_rad_per_s(j - 1), exact, 1e-10 * exact) << "N = " << n << ", mode " << j;
    EXPECT_NEAR(b.modal().period_s(j - 1), 2.0 * kPi / exact, 1e-10 * 2.0 * kPi / exact);
  }
}

TEST(ShearBuilding, UniformThreeStoryPeriodsMatchClosedForm) { expect_uniform_periods(3); }
TEST(ShearBuilding, UniformTenStoryPeriodsMatchClosedForm) { expect_uniform_periods(10); }

TEST(ShearBuilding, ModeShapesAreMassNormalizedAndDiagonalizeK) {
  BuildingParams p;
  p.story_mass_kip_s2_per_in = {0.3, 0.25, 0.2, 0.1};
  p.story_stiffness_kip_per_in = {200.0, 180.0, 150.0, 90.0};
  const ShearBuilding b(p);
  const Eigen::MatrixXd& phi = b.modal().mode_shapes;
  const Eigen::MatrixXd mm = phi.transpose() * b.mass() * phi;
  const Eigen::MatrixXd kk = phi.transpose() * b.stiffness() * phi;
  const Eigen::VectorXd w2 = b.modal().omega_rad_per_s.array().square();
  EXPECT_LT((mm - Eigen::MatrixXd::Identity(4, 4)).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((kk - Eigen::MatrixXd(w2.asDiagonal())).cwiseAbs().maxCoeff(), 1e-9 * w2.maxCoeff());
  for (int j = 0; j < 4; ++j) EXPECT_GE(phi(3, j), 0.0);
  for (int j = 1; j < 4; ++j) EXPECT_GT(b.modal().omega_rad_per_s(j), b.modal().omega_rad_per_s(j - 1));
}

TEST(ShearBuilding, ThreeStoryMatricesAndInfluence) {
  BuildingParams p;
  p.story_mass_kip_s2_per_in = {1.0, 2.0, 3.0};
  p.story_stiffness_kip_per_in = {10.0, 20.0, 30.0};
  const ShearBuilding b(p);
  Eigen::MatrixXd k_expected(3, 3);
  k_expected << 30, -20, 0, -20, 50, -30, 0, -30, 30;
  EXPECT_EQ(b.stiffness(), k_expected);
  EXPECT_EQ(b.mass(), Eigen::Vector3d(1, 2, 3).asDiagonal().toDenseMatrix());
  EXPECT_EQ(b.influence(), Eigen::VectorXd::Ones(3));
  EXPECT_EQ(b.num_stories(), 3);
  EXPECT_EQ(b.num_dampers(), 0);
  EXPECT_EQ(b.damper_gamma().rows(), 3);
  EXPECT_EQ(b.damper_gamma().cols(), 0);
}

// Modal damping ratio ζ_j = φ_jᵀCφ_j / (2ω_j) for mass-normalized φ_j: must equal the
// requested ratios at the two chosen modes.
TEST(ShearBuilding, RayleighDampingGivesRequestedRatios) {
  BuildingParams p = uniform(5, 0.2, 150.0);
  p.damping_modes = {1, 3};
  p.damping_ratios = {0.02, 0.05};
  const ShearBuilding b(p);
  for (int i = 0; i < 2; ++i) {
    const int mode = p.damping_modes[i] - 1;
    const Eigen::VectorXd phi = b.modal().mode_shapes.col(mode);
    const double zeta = phi.dot(b.damping() * phi) / (2.0 * b.modal().omega_rad_per_s(mode));
    EXPECT_NEAR(zeta, p.damping_ratios[i], 1e-12);
  }
  EXPECT_LT((b.damping() - (b.rayleigh_alpha() * b.mass() + b.rayleigh_beta() * b.stiffness()))
                .cwiseAbs()
                .maxCoeff(),
            1e-14);
}

TEST(ShearBuilding, SingleStoryUsesModeOneTwice) {
  BuildingParams p = uniform(1, 0.2, 150.0);
  p.damping_ratios = {0.05, 0.05};
  const ShearBuilding b(p);
  const double w = std::sqrt(150.0 / 0.2);
  EXPECT_NEAR(b.damping()(0, 0), 2.0 * 0.05 * w * 0.2, 1e-12);
  p.damping_modes = {1, 2};
  EXPECT_THROW(ShearBuilding{p}, std::invalid_argument);
}

TEST(ShearBuilding, DamperGammaMapsDriftToDrum) {
  BuildingParams p = uniform(3, 0.2, 150.0);
  p.dampers = {{1, 1.0}, {2, 1.5}};
  const ShearBuilding b(p);
  const Eigen::Vector3d x(0.5, 1.25, 2.0);
  const Eigen::VectorXd drum = b.damper_gamma().transpose() * x;
  EXPECT_DOUBLE_EQ(drum(0), 0.5);
  EXPECT_DOUBLE_EQ(drum(1), 1.5 * (1.25 - 0.5));
  const Eigen::VectorXd drift = b.interstory_drift(x);
  EXPECT_DOUBLE_EQ(drift(0), 0.5);
  EXPECT_DOUBLE_EQ(drift(1), 0.75);
  EXPECT_DOUBLE_EQ(drift(2), 0.75);
  EXPECT_THROW(b.interstory_drift(Eigen::VectorXd::Zero(2)), std::invalid_argument);
}

TEST(ShearBuilding, RejectsBadParams) {
  BuildingParams p = uniform(3, 0.2, 150.0);
  p.story_mass_kip_s2_per_in[1] = -0.2;
  EXPECT_THROW(ShearBuilding{p}, std::invalid_argument);
  p = uniform(3, 0.2, 150.0);
  p.story_stiffness_kip_per_in[2] = 0.0;
  EXPECT_THROW(ShearBuilding{p}, std::invalid_argument);
  p = uniform(3, 0.2, 150.0);
  p.story_stiffness_kip_per_in.pop_back();
  EXPECT_THROW(ShearBuilding{p}, std::invalid_argument);
  p = uniform(3, 0.2, 150.0);
  p.dampers = {{4, 1.0}};
  EXPECT_THROW(ShearBuilding{p}, std::invalid_argument);
  p = uniform(3, 0.2, 150.0);
  p.damping_modes = {1, 4};
  EXPECT_THROW(ShearBuilding{p}, std::invalid_argument);
  EXPECT_THROW(ShearBuilding{BuildingParams{}}, std::invalid_argument);
}

// ---- YAML ----

common::YamlSection section(const std::string& text) {
  return common::YamlSection(YAML::Load(text), "building_test.yaml", "building");
}

const char* kGoodYaml = R"(story_mass_kip_s2_per_in: [0.2, 0.2, 0.15]
story_stiffness_kip_per_in: [150, 140, 120]
damping:
  modes: [1, 3]
  ratios: [0.02, 0.03]
dampers:
  - story: 1
    drum_per_drift: 1.0
  - story: 3
    drum_per_drift: 0.5
)";

TEST(BuildingYaml, ReadsAllKeysAndRoundTrips) {
  const BuildingParams p = building_params_from_yaml(section(kGoodYaml));
  EXPECT_EQ(p.story_mass_kip_s2_per_in, (std::vector<double>{0.2, 0.2, 0.15}));
  EXPECT_EQ(p.story_stiffness_kip_per_in, (std::vector<double>{150, 140, 120}));
  EXPECT_EQ(p.damping_modes, (std::array<int, 2>{{1, 3}}));
  EXPECT_EQ(p.damping_ratios, (std::array<double, 2>{{0.02, 0.03}}));
  ASSERT_EQ(p.dampers.size(), 2u);
  EXPECT_EQ(p.dampers[1].story, 3);
  EXPECT_EQ(p.dampers[1].drum_per_drift, 0.5);

  const BuildingParams q = building_params_from_yaml(section(building_params_to_yaml(p)));
  EXPECT_EQ(q.story_mass_kip_s2_per_in, p.story_mass_kip_s2_per_in);
  EXPECT_EQ(q.story_stiffness_kip_per_in, p.story_stiffness_kip_per_in);
  EXPECT_EQ(q.damping_modes, p.damping_modes);
  EXPECT_EQ(q.damping_ratios, p.damping_ratios);
  ASSERT_EQ(q.dampers.size(), 2u);
  EXPECT_EQ(q.dampers[0].story, 1);
  EXPECT_EQ(q.dampers[1].drum_per_drift, 0.5);
}

TEST(BuildingYaml, DampingAndDampersAreOptional) {
  const BuildingParams p = building_params_from_yaml(
      section("story_mass_kip_s2_per_in: [0.2, 0.2]\nstory_stiffness_kip_per_in: [150, 150]\n"));
  EXPECT_EQ(p.damping_modes, (std::array<int, 2>{{1, 2}}));
  EXPECT_EQ(p.damping_ratios, (std::array<double, 2>{{0.02, 0.02}}));
  EXPECT_TRUE(p.dampers.empty());
  const BuildingParams q = building_params_from_yaml(section(building_params_to_yaml(p)));
  EXPECT_TRUE(q.dampers.empty());
}

// Expects a ConfigError whose message contains every fragment.
void expect_config_error(const std::string& yaml, std::initializer_list<const char*> fragments) {
  try {
    building_params_from_yaml(section(yaml));
    ADD_FAILURE() << "no ConfigError for:\n" << yaml;
  } catch (const common::ConfigError& e) {
    const std::string msg = e.what();
    for (const char* f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << "'" << f << "' not in: " << msg;
  }
}

TEST(BuildingYaml, NegativeMassNamesTheEntry) {
  expect_config_error("story_mass_kip_s2_per_in: [0.2, -1, 0.2]\nstory_stiffness_kip_per_in: [1, 1, 1]\n",
                      {"building_test.yaml:1", "building.story_mass_kip_s2_per_in[1]", "must be > 0", "-1"});
}

TEST(BuildingYaml, ZeroStiffnessNamesTheEntry) {
  expect_config_error("story_mass_kip_s2_per_in: [0.2]\nstory_stiffness_kip_per_in: [0]\n",
                      {"building.story_stiffness_kip_per_in[0]", "must be > 0"});
}

TEST(BuildingYaml, UnknownKeyIsNamed) {
  expect_config_error(
      "story_mass_kip_s2_per_in: [0.2]\nstory_stiffness_kip_per_in: [150]\nstory_masses: [1]\n",
      {"building_test.yaml:3", "building.story_masses", "unknown key"});
  expect_config_error(std::string(kGoodYaml) + "  - story: 2\n    drum_ratio: 1\n",
                      {"building.dampers[2].drum_ratio", "unknown key"});
}

TEST(BuildingYaml, MissingKeyIsNamed) {
  expect_config_error("story_mass_kip_s2_per_in: [0.2]\n",
                      {"building.story_stiffness_kip_per_in", "missing required key"});
  expect_config_error(
      "story_mass_kip_s2_per_in: [0.2]\nstory_stiffness_kip_per_in: [150]\ndamping: {modes: [1, 1]}\n",
      {"building.damping.ratios", "missing required key"});
}

TEST(BuildingYaml, OtherErrorsAreNamed) {
  expect_config_error("story_mass_kip_s2_per_in: [0.2, 0.2]\nstory_stiffness_kip_per_in: [150]\n",
                      {"building.story_stiffness_kip_per_in", "has 1 entries"});
  expect_config_error(
      "story_mass_kip_s2_per_in: [0.2]\nstory_stiffness_kip_per_in: [150]\ndampers:\n  - story: 2\n",
      {"building_test.yaml:4", "building.dampers[0].story", "must be in 1..1"});
  expect_config_error(
      "story_mass_kip_s2_per_in: [0.2]\nstory_stiffness_kip_per_in: [150]\ndamping: {modes: [1, 2], ratios: [0.02, 0.02]}\n",
      {"building.damping.modes[1]", "out of range 1..1"});
  expect_config_error(
      "story_mass_kip_s2_per_in: [0.2, 0.3]\nstory_stiffness_kip_per_in: [150, 150]\ndamping: {modes: [1, 2], ratios: [0.02, 1.5]}\n",
      {"building.damping.ratios[1]", "[0, 1)"});
  expect_config_error("story_mass_kip_s2_per_in: [0.2, abc]\nstory_stiffness_kip_per_in: [150, 150]\n",
                      {"building.story_mass_kip_s2_per_in", "not a number"});
}

}  // namespace
}  // namespace structure
