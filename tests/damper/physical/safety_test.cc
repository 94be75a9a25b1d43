// The safety layer (damper/physical/safety.h) in-process: each limit refuses exactly what it
// should, and the ramps it shapes stay within the velocity they are given. End-to-end trips
// (hold, ramp, abort, no out-of-limit command at the rig) are in system_test.cc.
#include "damper/physical/safety.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using damper::physical::ActuatorSetpoint;
using damper::physical::SafetyLayer;
using damper::physical::SafetyLimits;
using damper::physical::SetpointRamp;

constexpr double kPeriod = 1.0 / 1024.0;

SafetyLimits limits() {
  SafetyLimits l;
  l.stroke_in = 1.0;
  l.velocity_in_per_s = 10.0;
  l.actuator_min_in = 0.3;
  l.actuator_max_in = 1.2;
  l.actuator_force_lb = 2000.0;
  l.drift_in = 0.8;
  l.tracking_error_in = 0.1;
  return l;
}

TEST(SafetyLayer, StrokeLimit) {
  SafetyLayer s(limits(), kPeriod);
  std::string why;
  EXPECT_TRUE(s.command_ok({0.99, 0.6, 0.8}, why)) << why;
  EXPECT_FALSE(s.command_ok({1.01, 0.6, 0.8}, why));
  EXPECT_NE(why.find("limits.stroke_in"), std::string::npos) << why;
  EXPECT_FALSE(s.command_ok({-1.01, 0.6, 0.8}, why));
  EXPECT_FALSE(s.command_ok({NAN, 0.6, 0.8}, why));
}

TEST(SafetyLayer, CommandRateLimitIsAgainstTheLastPublishedCommand) {
  SafetyLayer s(limits(), kPeriod);
  std::string why;
  s.published({0.5, 0.6, 0.8});
  const double step_ok = 0.99 * 10.0 * kPeriod, step_bad = 1.01 * 10.0 * kPeriod;
  EXPECT_TRUE(s.command_ok({0.5 + step_ok, 0.6, 0.8}, why)) << why;
  EXPECT_FALSE(s.command_ok({0.5 - step_bad, 0.6, 0.8}, why));
  EXPECT_NE(why.find("limits.velocity_in_per_s"), std::string::npos) << why;
}

TEST(SafetyLayer, ElectricActuatorPositionRange) {
  SafetyLayer s(limits(), kPeriod);
  std::string why;
  EXPECT_FALSE(s.command_ok({0.0, 0.29, 0.8}, why));
  EXPECT_NE(why.find("actuator 1"), std::string::npos) << why;
  EXPECT_FALSE(s.command_ok({0.0, 0.6, 1.21}, why));
  EXPECT_NE(why.find("actuator 2"), std::string::npos) << why;
}

TEST(SafetyLayer, ActuatorForceLimitOnEveryFrame) {
  SafetyLayer s(limits(), kPeriod);
  std::string why;
  hybrid_lcm::sensor_frame_t f{};
  f.actuator1_force_lb = 1999.0;
  f.actuator2_force_lb = 30.0;
  EXPECT_TRUE(s.frame_ok(f, why)) << why;
  f.actuator2_force_lb = 2001.0;
  EXPECT_FALSE(s.frame_ok(f, why));
  EXPECT_NE(why.find("limits.actuator_force_lb"), std::string::npos) << why;
  f.actuator2_force_lb = 30.0;
  f.friction_force_kip = INFINITY;
  EXPECT_FALSE(s.frame_ok(f, why));
}

TEST(SafetyLayer, DriftAndTrackingLimits) {
  SafetyLayer s(limits(), kPeriod);
  std::string why;
  EXPECT_TRUE(s.target_ok(0.79, why));
  EXPECT_FALSE(s.target_ok(-0.81, why));
  EXPECT_NE(why.find("limits.drift_in"), std::string::npos) << why;
  EXPECT_TRUE(s.tracking_ok(0.5, 0.59, why));
  EXPECT_FALSE(s.tracking_ok(0.5, 0.39, why));
  EXPECT_NE(why.find("limits.tracking_error_in"), std::string::npos) << why;
}

TEST(SetpointRamp, CosineMoveStaysWithinItsPeakVelocityAndEndsAtTheTarget) {
  const ActuatorSetpoint from{0.9, 0.6, 0.8}, to{0.0, 0.655, 0.8559};
  const double T = SetpointRamp::duration_for(from, to, 0.1, 2.0);
  EXPECT_NEAR(T, 0.5 * M_PI * 0.9 / 2.0, 1e-12);
  SetpointRamp r(from, to, T);
  SafetyLimits l = limits();
  l.velocity_in_per_s = 2.0 + 1e-9;
  SafetyLayer s(l, kPeriod);
  std::string why;
  s.published(from);
  for (double t = kPeriod; t <= T + 2 * kPeriod; t += kPeriod) {
    const ActuatorSetpoint sp = r.at(t);
    ASSERT_TRUE(s.command_ok(sp, why)) << "t " << t << ": " << why;
    s.published(sp);
  }
  EXPECT_DOUBLE_EQ(r.at(T).drum_in, 0.0);
  EXPECT_DOUBLE_EQ(r.at(T).actuator2_in, 0.8559);
  EXPECT_DOUBLE_EQ(damper::physical::ramp_factor(0.0, 0.25), 0.0);
  EXPECT_DOUBLE_EQ(damper::physical::ramp_factor(0.25, 0.25), 1.0);
}

}  // namespace
