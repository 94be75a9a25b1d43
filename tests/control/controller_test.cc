// Controller decisions on hand-made measurements: passive laws hold their positions, Lyapunov
// switches on the sign of F·v, clipped-optimal gives a stabilizing design, Inaudi's law tracks
// the last reversal; the criteria on known histories.
#include "control/controller.h"
#include "control/criteria.h"
#include "control/motion_fit.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <string>

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

TEST(Controller, LyapunovReleasesAheadOfAPredictedReversal) {
  // Drum decelerating toward a reversal, d(t) = A sin(ω t) past its zero crossing, force
  // resisting (F·v > 0): the plain law clamps all the way to the reversal; the law with the lead
  // releases once (|v| - v_s) / |a| < T_rel, v and a of the quadratic fit. Closed form for the
  // instant: v = Aω cos ωt, a = -Aω² sin ωt.
  const double dt = 1.0 / 1024, amp = 1.0, w = 2.0 * M_PI / 1.5;  // 1 in, 1.5 s period
  control::ControlConfig c;
  c.enabled = true;
  c.law = control::Law::lyapunov;
  control::Controller lead(c, three_story(), semiactive(), dt);
  c.reversal_lead = 0.0;
  control::Controller plain(c, three_story(), semiactive(), dt);
  const double t_rel = lead.inverse().release_time_s(1.0);
  const double vs = lead.inverse().stribeck_velocity_in_per_s();
  EXPECT_EQ(vs, semiactive().lugre.vs_in_per_s);  // Eq. (5)'s v_s
  Eigen::MatrixX2d t(1, 2);
  Frame f;
  double first_release_s = -1.0;
  for (int i = 0; i * dt < 0.375; ++i) {  // up to the reversal at a quarter period
    const double time = i * dt;
    f.drum[0] = amp * std::sin(w * time);
    f.force[0] = 2.0;
    lead.compute(f.m(), t);
    plain.compute(f.m(), t);
    if (i > 1) {
      EXPECT_NEAR(plain.desired_friction_kip(0), plain.inverse().range(1.0).max_kip, 1e-12) << time;
    }
    if (first_release_s < 0.0 && lead.reversal_release(0)) first_release_s = time;
  }
  ASSERT_GT(first_release_s, 0.0);
  // Predicted: the fitted speed falls to v_s + T_rel |a|.
  double expected = -1.0;
  for (double time = 0.0; time < 0.375; time += dt / 64)
    if (amp * w * std::cos(w * time) < vs + t_rel * amp * w * w * std::sin(w * time)) {
      expected = time;
      break;
    }
  // Within 3 ms: the quadratic fit over 15 ms of a sine misses its third derivative (2.3 ms here).
  EXPECT_NEAR(first_release_s, expected, 0.003);
  EXPECT_GT(first_release_s, 0.375 - t_rel - 0.2);  // not before the motion slows
  // T_rel = τ + (Fc_max - Fc_min) / |G_1 + G_2| / v_lim with the default actuators (35 ms, 0.6 in/s).
  const control::FrictionInverse& inv = lead.inverse();
  const double swing_in = (inv.range(1.0).max_kip - inv.range(1.0).min_kip) / -(inv.gain_kip_per_in(true, 1) + inv.gain_kip_per_in(true, 2));
  EXPECT_NEAR(t_rel, 0.035 + swing_in / 0.6, 1e-12);
}

TEST(Controller, LyapunovConfigBlockIsStrict) {
  const std::string ok = "law: lyapunov\nlyapunov: {reversal_lead: 0.5, motion_window_s: 0.03}\n";
  const control::ControlConfig c = control::control_config_from_yaml(common::YamlSection(YAML::Load(ok), "t.yaml", ""));
  EXPECT_EQ(c.reversal_lead, 0.5);
  EXPECT_EQ(c.motion_window_s, 0.03);
  EXPECT_EQ(control::ControlConfig{}.reversal_lead, 1.0);
  for (const char* bad : {"law: lyapunov\nlyapunov: {reversal_lead: -1}\n", "law: lyapunov\nlyapunov: {lead: 1}\n"}) {
    try {
      control::control_config_from_yaml(common::YamlSection(YAML::Load(bad), "t.yaml", ""));
      ADD_FAILURE() << bad;
    } catch (const common::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("t.yaml"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("lead"), std::string::npos) << e.what();
    }
  }
}

TEST(QuadraticMotionFit, ExactOnAQuadraticAndTheThreePointFormulaAtThreeSamples) {
  const double dt = 1.0 / 1024;
  const control::QuadraticMotionFit fit(16, dt);
  // d(t) = 0.3 + 2 t - 7 t²: v = 2 - 14 t, a = -14 at the newest sample t = 15 dt.
  auto d = [&](int i) { const double t = i * dt; return 0.3 + 2.0 * t - 7.0 * t * t; };
  double v = 0.0, a = 0.0;
  fit.estimate(d, v, a);
  EXPECT_NEAR(v, 2.0 - 14.0 * 15 * dt, 1e-9);
  EXPECT_NEAR(a, -14.0, 1e-6);
  const control::QuadraticMotionFit three(3, dt);
  auto x = [](int i) { return i == 0 ? 0.1 : i == 1 ? 0.25 : 0.3; };
  three.estimate(x, v, a);
  EXPECT_NEAR(v, (3 * 0.3 - 4 * 0.25 + 0.1) / (2 * dt), 1e-9);
  EXPECT_NEAR(a, (0.3 - 2 * 0.25 + 0.1) / (dt * dt), 1e-4);
  EXPECT_THROW(control::QuadraticMotionFit(2, dt), std::invalid_argument);
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
