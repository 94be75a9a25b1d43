// Controller decisions on hand-made measurements: passive laws hold their positions, Lyapunov
// switches on the sign of F·v, clipped-optimal gives a stabilizing design, Inaudi's law tracks
// the last reversal; the criteria on known histories.
#include "control/controller.h"
#include "control/criteria.h"

#include <gtest/gtest.h>

namespace {

control::BuildingMatrices three_story() {
  control::BuildingMatrices b;
  b.mass = 0.02 * Eigen::MatrixXd::Identity(3, 3);
  b.stiffness.resize(3, 3);
  b.stiffness << 32, -16, 0, -16, 32, -16, 0, -16, 16;
  b.damping = 0.001 * b.mass + 0.002 * b.stiffness;
  b.gamma = Eigen::MatrixXd::Zero(3, 1);
  b.gamma(0, 0) = 1.0;
  return b;
}

damper::BrfdParams semiactive() {
  damper::BrfdParams p;
  p.kind = damper::DamperKind::semiactive;
  return p;
}

struct Frame {
  Eigen::VectorXd accel = Eigen::VectorXd::Zero(3), drift = Eigen::VectorXd::Zero(3), force = Eigen::VectorXd::Zero(1),
                  drum = Eigen::VectorXd::Zero(1);
  control::Measurements m() const { return {&accel, &drift, &force, &drum}; }
};

TEST(Controller, LyapunovSwitchesOnTheSignOfForceTimesVelocity) {
  control::ControlConfig c;
  c.enabled = true;
  c.law = control::Law::lyapunov;
  control::Controller ctl(c, three_story(), semiactive(), 1.0 / 1024);
  Eigen::MatrixX2d t(1, 2);
  Frame f;
  ctl.compute(f.m(), t);  // first frame: no velocity yet
  f.drum[0] = 0.01;       // moving forward
  f.force[0] = 1.0;       // resisting: F·v > 0 -> clamp
  ctl.compute(f.m(), t);
  EXPECT_NEAR(ctl.desired_friction_kip(0), ctl.inverse().range(1.0).max_kip, 1e-12);
  f.drum[0] = 0.005;  // reversed, force still positive: F·v < 0 -> release
  ctl.compute(f.m(), t);
  EXPECT_NEAR(ctl.desired_friction_kip(0), ctl.inverse().range(-1.0).min_kip, 1e-12);
  EXPECT_GT(t(0, 0), semiactive().semiactive.actuator1_initial_in);  // release = extend
}

TEST(Controller, PassiveLawsHold) {
  for (control::Law law : {control::Law::passive_off, control::Law::passive_on}) {
    control::ControlConfig c;
    c.enabled = true;
    c.law = law;
    control::Controller ctl(c, three_story(), semiactive(), 1.0 / 1024);
    Eigen::MatrixX2d t(1, 2);
    Frame f;
    for (int i = 0; i < 50; ++i) {
      f.drum[0] = 0.1 * std::sin(i * 0.3);
      f.force[0] = 2.0 * std::cos(i * 0.3);
      ctl.compute(f.m(), t);
      const control::ActuatorTargets want =
          law == control::Law::passive_off ? ctl.inverse().initial() : ctl.inverse().strongest();
      EXPECT_EQ(t(0, 0), want.actuator1_in);
      EXPECT_EQ(t(0, 1), want.actuator2_in);
    }
  }
}

TEST(Controller, ClippedOptimalDesignIsStabilizingAndResistsDrift) {
  control::ControlConfig c;
  c.enabled = true;
  c.law = control::Law::clipped_optimal;
  control::Controller ctl(c, three_story(), semiactive(), 1.0 / 1024);
  const Eigen::MatrixXd& k = ctl.lqr_gain();
  ASSERT_EQ(k.rows(), 1);
  ASSERT_EQ(k.cols(), 6);
  ASSERT_TRUE(k.allFinite());
  // A first-story velocity in +x asks for a positive damper force (resisting, as a damper would).
  Eigen::VectorXd z = Eigen::VectorXd::Zero(6);
  z[3] = 1.0;
  EXPECT_GT(-(k * z)(0), 0.0) << "desired force opposes the first story's velocity";
}

TEST(Controller, ModulatedHomogeneousFollowsTheLastReversal) {
  control::ControlConfig c;
  c.enabled = true;
  c.law = control::Law::modulated_homogeneous;
  c.gain_kip_per_in = 4.0;
  control::Controller ctl(c, three_story(), semiactive(), 1.0 / 1024);
  Eigen::MatrixX2d t(1, 2);
  Frame f;
  for (double d : {0.0, 0.2, 0.5, 0.7, 0.6}) {  // reversal at 0.7
    f.drum[0] = d;
    ctl.compute(f.m(), t);
  }
  EXPECT_NEAR(ctl.desired_friction_kip(0), 4.0 * 0.7, 1e-9);
}

TEST(Criteria, RatiosOfPeaksAndRms) {
  const Eigen::VectorXd m = Eigen::VectorXd::Constant(2, 0.5);
  control::ResponseStats u(2, m), c(2, m);
  Eigen::VectorXd d(2), a(2);
  for (int i = 0; i < 100; ++i) {
    const double s = std::sin(0.1 * i);
    d << s, 0.5 * s;
    a << 10 * s, 20 * s;
    u.add(d, a);
    d *= 0.5;
    a *= 0.8;
    c.add(d, a);
  }
  const control::Criteria j = control::evaluate_criteria(c, u);
  EXPECT_NEAR(j.j1, 0.5, 1e-12);
  EXPECT_NEAR(j.j2, 0.8, 1e-12);
  EXPECT_NEAR(j.j3, 0.8, 1e-12);
  EXPECT_NEAR(j.j1_rms, 0.5, 1e-12);
  EXPECT_NEAR(j.j2_rms, 0.8, 1e-12);
  EXPECT_NEAR(j.j3_rms, 0.8, 1e-12);
}

}  // namespace
