// Band-brake model (damper/model/band_brake_model.h) against its limits and closed forms:
// LuGre with the capstan Fc when backlash, hardening and geometry are off; the capstan ratio
// e^{μθ}; Eq. (4) as the linearization of (B1)-(B3); non-negative dissipation per cycle.
#include "damper/model/band_brake_config.h"
#include "damper/model/band_brake_model.h"
#include "damper/model/brfd_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace damper {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDt = 1.0 / 1024.0;

BandBrakeParams plain() {
  BandBrakeParams p;
  p.friction_coefficient = 0.3;
  p.wrap_angle_fwd_rad = 3.0 * kPi;
  p.wrap_angle_bwd_rad = 2.5 * kPi;
  p.lever_ratio = 2.0;
  p.slack_tension_fwd_kip = 0.03;
  p.slack_tension_bwd_kip = 0.05;
  p.band_stiffness_kip_per_in = 12.0;
  p.band_hardening_per_in = 0.0;
  p.backlash_in = 0.0;
  p.wrap_change_rad_per_in = 0.0;
  p.viscous_kip_s_per_in = 0.0;
  p.transition_exponent = 1.0;
  return p;
}

TEST(BandBrakeModel, CapstanRatioIsExpMuTheta) {
  // Euler-Eytelwein: a rope with μ = 0.3 on a full turn holds e^{0.6π} = 6.5862 times its slack end.
  EXPECT_NEAR(BandBrakeModel::capstan_ratio(0.3, 2.0 * kPi), 6.586065, 1e-5);
  EXPECT_DOUBLE_EQ(BandBrakeModel::capstan_ratio(0.0, 5.0), 1.0);
  const BandBrakeParams p = plain();
  const BandBrakeModel m(p);
  const BandTensions t = m.tensions({0.0, 1.0, p.actuator1_initial_in, p.actuator2_initial_in});
  EXPECT_NEAR(t.ratio_fwd, std::exp(0.3 * 3.0 * kPi), 1e-9);
  EXPECT_NEAR(t.ratio_bwd, std::exp(0.3 * 2.5 * kPi), 1e-9);
  // (B3): Fc = L (T_taut - T_slack) at slip, T_taut = E T_slack.
  EXPECT_NEAR(t.fc_fwd_kip, 2.0 * (t.ratio_fwd * 0.03 - 0.03), 1e-12);
  EXPECT_NEAR(t.fc_bwd_kip, 2.0 * (t.ratio_bwd * 0.05 - 0.05), 1e-12);
}

TEST(BandBrakeModel, ReducesToLugreWithTheCapstanFcWhenBacklashAndStiffeningAreOff) {
  const BandBrakeParams p = plain();
  BandBrakeModel band(p);
  const BandTensions t = band.tensions({0.0, 1.0, p.actuator1_initial_in, p.actuator2_initial_in});
  BrfdParams lp;
  lp.kind = DamperKind::passive_lugre;
  lp.lugre.sigma0_kip_per_in = p.lever_ratio * p.band_stiffness_kip_per_in;
  lp.lugre.sigma1_kip_s_per_in = 0.0;
  lp.lugre.sigma2_kip_s_per_in = 0.0;
  lp.lugre.fc_fwd_kip = lp.lugre.fs_fwd_kip = t.fc_fwd_kip;
  lp.lugre.fc_bwd_kip = lp.lugre.fs_bwd_kip = t.fc_bwd_kip;
  BrfdModel lugre(lp);
  double worst = 0.0;
  for (int i = 1; i < 4 * 1024; ++i) {
    const double time = i * kDt;
    const double x = 0.8 * std::sin(2.0 * kPi * 0.5 * time) + 0.1 * std::sin(2.0 * kPi * 3.0 * time);
    const double v = 0.8 * kPi * std::cos(kPi * time) + 0.6 * kPi * std::cos(6.0 * kPi * time);
    const double fb = band.step({x, v, p.actuator1_initial_in, p.actuator2_initial_in}, kDt);
    const double fl = lugre.step({x, v, 0.0, 0.0}, kDt);
    worst = std::max(worst, std::abs(fb - fl));
  }
  // Both use the exact solution of the same linear ODE per sample.
  EXPECT_LT(worst, 1e-9);
}

TEST(BandBrakeModel, SteadySlipReachesTheCapstanLimitAndTheLoadCellsFollowTheTensions) {
  BandBrakeParams p = plain();
  p.backlash_in = 0.05;
  p.band_hardening_per_in = 3.0;
  p.transition_exponent = 3.0;
  BandBrakeModel m(p);
  const BandBrakeInput fwd{0.0, 2.0, p.actuator1_initial_in, p.actuator2_initial_in};
  const BandTensions t = m.tensions(fwd);
  double f = 0.0;
  for (int i = 0; i < 4096; ++i) f = m.step(fwd, kDt);
  EXPECT_NEAR(f, t.fc_fwd_kip, 1e-6 * t.fc_fwd_kip);
  const std::array<double, 2> cells = m.actuator_forces_kip(m.stretch_in(), fwd);
  EXPECT_NEAR(cells[0], p.slack_tension_fwd_kip, 1e-12);                 // actuator 1: slack end
  EXPECT_NEAR(cells[1], t.ratio_fwd * p.slack_tension_fwd_kip, 1e-6);   // actuator 2: E T_slack
  const BandBrakeInput bwd{0.0, -2.0, p.actuator1_initial_in, p.actuator2_initial_in};
  for (int i = 0; i < 4096; ++i) f = m.step(bwd, kDt);
  EXPECT_NEAR(f, -t.fc_bwd_kip, 1e-6 * t.fc_bwd_kip);
  const std::array<double, 2> back = m.actuator_forces_kip(m.stretch_in(), bwd);
  EXPECT_NEAR(back[0], t.ratio_bwd * p.slack_tension_bwd_kip, 1e-6);    // actuator 1 taut
  EXPECT_NEAR(back[1], p.slack_tension_bwd_kip, 1e-12);
}

TEST(BandBrakeModel, BacklashHoldsZeroForceAcrossTheSlack) {
  BandBrakeParams p = plain();
  p.backlash_in = 0.1;
  BandBrakeModel m(p);
  // From the slack centre, the first 0.1 in of travel carries no force; then the band loads.
  double x = 0.0;
  const double v = 0.5;
  for (int i = 0; i < 200; ++i) {  // 0.0977 in
    x += v * kDt;
    EXPECT_EQ(m.step({x, v, p.actuator1_initial_in, p.actuator2_initial_in}, kDt), 0.0);
  }
  for (int i = 0; i < 20; ++i) x += v * kDt, m.step({x, v, p.actuator1_initial_in, p.actuator2_initial_in}, kDt);
  EXPECT_GT(m.force_kip(m.stretch_in(), {x, v, p.actuator1_initial_in, p.actuator2_initial_in}), 0.0);
}

TEST(BandBrakeModel, Eq4IsTheLinearizationOfTheTensionPath) {
  BandBrakeParams p = plain();
  p.actuator_tension_kip_per_in = {0.2, 0.15, 0.1, 0.25};
  const BandBrakeModel m(p);
  const double h = 1e-6;
  const BandBrakeInput base{0.0, 1.0, p.actuator1_initial_in, p.actuator2_initial_in};
  BandBrakeInput moved = base;
  moved.actuator1_in -= h;  // retract actuator 1
  const BandTensions t0 = m.tensions(base), t1 = m.tensions(moved);
  // dFc_fwd/dx1 = -L (E_fwd - 1) k_fwd,1 (the Eq. 4 gain); retracting raises friction.
  EXPECT_NEAR((t1.fc_fwd_kip - t0.fc_fwd_kip) / -h, -p.lever_ratio * (t0.ratio_fwd - 1.0) * 0.2, 1e-5);
  EXPECT_NEAR((t1.fc_bwd_kip - t0.fc_bwd_kip) / -h, -p.lever_ratio * (t0.ratio_bwd - 1.0) * 0.1, 1e-5);
  EXPECT_GT(t1.fc_fwd_kip, t0.fc_fwd_kip);
}

TEST(BandBrakeModel, DissipatedEnergyPerCycleIsNonNegative) {
  // Over closed displacement cycles of several amplitudes and frequencies, with every effect on
  // (backlash, hardening, sharp slip, geometry, viscous), ∮ F dx >= 0.
  BandBrakeParams p = plain();
  p.backlash_in = 0.06;
  p.band_hardening_per_in = 4.0;
  p.transition_exponent = 2.5;
  p.wrap_change_rad_per_in = 0.3;
  p.viscous_kip_s_per_in = 0.02;
  for (double amplitude : {0.02, 0.1, 0.5, 1.0}) {
    for (double freq : {0.5, 2.0}) {
      BandBrakeModel m(p);
      double energy = 0.0, x_prev = 0.0, f_prev = 0.0;
      const int n = static_cast<int>(1024 / freq);
      for (int cycle = 0; cycle < 3; ++cycle) {
        double e_cycle = 0.0;
        for (int i = 1; i <= n; ++i) {
          const double t = (cycle * n + i) * kDt;
          const double x = amplitude * std::sin(2.0 * kPi * freq * t);
          const double v = amplitude * 2.0 * kPi * freq * std::cos(2.0 * kPi * freq * t);
          const double f = m.step({x, v, p.actuator1_initial_in, p.actuator2_initial_in}, kDt);
          e_cycle += 0.5 * (f + f_prev) * (x - x_prev);  // trapezoidal ∮ F dx
          x_prev = x;
          f_prev = f;
        }
        if (cycle > 0) {
          EXPECT_GE(e_cycle, -1e-9) << "amplitude " << amplitude << " freq " << freq;
        }
        energy += e_cycle;
      }
      EXPECT_GT(energy, 0.0);
    }
  }
}

TEST(BandBrakeConfig, RoundTripsAndRejectsBadValues) {
  BandBrakeParams p = plain();
  p.backlash_in = 0.07;
  p.actuator_tension_kip_per_in = {0.1, 0.2, 0.3, 0.4};
  const std::string dir = ::testing::TempDir();
  const std::string file = dir + "/band_brake_roundtrip.yaml";
  std::ofstream(file) << band_brake_params_to_yaml(p);
  const common::YamlSection s = common::YamlSection::load_file(file);
  EXPECT_EQ(s.get_string("model"), "band_brake");
  const BandBrakeParams q = band_brake_params_from_yaml(s.section("band_brake"));
  EXPECT_DOUBLE_EQ(q.backlash_in, 0.07);
  EXPECT_DOUBLE_EQ(q.actuator_tension_kip_per_in[3], 0.4);
  EXPECT_DOUBLE_EQ(q.wrap_angle_bwd_rad, p.wrap_angle_bwd_rad);
  const std::string bad = dir + "/band_brake_bad.yaml";
  std::ofstream(bad) << "band_brake:\n  friction_coefficient: -0.2\n  wrap_angle_fwd_rad: 9\n  wrap_angle_bwd_rad: 9\n"
                        "  lever_ratio: 2\n  slack_tension_fwd_kip: 0.02\n  slack_tension_bwd_kip: 0.02\n"
                        "  band_stiffness_kip_per_in: 10\n";
  try {
    band_brake_params_from_yaml(common::YamlSection::load_file(bad).section("band_brake"));
    FAIL() << "negative friction coefficient accepted";
  } catch (const common::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("friction_coefficient"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace damper
