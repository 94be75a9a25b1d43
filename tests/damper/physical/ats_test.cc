// ATS delay compensation (Chae, Kazemibidokhti & Ricles 2013) against the rig's servo-hydraulic
// actuator model, in-process: the bounded least squares is exact, a pure delay is identified as
// a1 = tau, and with a 20 ms emulated delay ATS cuts the measured delay and the RMS tracking
// error compared with no compensation. The end-to-end version over LCM is in system_test.cc.
#include "damper/physical/ats_compensator.h"
#include "damper/physical/tracking.h"
#include "damper/rig/rig_config.h"
#include "damper/rig/rig_simulator.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace {

using damper::physical::AtsCompensator;
using damper::physical::AtsSettings;

TEST(AtsBoundedLeastSquares, InteriorSolutionIsTheUnconstrainedOne) {
  Eigen::Matrix<double, 200, 3> phi = Eigen::Matrix<double, 200, 3>::Random();
  const Eigen::Vector3d truth(1.02, 0.021, 0.0002);
  const Eigen::Matrix<double, 200, 1> y = phi * truth;
  const Eigen::Vector3d a = AtsCompensator::bounded_least_squares(
      phi.transpose() * phi, phi.transpose() * y, Eigen::Vector3d(0.7, 0.0, 0.0), Eigen::Vector3d(1.3, 0.08, 0.0032));
  EXPECT_NEAR((a - truth).norm(), 0.0, 1e-10) << a.transpose();
}

TEST(AtsBoundedLeastSquares, ActiveBoundsMatchABruteForceSearch) {
  Eigen::Matrix<double, 100, 3> phi = Eigen::Matrix<double, 100, 3>::Random();
  const Eigen::Vector3d truth(1.5, -0.02, 0.01);  // a0 and a2 above, a1 below their bounds
  Eigen::Matrix<double, 100, 1> y = phi * truth;
  const Eigen::Vector3d lo(0.7, 0.0, 0.0), hi(1.3, 0.08, 0.0032);
  const Eigen::Vector3d a = AtsCompensator::bounded_least_squares(phi.transpose() * phi, phi.transpose() * y, lo, hi);
  EXPECT_TRUE((a.array() >= lo.array() - 1e-12).all() && (a.array() <= hi.array() + 1e-12).all()) << a.transpose();
  const double best = (phi * a - y).squaredNorm();
  double brute = 1e300;
  for (int i = 0; i <= 60; ++i)
    for (int j = 0; j <= 60; ++j)
      for (int k = 0; k <= 60; ++k) {
        const Eigen::Vector3d b(lo[0] + (hi[0] - lo[0]) * i / 60.0, lo[1] + (hi[1] - lo[1]) * j / 60.0,
                                lo[2] + (hi[2] - lo[2]) * k / 60.0);
        brute = std::min(brute, (phi * b - y).squaredNorm());
      }
  EXPECT_LE(best, brute + 1e-12);
}

double target_in(double t) {
  // Earthquake-like drift: two frequencies (1.3 and 2.7 Hz), ramped in over 1 s.
  const double ramp = std::min(1.0, t);
  return ramp * (0.6 * std::sin(2 * M_PI * 1.3 * t) + 0.25 * std::sin(2 * M_PI * 2.7 * t + 0.7));
}

struct LoopResult {
  damper::physical::TrackingIndicators all, settled;
  Eigen::Vector3d coefficients;
};

LoopResult run_loop(bool ats_on, double delay_s, bool noise) {
  damper::rig::RigConfig rc = damper::rig::load_rig_config(test_paths::source_dir() + "/configs/rig-default.yaml");
  rc.hydraulic.delay_s = delay_s;
  rc.noise.enabled = noise;
  damper::rig::RigSimulator rig(rc);
  AtsSettings a;
  a.enabled = ats_on;
  const double dt = 1.0 / 1024.0;
  AtsCompensator ats(a, dt);
  const int n = 10 * 1024;
  std::vector<double> target(n), measured(n);
  for (int k = 0; k < n; ++k) {
    target[k] = target_in(k * dt);
    const double xc = ats.compensate(target[k]);
    rig.step({xc, rc.initial.actuator1_in, rc.initial.actuator2_in});
    measured[k] = rig.reading().drum_in;
    ats.observe(xc, measured[k]);
  }
  return {damper::physical::tracking_indicators(target, measured, dt, 0, n),
          damper::physical::tracking_indicators(target, measured, dt, n / 2, n), ats.identified()};
}

TEST(Ats, IdentifiesAPureDelayAsA1) {
  const LoopResult r = run_loop(true, 0.020, false);
  // The rig adds its 6 ms servo lag to the 20 ms delay: a0 ≈ 1, a1 ≈ 26 ms, a2 ≈ a1²/2-ish.
  std::printf("identified a0 %.4f a1 %.4f s a2 %.6f s^2\n", r.coefficients[0], r.coefficients[1], r.coefficients[2]);
  EXPECT_NEAR(r.coefficients[0], 1.0, 0.05);
  EXPECT_NEAR(r.coefficients[1], 0.026, 0.004);
  EXPECT_GT(r.coefficients[2], 0.0);
}

TEST(Ats, With20msDelayCutsMeasuredDelayAndRmsTrackingError) {
  const LoopResult off = run_loop(false, 0.020, true);
  const LoopResult on = run_loop(true, 0.020, true);
  std::printf("20 ms emulated delay + 6 ms lag, noise on, 10 s, in-process:\n"
              "  no compensation: %s\n  ATS:             %s\n"
              "  last 5 s: no compensation delay %.2f ms NRMS %.2f %%; ATS delay %.2f ms NRMS %.2f %%\n",
              damper::physical::format_tracking(off.all).c_str(), damper::physical::format_tracking(on.all).c_str(),
              off.settled.delay_ms, off.settled.nrms_error_pct, on.settled.delay_ms, on.settled.nrms_error_pct);
  EXPECT_GT(off.all.delay_ms, 20.0);                      // the emulated delay is really there
  EXPECT_LT(std::abs(on.all.delay_ms), 0.25 * off.all.delay_ms);
  EXPECT_LT(on.all.rms_error_in, 0.35 * off.all.rms_error_in);
  EXPECT_LT(std::abs(on.settled.delay_ms), 2.0);          // converged: within two samples
  EXPECT_LT(on.settled.nrms_error_pct, 0.2 * off.settled.nrms_error_pct);
}

TEST(Tracking, CrossCorrelationFindsAKnownShift) {
  const double dt = 1.0 / 1024.0;
  std::vector<double> x(4096), y(4096);
  for (int k = 0; k < 4096; ++k) {
    x[k] = target_in(k * dt);
    y[k] = target_in(k * dt - 0.0175);  // 17.5 ms late
  }
  EXPECT_NEAR(damper::physical::cross_correlation_delay_ms(x, y, dt, 0, 4096, 64), 17.5, 0.3);
  EXPECT_NEAR(damper::physical::cross_correlation_delay_ms(y, x, dt, 0, 4096, 64), -17.5, 0.3);
}

}  // namespace
