// The inverse of Eq. (4): desired friction -> targets -> Eq. (4) gives the friction back
// inside the limits, saturates at them; the bounds are the paper's Tables 1-2 numbers.
#include "control/friction_inverse.h"
#include "damper/model/band_brake_model.h"
#include "damper/model/brfd_config.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <array>
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

// Band-brake model (damper/model/band_brake_model.h): the actuators set the slack-end tension
// (B2), Fc = L (E - 1) T_slack (B3): the same inverse with b and the gains of (B1)-(B3).
damper::BrfdParams band_brake_params() {
  return damper::load_brfd_params(test_paths::source_dir() + "/configs/brfd-band-brake.yaml");
}

TEST(FrictionInverseBandBrake, RoundTripThroughTheModelsOwnTensions) {
  const damper::BrfdParams p = band_brake_params();
  ASSERT_EQ(p.kind, damper::DamperKind::band_brake);
  const control::FrictionInverse inv(p);
  const damper::BandBrakeModel model(p.band_brake);
  // Linearizing (B1)-(B3) gives Eq. (4)'s gains: -L (E - 1) k_dj, close to Tables 1-2 (-48.9, -45.3).
  const double e_fwd = std::exp(p.band_brake.friction_coefficient * p.band_brake.wrap_angle_fwd_rad);
  EXPECT_NEAR(inv.gain_kip_per_in(true, 1),
              -p.band_brake.lever_ratio * (e_fwd - 1) * p.band_brake.actuator_tension_kip_per_in[0], 1e-12);
  int checked = 0;
  for (double drum : {-1.0, 0.0, 0.7})
    for (double v : {1.0, -1.0, 0.05, -2.0}) {
      const control::FrictionRange r = inv.range(v, drum);
      ASSERT_LT(r.min_kip, r.max_kip);
      for (double fc = r.min_kip; fc <= r.max_kip; fc += 0.1) {
        const control::ActuatorTargets t = inv.targets(fc, v, drum);
        EXPECT_FALSE(t.saturated);
        const damper::BandTensions bt = model.tensions({drum, v, t.actuator1_in, t.actuator2_in});
        EXPECT_NEAR(v >= 0 ? bt.fc_fwd_kip : bt.fc_bwd_kip, fc, 1e-9) << "drum " << drum << " v " << v;
        EXPECT_NEAR(t.kinetic_friction_kip, fc, 1e-9);
        ++checked;
      }
    }
  EXPECT_GT(checked, 200);
}

TEST(FrictionInverseBandBrake, SaturatesWhereTheTautEndsLoadCellReachesItsLimit) {
  const damper::BrfdParams p = band_brake_params();
  const control::FrictionInverse inv(p);
  const damper::BandBrakeModel model(p.band_brake);
  const double limit_kip = p.electric_actuators.force_limit_lb / 1000.0;
  for (double drum : {-0.5, 0.0, 0.5})
    for (double v : {1.0, -1.0}) {
      const control::ActuatorTargets hi = inv.targets(50.0, v, drum);
      EXPECT_TRUE(hi.saturated);
      // The model's own load cells with the band slipping at that friction (B6): the taut end
      // carries the limit, the slack end T_slack.
      const damper::DamperInput in{drum, v, hi.actuator1_in, hi.actuator2_in};
      const double s = model.stretch_for_force(v >= 0 ? hi.kinetic_friction_kip : -hi.kinetic_friction_kip);
      const std::array<double, 2> cells = model.actuator_forces_kip(s, in);
      EXPECT_NEAR(std::max(cells[0], cells[1]), limit_kip, 1e-9) << "drum " << drum << " v " << v;
      EXPECT_NEAR(inv.taut_actuator_force_lb(hi.kinetic_friction_kip, v >= 0, drum), 1000 * limit_kip, 1e-6);
      // Low end: the configured minimum friction.
      const control::ActuatorTargets lo = inv.targets(0.0, v, drum);
      EXPECT_TRUE(lo.saturated);
      EXPECT_NEAR(lo.kinetic_friction_kip, 0.0 + inv.range(v, drum).min_kip, 1e-12);
      EXPECT_GE(lo.actuator1_in, p.electric_actuators.min_in);
      EXPECT_LE(lo.actuator2_in, p.electric_actuators.max_in);
    }
  // passive_on keeps both directions within the limit at the centred drum.
  const control::ActuatorTargets on = inv.strongest();
  EXPECT_LE(inv.taut_actuator_force_lb(inv.kinetic_friction_kip(on.actuator1_in, on.actuator2_in, 1.0), true), 3000 + 1e-6);
  EXPECT_LE(inv.taut_actuator_force_lb(inv.kinetic_friction_kip(on.actuator1_in, on.actuator2_in, -1.0), false), 3000 + 1e-6);
}
