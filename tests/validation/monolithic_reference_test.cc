#include "test_buildings.h"
#include "test_dampers.h"
#include "validation/monolithic_reference.h"

#include "damper/model/brfd_config.h"

#include "in_process_run.h"
#include "sdof_closed_form.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace structure {
namespace {

constexpr double kPi = 3.14159265358979323846;
const std::string kRecords = PROJECT_RECORDS_DIR;

using test_buildings::sdof;

GroundMotion zero_motion(double dt, double duration) {
  GroundMotion gm;
  gm.source = "zero";
  gm.dt_s = dt;
  gm.accel_g.assign(static_cast<std::size_t>(std::lround(duration / dt)) + 1, 0.0);
  return gm;
}

// CVODE at rtol 1e-8, atol 1e-10: the global error over a few seconds is expected near
// 1e-7 of the amplitude; bound 1e-5 in for x0 = 1 in.
TEST(MonolithicReference, SdofFreeVibrationMatchesClosedForm) {
  const double m = 0.2, k = 150.0, zeta = 0.05, x0 = 1.0, v0 = -3.0;
  const ShearBuilding b(sdof(m, k, zeta));
  const testing::Sdof exact{std::sqrt(k / m), zeta};
  ReferenceOptions opt;
  opt.duration_s = 3.0;
  opt.initial_floor_disp_in = Eigen::VectorXd::Constant(1, x0);
  opt.initial_floor_vel_in_per_s = Eigen::VectorXd::Constant(1, v0);
  const ResponseHistory h = simulate_monolithic(b, zero_motion(0.01, 3.0), {}, opt);
  ASSERT_EQ(h.size(), 3u * 1024 + 1);
  double err = 0.0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    err = std::max(err, std::abs(h.floor_disp_in[i](0) - exact.free_disp(h.time_s[i], x0, v0)));
  }
  std::printf("[ measured ] CVODE SDOF free vibration: max error %.3e in\n", err);
  EXPECT_LT(err, 1e-5);
  EXPECT_NEAR(h.time_s.back(), 3.0, 1e-12);
}

// Harmonic 0.3 g at 3 Hz, from rest, 4 s. The record samples the sine every 1/8192 s, and its
// linear interpolation differs from the sine by at most a(Ωh)²/8 = 6.6e-7·a, so the bound is
// 1e-5 of the peak response.
TEST(MonolithicReference, SdofHarmonicMatchesClosedForm) {
  const double m = 0.2, k = 150.0, zeta = 0.05;
  const ShearBuilding b(sdof(m, k, zeta));
  const testing::Sdof exact{std::sqrt(k / m), zeta};
  const double a_g = 0.3, big_omega = 2 * kPi * 3.0, t_end = 4.0, h_rec = 1.0 / 8192;
  GroundMotion gm;
  gm.source = "sine";
  gm.dt_s = h_rec;
  for (long i = 0; i <= std::lround(t_end / h_rec); ++i) gm.accel_g.push_back(a_g * std::sin(big_omega * i * h_rec));
  ReferenceOptions opt;
  opt.duration_s = t_end;
  const ResponseHistory h = simulate_monolithic(b, gm, {}, opt);
  double err = 0.0, peak = 0.0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double xe = exact.harmonic_disp(h.time_s[i], a_g * kGravity_in_per_s2, big_omega);
    err = std::max(err, std::abs(h.floor_disp_in[i](0) - xe));
    peak = std::max(peak, std::abs(xe));
  }
  std::printf("[ measured ] CVODE SDOF harmonic: max error %.3e in = %.2e of peak %.4f in\n", err, err / peak, peak);
  EXPECT_LT(err, 1e-5 * peak);
}

TEST(MonolithicReference, DamperCountMustMatchPlacements) {
  BuildingParams p = sdof(0.2, 150, 0.02);
  p.dampers = {{1, 1.0}};
  const ShearBuilding b(p);
  ReferenceOptions opt;
  opt.duration_s = 0.1;
  EXPECT_THROW(simulate_monolithic(b, zero_motion(0.01, 0.1), {}, opt), std::invalid_argument);
  opt.output_dt_s = 0.0;
  EXPECT_THROW(simulate_monolithic(b, zero_motion(0.01, 0.1), {damper::BrfdParams{}}, opt), std::invalid_argument);
}

// A SUNDIALS failure becomes a SolverError naming the function (here CVode runs out of its
// internal step budget).
TEST(MonolithicReference, SundialsFailureNamesTheFunction) {
  const ShearBuilding b(sdof(0.2, 150, 0.02));
  ReferenceOptions opt;
  opt.duration_s = 1.0;
  opt.output_dt_s = 0.5;
  opt.max_num_steps = 2;
  opt.initial_floor_disp_in = Eigen::VectorXd::Constant(1, 1.0);
  try {
    simulate_monolithic(b, zero_motion(1.0, 1.0), {}, opt);
    ADD_FAILURE() << "no SolverError";
  } catch (const SolverError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("CVode"), std::string::npos) << msg;
    EXPECT_NE(msg.find("CV_TOO_MUCH_WORK"), std::string::npos) << msg;
    std::printf("[ measured ] SolverError: %s\n", msg.c_str());
  }
}

// ---- CR with the LuGre BRFD vs the monolithic CVODE reference on El Centro 1940 ----

using test_dampers::lugre_damper;

BuildingParams three_story(double m, double k) { return test_buildings::uniform_three_story(m, k, true); }

struct Comparison {
  Eigen::VectorXd ref_drift, cr_drift, no_damper_drift;
  double ref_force = 0.0, cr_force = 0.0, max_rel_drift_error = 0.0;
};

// The real step loop (server::run_hybrid: CR at Δt = 1/1024 s, the damper bank in-process)
// vs the CVODE reference, first 20 s of El Centro 1940 (RSN6, 180), 3-story building, one
// LuGre damper at story 1.
Comparison compare_on_el_centro(double m, double k, const damper::BrfdParams& damper = lugre_damper()) {
  const GroundMotion gm = read_ground_motion(kRecords + "/ImperialValley1940_ElCentroArray9_180_NS_RSN6.AT2");
  const ShearBuilding b(three_story(m, k));
  ReferenceOptions opt;
  opt.duration_s = 20.0;
  const ResponseHistory ref = simulate_monolithic(b, gm, {damper}, opt);
  const ResponseHistory cr = testing_support::run_in_process(testing_support::in_process_config(
      three_story(m, k), kRecords + "/ImperialValley1940_ElCentroArray9_180_NS_RSN6.AT2", damper, 1.0 / 1024,
      20.0));
  EXPECT_EQ(ref.size(), cr.size());
  BuildingParams bare = three_story(m, k);
  bare.dampers.clear();
  const ShearBuilding b_bare(bare);
  Comparison c;
  c.ref_drift = ref.peak_abs_drift_in(b);
  c.cr_drift = cr.peak_abs_drift_in(b);
  c.no_damper_drift = simulate_monolithic(b_bare, gm, {}, opt).peak_abs_drift_in(b_bare);
  c.ref_force = ref.peak_abs_damper_force_kip(b)(0);
  c.cr_force = cr.peak_abs_damper_force_kip(b)(0);
  c.max_rel_drift_error = (c.cr_drift - c.ref_drift).cwiseQuotient(c.ref_drift).cwiseAbs().maxCoeff();
  std::printf("[ measured ] m = %.3f kip*s^2/in, k = %.1f kip/in, El Centro 0-20 s, peak drifts (in):\n", m, k);
  for (int i = 0; i < 3; ++i) {
    std::printf("[ measured ]   story %d: CVODE %.5f  CR %.5f  (%+.3f%%)  without damper %.5f\n", i + 1,
                c.ref_drift(i), c.cr_drift(i), 100 * (c.cr_drift(i) - c.ref_drift(i)) / c.ref_drift(i),
                c.no_damper_drift(i));
  }
  std::printf("[ measured ]   peak damper force: CVODE %.4f kip, CR %.4f kip; max drift error %.3f%%\n",
              c.ref_force, c.cr_force, 100 * c.max_rel_drift_error);
  return c;
}

// The brief's building: masses 0.2 kip·s²/in, stories 150 kip/in (T1 = 0.52 s). Bound: 2%.
TEST(MonolithicReference, CrWithLugreDamperMatchesCvodeOnElCentro) {
  const Comparison c = compare_on_el_centro(0.2, 150.0);
  EXPECT_LT(c.max_rel_drift_error, 0.02);
  EXPECT_NEAR(c.cr_force, c.ref_force, 0.02 * c.ref_force);
  // The damper is engaged: it lowers the first-story drift by more than 3%.
  EXPECT_LT(c.ref_drift(0), 0.97 * c.no_damper_drift(0));
}

// Same periods, ten times lighter and softer: the 2.4 kip damper now carries a large share
// of the story shear (drift ~40% lower than without it), so the coupling is strongly
// nonlinear. Bound: 2%.
TEST(MonolithicReference, CrWithStrongLugreDamperMatchesCvodeOnElCentro) {
  const Comparison c = compare_on_el_centro(0.02, 15.0);
  EXPECT_LT(c.max_rel_drift_error, 0.02);
  EXPECT_NEAR(c.cr_force, c.ref_force, 0.02 * c.ref_force);
  EXPECT_LT(c.ref_drift(0), 0.7 * c.no_damper_drift(0));
}

// The band-brake model (configs/brfd-band-brake.yaml, the default runs' virtual damper) in the
// CVODE reference (its continuous form: band stretch s, Eq. B5) vs the step loop (its discrete
// step), on the default run's building. Bound: 2%.
TEST(MonolithicReference, CrWithBandBrakeDamperMatchesCvodeOnElCentro) {
  const damper::BrfdParams band = damper::load_brfd_params(std::string(HYBRIDSIM_SOURCE_DIR) + "/configs/brfd-band-brake.yaml");
  ASSERT_EQ(band.kind, damper::DamperKind::band_brake);
  const Comparison c = compare_on_el_centro(0.02, 16.0, band);
  EXPECT_LT(c.max_rel_drift_error, 0.02);
  EXPECT_NEAR(c.cr_force, c.ref_force, 0.02 * c.ref_force);
  EXPECT_LT(c.ref_drift(0), 0.9 * c.no_damper_drift(0));
}

// The reference itself is converged: tightening rtol/atol by 100 changes the peak drifts by
// less than 1e-5 (relative).
TEST(MonolithicReference, ReferenceIsConvergedInTolerance) {
  const GroundMotion gm = read_ground_motion(kRecords + "/ImperialValley1940_ElCentroArray9_180_NS_RSN6.AT2");
  const ShearBuilding b(three_story(0.02, 15.0));
  ReferenceOptions opt;
  opt.duration_s = 10.0;
  const Eigen::VectorXd loose = simulate_monolithic(b, gm, {lugre_damper()}, opt).peak_abs_drift_in(b);
  opt.rtol = 1e-10;
  opt.atol = 1e-12;
  const Eigen::VectorXd tight = simulate_monolithic(b, gm, {lugre_damper()}, opt).peak_abs_drift_in(b);
  const double change = (loose - tight).cwiseQuotient(tight).cwiseAbs().maxCoeff();
  std::printf("[ measured ] CVODE peak drifts, rtol 1e-8 vs 1e-10: max relative change %.2e\n", change);
  EXPECT_LT(change, 1e-5);
}

// A semi-active damper held at its initial actuator positions behaves as LuGre with Fc = b.
TEST(MonolithicReference, SemiactiveAtInitialPositionsEqualsLugre) {
  const GroundMotion gm = read_ground_motion(kRecords + "/ImperialValley1940_ElCentroArray9_180_NS_RSN6.AT2");
  const ShearBuilding b(three_story(0.02, 15.0));
  ReferenceOptions opt;
  opt.duration_s = 5.0;
  damper::BrfdParams semi = lugre_damper();
  semi.kind = damper::DamperKind::semiactive;
  const ResponseHistory a = simulate_monolithic(b, gm, {lugre_damper()}, opt);
  const ResponseHistory s = simulate_monolithic(b, gm, {semi}, opt);
  EXPECT_LT((a.peak_abs_drift_in(b) - s.peak_abs_drift_in(b)).cwiseAbs().maxCoeff(), 1e-9);
}

}  // namespace
}  // namespace structure
