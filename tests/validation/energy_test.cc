#include "test_buildings.h"
#include "test_dampers.h"
#include "structure/energy.h"

#include "structure/ground_motion.h"
#include "structure/integrator.h"
#include "validation/monolithic_reference.h"
#include "in_process_run.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace structure {
namespace {

const std::string kRecords = PROJECT_RECORDS_DIR;

using test_dampers::lugre_damper;

using test_buildings::uniform_three_story;

EnergyLedger ledger_of(const ShearBuilding& b, const GroundMotion& gm, const ResponseHistory& h,
                       EnergyDefinition definition = EnergyDefinition::trapezoidal_state) {
  EnergyLedger e(b, definition);
  e.start(h.floor_disp_in[0], h.floor_vel_in_per_s[0], gm.accel_in_per_s2(h.time_s[0]), h.damper_force_kip[0]);
  for (std::size_t i = 1; i < h.size(); ++i) {
    e.add_step(h.time_s[i] - h.time_s[i - 1], h.floor_disp_in[i], h.floor_vel_in_per_s[i],
               gm.accel_in_per_s2(h.time_s[i]), h.damper_force_kip[i]);
  }
  return e;
}

void print(const char* what, const EnergyLedger& e) {
  std::printf("[ measured ] %s: E_in %.4f, kinetic %.4f, strain %.4f, damping %.4f, damper %.4f, algorithmic %.3e "
              "kip*in; balance error %.3e\n",
              what, e.input_kip_in(), e.kinetic_kip_in(), e.strain_kip_in(), e.inherent_damping_kip_in(),
              e.damper_kip_in(), e.algorithmic_kip_in(), e.balance_error());
}

// Energy balance at the end of the whole El Centro record (53.7 s), CR at Δt = 1/1024 s with
// the LuGre damper in-process. With CR's own velocity (the backward difference, half a step
// late) and the trapezoidal definition the residual is first order in Δt (bound 1 %); the
// centred-difference ledger (energy.h) is an exact identity for CR's displacement recurrence,
// the nonlinear damper force included: it closes to round-off (bound 1e-8) and its
// algorithmic term, computed from the recurrence residual, is round-off too.
TEST(EnergyLedger, CrWithDamperBalancesOverElCentro) {
  const GroundMotion gm = read_ground_motion(kRecords + "/ImperialValley1940_ElCentroArray9_180_NS_RSN6.AT2");
  for (double m : {0.2, 0.02}) {
    const ShearBuilding b(uniform_three_story(m, 150.0 * m / 0.2, true));
    const ResponseHistory h = testing_support::run_in_process(testing_support::in_process_config(
        uniform_three_story(m, 150.0 * m / 0.2, true), kRecords + "/ImperialValley1940_ElCentroArray9_180_NS_RSN6.AT2",
        lugre_damper(), 1.0 / 1024, -1));
    const EnergyLedger e = ledger_of(b, gm, h);
    print(m == 0.2 ? "CR + LuGre, m 0.2, k 150, El Centro 53.7 s, trapezoidal" : "CR + LuGre, m 0.02, k 15, El Centro 53.7 s, trapezoidal", e);
    EXPECT_LT(e.balance_error(), 0.01);
    EXPECT_GT(e.damper_kip_in(), 0.1 * e.input_kip_in());  // the damper dissipates a real share

    const EnergyLedger c = ledger_of(b, gm, h, EnergyDefinition::centred_difference);
    print("  same run, centred-difference ledger", c);
    EXPECT_LT(c.balance_error(), 1e-8);
    EXPECT_LT(std::abs(c.algorithmic_kip_in()), 1e-8 * c.input_kip_in());
    EXPECT_NEAR(c.damper_kip_in(), e.damper_kip_in(), 0.02 * e.damper_kip_in());
    EXPECT_NEAR(c.damper_kip_in_per_damper()(0), c.damper_kip_in(), 1e-9 * c.damper_kip_in());
  }
}

// A linear 3-story (the OpenSees case of opensees_regression_test.cc) under El Centro, each
// integrator feeding the ledger as the hybrid run does: balance error < 1e-8 for all. CR's
// algorithmic term is round-off, and so is KR-α's with ρ∞ = 1 (which is CR). With ρ∞ < 1 the
// numerical dissipation at these Ω ≤ 0.04 is ~Ω³ small: algorithmic term < 1e-4 of the input.
TEST(EnergyLedger, LinearThreeStoryClosesForEachIntegrator) {
  const GroundMotion gm = read_ground_motion(kRecords + "/ImperialValley1940_ElCentroArray9_180_NS_RSN6.AT2");
  BuildingParams p;
  p.story_mass_kip_s2_per_in = {0.5, 0.5, 0.5};
  p.story_stiffness_kip_per_in = {300, 250, 200};
  p.damping_ratios = {0.05, 0.05};
  const ShearBuilding b(p);
  const double dt = 1.0 / 1024;
  for (const IntegratorSettings& s : {IntegratorSettings{"cr", 1.0}, IntegratorSettings{"kr_alpha", 1.0},
                                      IntegratorSettings{"kr_alpha", 0.5}, IntegratorSettings{"kr_alpha", 0.0}}) {
    auto in = make_integrator(b, dt, s);
    EnergyLedger e(b);
    const Eigen::VectorXd none(0);
    in->initialize(gm.accel_in_per_s2(0), none);
    e.start(in->displacement_in(), in->velocity_in_per_s(), gm.accel_in_per_s2(0), none);
    const long steps = std::lround(gm.duration_s() / dt);
    for (long n = 1; n <= steps; ++n) {
      in->predict();
      in->complete(gm.accel_in_per_s2(n * dt), none);
      e.add_step(dt, in->displacement_in(), in->velocity_in_per_s(), gm.accel_in_per_s2(n * dt), none);
    }
    print(in->description().c_str(), e);
    EXPECT_LT(e.balance_error(), 1e-8);
    if (s.kind == "cr" || s.rho_inf == 1.0) {
      EXPECT_LT(std::abs(e.algorithmic_kip_in()), 1e-8 * e.input_kip_in());
    } else {
      EXPECT_LT(std::abs(e.algorithmic_kip_in()), 1e-4 * e.input_kip_in());
    }
  }
}

// Undamped SDOF free vibration at Ω = ωΔt = 0.5 with KR-α: the only sink is the method's
// numerical dissipation, so the ledger's algorithmic term must take the initial energy E₀ down
// as the root modulus says: after N steps E_alg/E₀ ≈ 1 − |λ|^{2N}, with |λ|² of the principal
// root fitted (Prony) on the displacement sequence, N chosen so that 2-5 ‰ of E₀ remains (the
// half-step stored energy of a discrete oscillation differs from |λ|^{2n}E₀ by O(Ω²) of what
// remains). Bound 0.5 % of E₀; balance error < 1e-8.
TEST(EnergyLedger, KrAlphaAlgorithmicEnergyIsItsNumericalDissipation) {
  BuildingParams p;
  p.story_mass_kip_s2_per_in = {0.2};
  p.story_stiffness_kip_per_in = {150.0};
  p.damping_modes = {1, 1};
  p.damping_ratios = {0.0, 0.0};
  const ShearBuilding b(p);
  const double omega = std::sqrt(150.0 / 0.2), dt = 0.5 / omega;
  for (double rho : {0.5, 0.0}) {
    auto in = make_integrator(b, dt, {"kr_alpha", rho});
    EnergyLedger e(b);
    const Eigen::VectorXd none(0), x0 = Eigen::VectorXd::Constant(1, 1.0), v0 = Eigen::VectorXd::Zero(1);
    in->initialize(x0, v0, 0.0, none);
    e.start(x0, v0, 0.0, none);
    const int steps = rho > 0 ? 3000 : 200;
    std::vector<double> x{1.0};
    for (int n = 1; n <= steps; ++n) {
      in->predict();
      in->complete(0.0, none);
      e.add_step(dt, in->displacement_in(), v0, 0.0, none);
      x.push_back(in->displacement_in()(0));
    }
    // |λ|² from the sequence itself: x_{n+1} = 2Re(λ) x_n − |λ|² x_{n−1} (least squares, after 80 steps).
    Eigen::MatrixXd a(15, 2);
    Eigen::VectorXd y(15);
    for (int r = 0; r < 15; ++r) {
      a(r, 0) = x[80 + r];
      a(r, 1) = -x[79 + r];
      y(r) = x[81 + r];
    }
    const double modulus2 = a.colPivHouseholderQr().solve(y)(1);
    const double expected = 1.0 - std::pow(modulus2, steps);
    const double got = e.algorithmic_kip_in() / e.input_kip_in();
    std::printf("[ measured ] KR-alpha rho_inf %.1f, undamped SDOF, Omega 0.5, %d steps: algorithmic %.5f of E0, "
                "1 - |lambda|^2N = %.5f, balance error %.2e\n", rho, steps, got, expected, e.balance_error());
    EXPECT_NEAR(got, expected, 0.005);
    EXPECT_LT(e.balance_error(), 1e-8);
  }
}

// The same balance from the CVODE reference output (independent integrator, same ledger).
TEST(EnergyLedger, CvodeWithDamperBalancesOverElCentro) {
  const GroundMotion gm = read_ground_motion(kRecords + "/ImperialValley1940_ElCentroArray9_180_NS_RSN6.AT2");
  const ShearBuilding b(uniform_three_story(0.02, 15.0, true));
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
  const ShearBuilding b(uniform_three_story(0.2, 150.0, true));
  EnergyLedger e(b);
  EXPECT_THROW(EnergyLedger(b).add_step(0.01, Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(3), 0.0, Eigen::VectorXd::Zero(1)),
               std::logic_error);
  const Eigen::VectorXd z3 = Eigen::VectorXd::Zero(3), z1 = Eigen::VectorXd::Zero(1);
  EXPECT_THROW(e.add_step(0.01, z3, z3, 0.0, z1), std::logic_error);
  EXPECT_THROW(e.start(z3, z3, 0.0, Eigen::VectorXd(0)), std::invalid_argument);
  e.start(z3, z3, 0.0, z1);
  EXPECT_EQ(e.balance_error(), 0.0);
  e.add_step(0.01, z3, z3, 0.0, z1);
  EXPECT_THROW(e.add_step(0.02, z3, z3, 0.0, z1), std::invalid_argument);  // centred: uniform step
}

}  // namespace
}  // namespace structure
