// The rig emulator's physical BRFD (damper/rig/rig_simulator.h), in-process: each effect is
// there when switched on and gone when switched off: actuator delay and lag, sensor noise,
// backlash after a reversal, residual static force after motion stops.
#include "damper/physical/tracking.h"
#include "damper/rig/rig_config.h"
#include "damper/rig/rig_simulator.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace {

using damper::rig::RigConfig;
using damper::rig::RigSimulator;

constexpr double kDt = 1.0 / 1024.0;

RigConfig quiet_config() {
  RigConfig c = damper::rig::load_rig_config(test_paths::source_dir() + "/configs/rig-default.yaml");
  c.noise.enabled = false;
  c.backlash.enabled = false;
  c.residual_force.enabled = false;
  c.residual_force.initial_kip = 0.0;
  return c;
}

double sine(double t) { return 0.8 * std::sin(2 * M_PI * 0.5 * t); }

// Runs a 0.5 Hz, 0.8 in sine for `seconds`; returns measured drum and force series.
void run(RigSimulator& rig, const RigConfig& c, double seconds, std::vector<double>& cmd, std::vector<double>& drum,
         std::vector<double>& force) {
  const int n = static_cast<int>(seconds / kDt);
  for (int k = 0; k < n; ++k) {
    cmd.push_back(sine(k * kDt));
    rig.step({cmd.back(), c.initial.actuator1_in, c.initial.actuator2_in});
    drum.push_back(rig.reading().drum_in);
    force.push_back(rig.reading().friction_kip);
  }
}

TEST(RigSimulator, ActuatorDelayAndLagAreSwitchable) {
  RigConfig c = quiet_config();
  c.hydraulic.delay_s = 0.020;
  c.hydraulic.lag_time_constant_s = 0.006;
  std::vector<double> cmd, drum, force;
  RigSimulator rig(c);
  run(rig, c, 6.0, cmd, drum, force);
  const double delay = damper::physical::cross_correlation_delay_ms(cmd, drum, kDt, 0, cmd.size(), 100);
  std::printf("emulated 20 ms delay + 6 ms lag: measured %.2f ms\n", delay);
  EXPECT_NEAR(delay, 26.0, 1.5);

  c.hydraulic.enabled = false;
  RigSimulator ideal(c);
  std::vector<double> cmd2, drum2, force2;
  run(ideal, c, 2.0, cmd2, drum2, force2);
  for (std::size_t i = 0; i < cmd2.size(); ++i) ASSERT_DOUBLE_EQ(drum2[i], cmd2[i]);
}

TEST(RigSimulator, SensorNoiseHasTheConfiguredSpread) {
  RigConfig c = quiet_config();
  c.noise.enabled = true;
  c.noise.friction_force_std_kip = 0.05;
  RigSimulator rig(c);
  double sum = 0, sum2 = 0;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {  // at rest: the reading is noise around the true force
    rig.step({0.0, c.initial.actuator1_in, c.initial.actuator2_in});
    const double e = rig.reading().friction_kip - rig.truth().friction_kip;
    sum += e;
    sum2 += e * e;
  }
  EXPECT_NEAR(std::sqrt(sum2 / n - (sum / n) * (sum / n)), 0.05, 0.003);
}

TEST(RigSimulator, BacklashHoldsTheForceNearZeroRightAfterEachReversal) {
  RigConfig c = quiet_config();
  c.hydraulic.enabled = false;
  std::vector<double> cmd, drum, with, without;
  {
    c.backlash.enabled = true;
    RigSimulator rig(c);
    run(rig, c, 4.0, cmd, drum, with);
  }
  {
    c.backlash.enabled = false;
    RigSimulator rig(c);
    std::vector<double> cmd2, drum2;
    run(rig, c, 4.0, cmd2, drum2, without);
  }
  // First reversal of the sine at t = 0.5 s (drum at +0.8 in). Look at the travel window
  // 0.02-0.06 in after it (inside release 0.01 + gap 0.05).
  double max_with = 0, max_without = 0;
  int samples = 0;
  for (std::size_t k = 512; k < 1536; ++k) {
    const double travel = 0.8 - drum[k];
    if (travel > 0.02 && travel < 0.06) {
      max_with = std::max(max_with, std::abs(with[k]));
      max_without = std::max(max_without, std::abs(without[k]));
      ++samples;
    }
  }
  std::printf("after the reversal (%d samples, 0.02-0.06 in of travel): |F| <= %.3f kip with backlash, up to %.3f kip without\n",
              samples, max_with, max_without);
  ASSERT_GT(samples, 10);
  EXPECT_LT(max_with, 0.15);
  EXPECT_GT(max_without, 1.0);
}

TEST(RigSimulator, ResidualStaticForceStaysAfterMotionStopsAndIsThereAtTheStart) {
  RigConfig c = quiet_config();
  c.hydraulic.enabled = false;
  c.residual_force.enabled = true;
  c.residual_force.initial_kip = 0.4;
  RigSimulator rig(c);
  rig.step({0.0, c.initial.actuator1_in, c.initial.actuator2_in});
  EXPECT_NEAR(rig.truth().friction_kip, 0.4, 1e-9);  // locked in before any motion
  // Move forward 0.5 in in 1 s, then stop for 1 s.
  for (int k = 1; k <= 1024; ++k) rig.step({0.5 * k / 1024.0, c.initial.actuator1_in, c.initial.actuator2_in});
  for (int k = 0; k < 1024; ++k) rig.step({0.5, c.initial.actuator1_in, c.initial.actuator2_in});
  const double locked = rig.truth().friction_kip;
  const double expected = c.residual_force.fraction * c.model.lugre.fc_fwd_kip;
  std::printf("force 1 s after the drum stopped: %.3f kip (fraction x Fc = %.3f kip)\n", locked, expected);
  EXPECT_NEAR(locked, expected, 0.05);

  // A noise-sized move (a positioning step of 0.3 mil) does not re-tension the bands.
  RigSimulator small(c);
  for (int k = 0; k < 1024; ++k) small.step({0.0003, c.initial.actuator1_in, c.initial.actuator2_in});  // 0.3 in/s for a tick
  EXPECT_NEAR(small.truth().friction_kip, 0.4, 0.05);

  c.residual_force.enabled = false;
  RigSimulator plain(c);
  plain.step({0.0, c.initial.actuator1_in, c.initial.actuator2_in});
  EXPECT_NEAR(plain.truth().friction_kip, 0.0, 1e-9);
}

TEST(RigSimulator, BandActuatorLoadCellsFollowTheScalingFactors) {
  RigConfig c = quiet_config();
  c.hydraulic.enabled = false;
  RigSimulator rig(c);
  for (int k = 1; k <= 1024; ++k) rig.step({0.5 * k / 1024.0, c.initial.actuator1_in, c.initial.actuator2_in});
  const auto& t = rig.truth();
  ASSERT_GT(t.friction_kip, 1.0);  // forward: band 2 taut
  const auto& C = c.model.semiactive.scaling;
  EXPECT_NEAR(t.actuator2_force_lb, c.electric.band_pretension_lb + 1000.0 * t.friction_kip / C[1], 1e-9);
  EXPECT_NEAR(t.actuator1_force_lb, c.electric.band_pretension_lb + 1000.0 * t.friction_kip / C[0], 1e-9);
  EXPECT_GT(t.actuator2_force_lb, 10 * t.actuator1_force_lb - 400);
}

}  // namespace
