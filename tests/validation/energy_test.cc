#include "structure/energy.h"

#include "structure/ground_motion.h"
#include "validation/monolithic_reference.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace structure {
namespace {

const std::string kRecords = PROJECT_RECORDS_DIR;

damper::BrfdParams lugre_damper() {
  damper::BrfdParams d;
  d.kind = damper::DamperKind::passive_lugre;
  d.lugre.sigma0_kip_per_in = 60.0;
  d.lugre.sigma1_kip_s_per_in = 0.5;
  d.lugre.sigma2_kip_s_per_in = 0.05;
  d.lugre.fs_fwd_kip = d.lugre.fs_bwd_kip = 2.4;
  d.lugre.fc_fwd_kip = d.lugre.fc_bwd_kip = 2.0;
  d.lugre.vs_in_per_s = 0.5;
  return d;
}

BuildingParams three_story(double m, double k, bool with_damper) {
  BuildingParams p;
  p.story_mass_kip_s2_per_in = {m, m, m};
  p.story_stiffness_kip_per_in = {k, k, k};
  if (with_damper) p.dampers = {{1, 1.0}};
  return p;
}

EnergyLedger ledger_of(const ShearBuilding& b, const GroundMotion& gm, const ResponseHistory& h) {
  EnergyLedger e(b);
  e.start(h.floor_disp_in[0], h.floor_vel_in_per_s[0], gm.accel_in_per_s2(h.time_s[0]), h.damper_force_kip[0]);
  for (std::size_t i = 1; i < h.size(); ++i) {
    e.add_step(h.time_s[i] - h.time_s[i - 1], h.floor_disp_in[i], h.floor_vel_in_per_s[i],
               gm.accel_in_per_s2(h.time_s[i]), h.damper_force_kip[i]);
  }
  return e;
}

void print(const char* what, const EnergyLedger& e) {
  std::printf("[ measured ] %s: E_in %.4f, kinetic %.4f, strain %.4f, damping %.4f, damper %.4f kip*in; "
              "balance error %.4f%%\n",
              what, e.input_kip_in(), e.kinetic_kip_in(), e.strain_kip_in(), e.inherent_damping_kip_in(),
              e.damper_kip_in(), 100 * e.balance_error());
}

// Energy balance at the end of the whole El Centro record (53.7 s), CR at Δt = 1/1024 s with
// the LuGre damper in-process: input = kinetic + strain + inherent damping + damper within 1%.
TEST(EnergyLedger, CrWithDamperBalancesOverElCentro) {
  const GroundMotion gm = read_ground_motion(kRecords + "/ImperialValley1940_ElCentroArray9_180_NS_RSN6.AT2");
  for (double m : {0.2, 0.02}) {
    const ShearBuilding b(three_story(m, 150.0 * m / 0.2, true));
    const ResponseHistory h = simulate_cr_in_process(b, gm, {lugre_damper()}, 1.0 / 1024, -1);
    const EnergyLedger e = ledger_of(b, gm, h);
    print(m == 0.2 ? "CR + LuGre, m 0.2, k 150, El Centro 53.7 s" : "CR + LuGre, m 0.02, k 15, El Centro 53.7 s", e);
    EXPECT_LT(e.balance_error(), 0.01);
    EXPECT_GT(e.damper_kip_in(), 0.1 * e.input_kip_in());  // the damper dissipates a real share

    // CR's velocity is the backward difference (x₊ − x)/Δt, so as ẋ(t) it lags half a step and
    // the balance error above is first order in Δt. With the centred velocity (v_n + v_{n+1})/2
    // the same ledger closes to round-off level: the residual is the velocity definition, not
    // lost energy. Bound 1e-4.
    EnergyLedger centred(b);
    centred.start(h.floor_disp_in[0], h.floor_vel_in_per_s[0], gm.accel_in_per_s2(0.0), h.damper_force_kip[0]);
    for (std::size_t i = 1; i < h.size(); ++i) {
      const Eigen::VectorXd v = i + 1 < h.size()
                                    ? Eigen::VectorXd(0.5 * (h.floor_vel_in_per_s[i] + h.floor_vel_in_per_s[i + 1]))
                                    : h.floor_vel_in_per_s[i];
      centred.add_step(h.time_s[i] - h.time_s[i - 1], h.floor_disp_in[i], v, gm.accel_in_per_s2(h.time_s[i]),
                       h.damper_force_kip[i]);
    }
    std::printf("[ measured ]   with the centred CR velocity: balance error %.2e%%\n", 100 * centred.balance_error());
    EXPECT_LT(centred.balance_error(), 1e-4);
  }
}

// The same balance from the CVODE reference output (independent integrator, same ledger).
TEST(EnergyLedger, CvodeWithDamperBalancesOverElCentro) {
  const GroundMotion gm = read_ground_motion(kRecords + "/ImperialValley1940_ElCentroArray9_180_NS_RSN6.AT2");
  const ShearBuilding b(three_story(0.02, 15.0, true));
  ReferenceOptions opt;
  opt.duration_s = 20.0;
  const EnergyLedger e = ledger_of(b, gm, simulate_monolithic(b, gm, {lugre_damper()}, opt));
  print("CVODE + LuGre, m 0.02, k 15, El Centro 0-20 s", e);
  EXPECT_LT(e.balance_error(), 0.01);
}

// SDOF free vibration from x0 without ground motion: the initial strain energy ½kx0² counts as
// input and is all dissipated by Rayleigh damping after many cycles (closed form). Bound 0.5%.
TEST(EnergyLedger, FreeVibrationDissipatesInitialEnergy) {
  BuildingParams p;
  p.story_mass_kip_s2_per_in = {0.2};
  p.story_stiffness_kip_per_in = {150.0};
  p.damping_modes = {1, 1};
  p.damping_ratios = {0.05, 0.05};
  const ShearBuilding b(p);
  GroundMotion none;
  none.dt_s = 0.01;
  none.accel_g = {0.0, 0.0};
  ReferenceOptions opt;
  opt.duration_s = 10.0;  // 44 periods, amplitude decays by e^{-0.05·ω·10} ≈ 1e-6
  opt.initial_floor_disp_in = Eigen::VectorXd::Constant(1, 1.0);
  const EnergyLedger e = ledger_of(b, none, simulate_monolithic(b, none, {}, opt));
  print("SDOF free vibration, CVODE", e);
  EXPECT_NEAR(e.input_kip_in(), 0.5 * 150.0, 1e-12);
  EXPECT_NEAR(e.inherent_damping_kip_in(), 75.0, 0.005 * 75.0);
  EXPECT_LT(e.balance_error(), 0.005);
}

TEST(EnergyLedger, MisuseThrows) {
  const ShearBuilding b(three_story(0.2, 150.0, true));
  EnergyLedger e(b);
  const Eigen::VectorXd z3 = Eigen::VectorXd::Zero(3), z1 = Eigen::VectorXd::Zero(1);
  EXPECT_THROW(e.add_step(0.01, z3, z3, 0.0, z1), std::logic_error);
  EXPECT_THROW(e.start(z3, z3, 0.0, Eigen::VectorXd(0)), std::invalid_argument);
  e.start(z3, z3, 0.0, z1);
  EXPECT_EQ(e.balance_error(), 0.0);
}

}  // namespace
}  // namespace structure
