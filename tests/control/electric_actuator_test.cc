// The electric actuator model against closed-form responses and its limits; its defaults
// against the fit on the measured semi-active tests (../shared, skipped when absent).
#include "damper/fit/actuator_fit.h"
#include "damper/model/brfd_model.h"
#include "damper/model/electric_actuator.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace {

constexpr double kDt = 1.0 / 1024;

TEST(ElectricActuator, FirstOrderStepIsTheExponential) {
  damper::ElectricActuatorParams p;
  p.time_constant_s = 0.02;
  p.velocity_limit_in_per_s = 100.0;  // not binding
  damper::ElectricActuator a(p);
  a.reset(0.6);
  for (int i = 1; i <= 200; ++i) {
    const double x = a.step(0.65, kDt);
    EXPECT_NEAR(x, 0.65 - 0.05 * std::exp(-i * kDt / 0.02), 1e-12);
  }
}

TEST(ElectricActuator, SecondOrderStepIsTheDampedOscillator) {
  damper::ElectricActuatorParams p;
  p.order = 2;
  p.time_constant_s = 0.01;  // ω_n = 100 rad/s
  p.damping_ratio = 0.5;
  p.velocity_limit_in_per_s = 100.0;
  damper::ElectricActuator a(p);
  a.reset(0.6);
  const double wn = 100.0, z = 0.5, wd = wn * std::sqrt(1 - z * z);
  double overshoot = 0.0;
  for (int i = 1; i <= 300; ++i) {
    const double t = i * kDt;
    const double x = a.step(0.7, kDt);
    const double ref = 0.7 - 0.1 * std::exp(-z * wn * t) * (std::cos(wd * t) + z * wn / wd * std::sin(wd * t));
    EXPECT_NEAR(x, ref, 1e-9);
    overshoot = std::max(overshoot, x - 0.7);
  }
  EXPECT_NEAR(overshoot / 0.1, std::exp(-M_PI * z / std::sqrt(1 - z * z)), 2e-3);  // 16.3 %
}

TEST(ElectricActuator, RateAndStrokeLimitsHold) {
  for (int order : {1, 2}) {
    damper::ElectricActuatorParams p;
    p.order = order;
    p.time_constant_s = 0.005;
    p.velocity_limit_in_per_s = 0.4;
    damper::ElectricActuator a(p);
    a.reset(0.655);
    double prev = a.position_in();
    for (int i = 0; i < 4096; ++i) {
      const double target = (i / 512) % 2 ? 5.0 : -5.0;  // far beyond both stroke ends
      const double x = a.step(target, kDt);
      EXPECT_LE(std::abs(x - prev), 0.4 * kDt + 1e-15);
      EXPECT_GE(x, p.min_in);
      EXPECT_LE(x, p.max_in);
      prev = x;
    }
  }
  // a long ramp is exactly at the velocity limit
  damper::ElectricActuatorParams p;
  p.velocity_limit_in_per_s = 0.4;
  damper::ElectricActuator a(p);
  a.reset(1.0);
  for (int i = 0; i < 100; ++i) a.step(0.3, kDt);
  EXPECT_NEAR(a.position_in(), 1.0 - 0.4 * 100 * kDt, 1e-12);
}

TEST(ElectricActuator, DefaultsComeFromTheMeasuredSemiActiveTests) {
  if (!test_paths::have_shared()) GTEST_SKIP() << "../shared absent: no measured semi-active tests";
  const std::string dir = test_paths::shared_dir() + "/data/brfd/semiactive/";
  std::vector<double> taus;
  double peak_speed = 0.0;
  for (const char* name : {"harmonic0.03ea1forward", "harmonic0.03ea1backward", "harmonic0.03ea2forward",
                           "harmonic0.03ea2backward", "harmonic0.015forward", "harmonic0.015backward"}) {
    const damper::BrfdTest test = damper::read_brfd_test(dir + name + ".json");
    const double amp = std::string(name).find("0.015") != std::string::npos ? 0.015 : 0.03;
    const auto fits = damper::fit_actuator_cycles(test, amp);
    ASSERT_FALSE(fits.empty()) << name;
    for (const auto& f : fits) {
      std::cout << name << " actuator " << f.actuator << ": T " << f.period_s << " s, tau " << 1e3 * f.time_constant_s
                << " ms, RMS " << 1e3 * f.rms_error_in << " mil (no lag " << 1e3 * f.rms_error_no_lag_in << "), peak "
                << f.peak_measured_in << " in, speed " << f.peak_speed_in_per_s << " in/s\n";
      EXPECT_LE(f.rms_error_in, f.rms_error_no_lag_in);
      EXPECT_LT(f.rms_error_in, 0.25 * amp) << name;  // the one-cycle sine explains the motion
      taus.push_back(f.time_constant_s);
      peak_speed = std::max(peak_speed, f.peak_speed_in_per_s);
    }
  }
  std::sort(taus.begin(), taus.end());
  const double median = taus[taus.size() / 2];
  std::cout << "median tau " << 1e3 * median << " ms over " << taus.size() << " cycles, peak speed " << peak_speed << " in/s\n";
  const damper::ElectricActuatorParams defaults;
  EXPECT_NEAR(defaults.time_constant_s, median, 0.004);           // default = the median fit, rounded
  EXPECT_GE(defaults.velocity_limit_in_per_s, peak_speed);         // never slower than measured
}

}  // namespace
