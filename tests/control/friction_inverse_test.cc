// The inverse of Eq. (4): desired friction -> targets -> Eq. (4) gives the friction back
// inside the limits, saturates at them; the bounds are the paper's Tables 1-2 numbers.
#include "control/friction_inverse.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

damper::BrfdParams paper_params() {
  damper::BrfdParams p;  // defaults: Tables 1-2, x' of the semi-active tests, b = 2 kip
  p.kind = damper::DamperKind::semiactive;
  return p;
}

TEST(FrictionInverse, GainsAreTheTablesProducts) {
  const control::FrictionInverse inv(paper_params());
  // C1 m11 + C2 m21 = 119.68(-0.14) + 2.10(-15.29) by hand
  EXPECT_NEAR(inv.gain_kip_per_in(true, 1), -16.7552 - 32.109, 1e-9);
  EXPECT_NEAR(inv.gain_kip_per_in(true, 2), 119.68 * -0.15 + 2.10 * -13.00, 1e-12);
  EXPECT_NEAR(inv.gain_kip_per_in(false, 1), 1.94 * -16.66 + 123.31 * -0.13, 1e-12);
  EXPECT_NEAR(inv.gain_kip_per_in(false, 2), 1.94 * -15.77 + 123.31 * -0.15, 1e-12);
}

TEST(FrictionInverse, RoundTripInsideTheRange) {
  const control::FrictionInverse inv(paper_params());
  for (double v : {1.0, -1.0, 0.01, -3.0}) {
    const control::FrictionRange r = inv.range(v);
    ASSERT_LT(r.min_kip, r.max_kip);
    for (double fc = r.min_kip; fc <= r.max_kip; fc += 0.1) {
      const control::ActuatorTargets t = inv.targets(fc, v);
      EXPECT_FALSE(t.saturated);
      // Eq. (4) evaluated independently by the damper model at the targets
      damper::BrfdModel model(paper_params());
      damper::DamperInput in{0.0, v, t.actuator1_in, t.actuator2_in};
      EXPECT_NEAR(model.kinetic_friction_kip(in), fc, 1e-9) << "v " << v << " fc " << fc;
      EXPECT_NEAR(t.kinetic_friction_kip, fc, 1e-9);
      EXPECT_LE(inv.taut_actuator_force_lb(fc, v >= 0), 3000.0 + 1e-6);
    }
  }
}

TEST(FrictionInverse, SaturatesAtForceAndStrokeLimits) {
  damper::BrfdParams p = paper_params();
  const control::FrictionInverse inv(p);
  // Force limit 3000 lb on the taut band: forward C2 = 2.10 -> 6.3 kip, backward C3 = 1.94 -> 5.82 kip.
  EXPECT_NEAR(inv.range(1.0).max_kip, 6.3, 1e-9);
  EXPECT_NEAR(inv.range(-1.0).max_kip, 5.82, 1e-9);
  const control::ActuatorTargets hi = inv.targets(50.0, 1.0);
  EXPECT_TRUE(hi.saturated);
  EXPECT_NEAR(hi.kinetic_friction_kip, 6.3, 1e-9);
  EXPECT_NEAR(inv.taut_actuator_force_lb(hi.kinetic_friction_kip, true), 3000.0, 1e-6);
  // Low end: the configured minimum (here the model floor 0.05 kip) or full extension.
  const control::ActuatorTargets lo = inv.targets(0.0, -1.0);
  EXPECT_TRUE(lo.saturated);
  EXPECT_NEAR(lo.kinetic_friction_kip, 0.05, 1e-9);
  // A large force limit leaves the stroke as the bound: x'1 = 0.655 -> 0.30 in (D = -0.355).
  p.electric_actuators.force_limit_lb = 1e6;
  const control::FrictionInverse stroke(p);
  const control::ActuatorTargets s = stroke.targets(1e3, 1.0);
  EXPECT_TRUE(s.saturated);
  EXPECT_NEAR(s.actuator1_in, 0.30, 1e-12);
  EXPECT_GE(s.actuator2_in, 0.30);
  EXPECT_NEAR(s.kinetic_friction_kip, 2.0 + 0.355 * -(stroke.gain_kip_per_in(true, 1) + stroke.gain_kip_per_in(true, 2)),
              1e-9);
  // passive_on: both directions inside the force limit, the tighter (backward) reached.
  const control::ActuatorTargets on = inv.strongest();
  EXPECT_NEAR(inv.kinetic_friction_kip(on.actuator1_in, on.actuator2_in, -1.0), 5.82, 1e-9);
  EXPECT_LE(inv.kinetic_friction_kip(on.actuator1_in, on.actuator2_in, 1.0), 6.3);
}

TEST(FrictionInverse, RejectsInitialPositionsOutsideTheStroke) {
  damper::BrfdParams p = paper_params();
  p.electric_actuators.max_in = 0.8;  // x'2 = 0.8559 beyond it
  EXPECT_THROW(control::FrictionInverse{p}, std::invalid_argument);
  p = paper_params();
  p.kind = damper::DamperKind::passive_lugre;
  EXPECT_THROW(control::FrictionInverse{p}, std::invalid_argument);
}

}  // namespace
