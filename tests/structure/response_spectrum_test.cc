// Sa(T, ζ) of structure/response_spectrum.h against two independent references:
//  1. the closed-form response of the damped SDOF oscillator to a harmonic ground motion
//     from rest (tests/structure/sdof_closed_form.h), peak taken on a 10x finer grid;
//  2. a second integrator written here: Newmark's average-acceleration method (γ = 1/2,
//     β = 1/4) on the same record, 20 sub-steps per record sample.
// Bound: 0.5 % (the tolerance). Measured differences are printed.
#include "structure/response_spectrum.h"

#include "sdof_closed_form.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace {

using structure::GroundMotion;

constexpr double kPi = 3.14159265358979323846;

GroundMotion harmonic_record(double amplitude_g, double period_s, double dt, double duration_s) {
  GroundMotion g;
  g.source = "harmonic";
  g.dt_s = dt;
  const long n = static_cast<long>(std::lround(duration_s / dt)) + 1;
  for (long i = 0; i < n; ++i) g.accel_g.push_back(amplitude_g * std::sin(2.0 * kPi / period_s * i * dt));
  return g;
}

/// Newmark average acceleration on ü + 2ζω u̇ + ω² u = −ü_g, the record linearly interpolated
/// between samples, `sub` steps per sample; returns ω²·max|u|.
double newmark_sa(const GroundMotion& g, double period_s, double zeta, int sub) {
  const double w = 2.0 * kPi / period_s, h = g.dt_s / sub;
  const double k = w * w, c = 2.0 * zeta * w;
  const double keff = k + 2.0 * c / h + 4.0 / (h * h);
  double u = 0.0, v = 0.0, a = -g.accel_g[0], peak = 0.0;
  for (std::size_t i = 0; i + 1 < g.accel_g.size(); ++i) {
    for (int j = 1; j <= sub; ++j) {
      const double f = static_cast<double>(j) / sub;
      const double p = -((1.0 - f) * g.accel_g[i] + f * g.accel_g[i + 1]);
      const double peff = p + (4.0 / (h * h)) * u + (4.0 / h) * v + a + c * ((2.0 / h) * u + v);
      const double u1 = peff / keff;
      const double v1 = 2.0 / h * (u1 - u) - v;
      const double a1 = 4.0 / (h * h) * (u1 - u) - 4.0 / h * v - a;
      u = u1;
      v = v1;
      a = a1;
      peak = std::max(peak, std::abs(u));
    }
  }
  return k * peak;
}

double closed_form_sa(double amplitude_g, double forcing_period_s, double period_s, double zeta, double duration_s) {
  structure::testing::Sdof sdof{2.0 * kPi / period_s, zeta};
  const double fine = 1e-4;
  double peak = 0.0;
  for (double t = 0.0; t <= duration_s; t += fine)
    peak = std::max(peak, std::abs(sdof.harmonic_disp(t, amplitude_g, 2.0 * kPi / forcing_period_s)));
  return sdof.omega * sdof.omega * peak;
}

TEST(ResponseSpectrum, HarmonicRecordMatchesClosedForm) {
  // Off resonance, at resonance (transient build-up) and well above it.
  struct Case { double forcing_T, T; } cases[] = {{0.7, 0.5}, {0.5, 0.5}, {0.3, 1.2}};
  for (const auto& cs : cases) {
    const double duration = 8.0;
    const GroundMotion g = harmonic_record(0.3, cs.forcing_T, 0.001, duration);
    const double sa = structure::spectral_accel_g(g, cs.T, 0.05);
    const double ref = closed_form_sa(0.3, cs.forcing_T, cs.T, 0.05, duration);
    std::printf("harmonic T_forcing %.2f s, T %.2f s: Sa %.6f g, closed form %.6f g, diff %.4f %%\n", cs.forcing_T,
                cs.T, sa, ref, 100.0 * (sa / ref - 1.0));
    EXPECT_NEAR(sa / ref, 1.0, 0.005);
  }
}

TEST(ResponseSpectrum, RealRecordMatchesNewmark) {
  const GroundMotion g =
      structure::read_ground_motion(std::string(PROJECT_RECORDS_DIR) + "/ImperialValley1940_ElCentroArray9_180_NS_RSN6.AT2");
  for (double T : {0.1, 0.3, 0.5, 1.0, 2.0, 4.0}) {
    const double sa = structure::spectral_accel_g(g, T, 0.05);
    const double ref = newmark_sa(g, T, 0.05, 20);
    std::printf("El Centro T %.1f s: Sa %.5f g, Newmark %.5f g, diff %.4f %%\n", T, sa, ref, 100.0 * (sa / ref - 1.0));
    EXPECT_NEAR(sa / ref, 1.0, 0.005) << "T = " << T;
    EXPECT_GT(sa, 0.0);
  }
  // Rigid limit: a very stiff oscillator follows the ground, Sa -> PGA.
  EXPECT_NEAR(structure::spectral_accel_g(g, 0.005, 0.05) / g.pga_g(), 1.0, 0.02);
}

TEST(ResponseSpectrum, ScalesLinearlyWithTheRecord) {
  GroundMotion g = harmonic_record(0.2, 0.6, 0.005, 6.0);
  const double sa1 = structure::spectral_accel_g(g, 0.8, 0.05);
  for (double& a : g.accel_g) a *= 2.5;
  EXPECT_NEAR(structure::spectral_accel_g(g, 0.8, 0.05), 2.5 * sa1, 1e-12 * sa1);
}

TEST(ResponseSpectrum, RejectsBadInput) {
  const GroundMotion g = harmonic_record(0.2, 0.6, 0.005, 1.0);
  EXPECT_THROW(structure::spectral_accel_g(g, 0.0, 0.05), std::invalid_argument);
  EXPECT_THROW(structure::spectral_accel_g(g, 1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(structure::spectral_accel_g(GroundMotion{}, 1.0, 0.05), std::invalid_argument);
}

}  // namespace
