// Physical sanity of each hidden-effect shape of damper/synthetic against closed forms and
// against the project's own replay of the base model (damper::replay_force_kip).
#include "damper/synthetic/hidden_shapes.h"

#include "damper/model/brfd_config.h"
#include "damper/data/brfd_data.h"
#include "damper/data/replay.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace ds = damper::synthetic;

namespace {

constexpr double kPi = 3.14159265358979323846;

damper::BrfdParams paper_params() {
  return damper::load_brfd_params(std::string(HYBRIDSIM_SOURCE_DIR) + "/configs/brfd-semiactive.yaml");
}

/// The paper's model with a stiff band (σ0 = 3000 kip/in instead of 15.4): the bristle state
/// then tracks its steady state z = g(v)/σ0 within ~0.001-0.002 in of travel, so steady sliding
/// force minus σ2 v is the Stribeck level g(v) of the moment, and friction factors can be read
/// off as ratios. With σ0 = 15.4 the LuGre lag length g/σ0 is 0.17-0.46 in and smears them.
damper::BrfdParams stiff_band_params() {
  auto p = paper_params();
  p.lugre.sigma0_kip_per_in = 3000.0;
  return p;
}

ds::SyntheticSpec quiet_spec(ds::HiddenShape shape) {
  ds::SyntheticSpec s;
  s.effect.shape = shape;
  s.noise_std_kip = 0.0;
  return s;
}

/// Index of the samples where the drum velocity changes sign (first sample of the new sign).
std::vector<std::size_t> reversals(const damper::BrfdTest& t) {
  std::vector<std::size_t> r;
  int dir = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double v = t.drum_vel_in_per_s[i];
    const int d = v > 0 ? 1 : (v < 0 ? -1 : 0);
    if (d != 0 && d != dir) {
      if (dir != 0) r.push_back(i);
      dir = d;
    }
  }
  return r;
}

/// Travel since the last reversal at every sample (0 before the first).
std::vector<double> travel_since_reversal(const damper::BrfdTest& t) {
  std::vector<double> s(t.size(), 0.0);
  const auto rev = reversals(t);
  std::size_t k = 0;
  double x_rev = 0.0;
  bool have = false;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (k < rev.size() && rev[k] == i) {
      x_rev = t.drum_disp_in[i - 1];
      have = true;
      ++k;
    }
    s[i] = have ? std::abs(t.drum_disp_in[i] - x_rev) : 0.0;
  }
  return s;
}

}  // namespace

TEST(SyntheticMotion, HarmonicProfileIsThePapersRampedSineWithTable3Moves) {
  const auto p = paper_params();
  const auto gen = ds::generate_synthetic_test(p, quiet_spec(ds::HiddenShape::none));
  const auto& t = gen.test;
  ASSERT_EQ(t.size(), 15361u);  // 15 s at 1024 Hz like the measured files
  // Ramp: x = (t/2) sin(πt) in the first cycle (measured tests: 0.23 in at 0.5 s, -0.77 at 1.5 s).
  EXPECT_NEAR(t.drum_disp_in[512], 0.25, 1e-12);
  EXPECT_NEAR(t.drum_disp_in[1536], -0.75, 1e-12);
  double peak = 0.0;
  for (std::size_t i = 2048; i < 12288; ++i) peak = std::max(peak, std::abs(t.drum_disp_in[i]));
  EXPECT_NEAR(peak, 1.0, 1e-6);
  for (std::size_t i = 14336; i < t.size(); ++i) {  // at rest after 14 s
    ASSERT_EQ(t.drum_vel_in_per_s[i], 0.0);
    ASSERT_EQ(t.drum_disp_in[i], 0.0);
  }
  // Velocity is the derivative of displacement.
  for (std::size_t i = 1; i + 1 < t.size(); i += 97) {
    const double cd = (t.drum_disp_in[i + 1] - t.drum_disp_in[i - 1]) / (2 * t.dt_s);
    ASSERT_NEAR(t.drum_vel_in_per_s[i], cd, 2e-3) << "t=" << t.time_s[i];
  }
  // Test 6 of Table 3: both actuators 0.015 in, backward strokes starting at 4.5, 6.5, 8.5 s.
  const auto moves = ds::paper_harmonic_moves(6);
  ASSERT_EQ(moves.size(), 3u);
  EXPECT_DOUBLE_EQ(moves[0].start_s, 4.5);
  EXPECT_DOUBLE_EQ(moves[2].start_s, 8.5);
  EXPECT_DOUBLE_EQ(moves[0].amplitude_in, 0.015);
  EXPECT_TRUE(moves[0].actuator1 && moves[0].actuator2);
  // During a backward stroke (maximum of x at 4.5 s): retract first, x1 - x'1 = -0.015 at 4.75 s.
  EXPECT_LT(t.drum_vel_in_per_s[static_cast<std::size_t>(4.75 * 1024)], 0.0);
  EXPECT_NEAR(t.actuator1_in[static_cast<std::size_t>(4.75 * 1024)] - p.semiactive.actuator1_initial_in,
              -0.015, 1e-9);
  EXPECT_NEAR(t.actuator2_in[static_cast<std::size_t>(5.25 * 1024)] - p.semiactive.actuator2_initial_in,
              0.015, 1e-9);
  EXPECT_EQ(t.actuator1_in[static_cast<std::size_t>(4.0 * 1024)], p.semiactive.actuator1_initial_in);
  // Test 1: actuator one only, 0.03 in, forward strokes starting at 3.5 s.
  const auto m1 = ds::paper_harmonic_moves(1);
  EXPECT_DOUBLE_EQ(m1[0].start_s, 3.5);
  EXPECT_TRUE(m1[0].actuator1 && !m1[0].actuator2);
  EXPECT_THROW(ds::paper_harmonic_moves(7), std::invalid_argument);
}

TEST(SyntheticMotion, EarthquakeMotionIsBroadbandSeededAndEndsAtRest) {
  const auto p = paper_params();
  auto spec = quiet_spec(ds::HiddenShape::none);
  spec.motion = ds::SyntheticSpec::Motion::earthquake;
  spec.seed = 7;
  const auto a = ds::generate_synthetic_test(p, spec);
  const auto b = ds::generate_synthetic_test(p, spec);
  spec.seed = 8;
  const auto c = ds::generate_synthetic_test(p, spec);
  EXPECT_EQ(a.test.drum_disp_in, b.test.drum_disp_in);
  EXPECT_NE(a.test.drum_disp_in, c.test.drum_disp_in);
  double peak = 0.0;
  for (std::size_t i = 0; i < a.test.size(); ++i)
    if (a.test.time_s[i] < 13.5) peak = std::max(peak, std::abs(a.test.drum_disp_in[i]));
  EXPECT_NEAR(peak, 1.0, 1e-12);
  for (std::size_t i = 14336; i < a.test.size(); ++i) {  // at rest at the residual drift
    ASSERT_EQ(a.test.drum_vel_in_per_s[i], 0.0);
    ASSERT_NEAR(a.test.drum_disp_in[i], 0.2, 1e-12);
  }
  for (std::size_t i = 1; i + 1 < a.test.size(); i += 53) {
    const double cd = (a.test.drum_disp_in[i + 1] - a.test.drum_disp_in[i - 1]) / (2 * a.test.dt_s);
    ASSERT_NEAR(a.test.drum_vel_in_per_s[i], cd, 5e-3) << "t=" << a.test.time_s[i];
  }
  // Broadband: many reversals of irregular spacing (a 0.5 Hz sine would give 28 in 14 s).
  const auto rev = reversals(a.test);
  std::printf("earthquake seed 7: %zu reversals\n", rev.size());
  EXPECT_GT(rev.size(), 15u);
  EXPECT_LT(rev.size(), 200u);
  double min_gap = 1e9, max_gap = 0.0;
  for (std::size_t k = 1; k < rev.size(); ++k) {
    const double gap = (rev[k] - rev[k - 1]) * a.test.dt_s;
    min_gap = std::min(min_gap, gap);
    max_gap = std::max(max_gap, gap);
  }
  EXPECT_GT(max_gap / min_gap, 2.0);
}

TEST(SyntheticShapes, NoneIsTheBaseModelPlusNoiseOfTheGivenStd) {
  const auto p = paper_params();
  auto spec = quiet_spec(ds::HiddenShape::none);
  const auto quiet = ds::generate_synthetic_test(p, spec);
  // The base model is the project's replay of the recorded inputs (independent code path).
  damper::BrfdTest replay_input = quiet.test;
  const auto replayed = damper::replay_force_kip(p, replay_input, 0, replay_input.size());
  for (std::size_t i = 0; i < replayed.size(); ++i)
    ASSERT_NEAR(quiet.test.force_kip[i], replayed[i], 1e-9) << "t=" << quiet.test.time_s[i];
  EXPECT_EQ(quiet.clean_force_kip, quiet.base_force_kip);
  EXPECT_EQ(quiet.label, "none");

  spec.noise_std_kip = 0.08;
  spec.seed = 42;
  const auto noisy = ds::generate_synthetic_test(p, spec);
  const auto again = ds::generate_synthetic_test(p, spec);
  EXPECT_EQ(noisy.test.force_kip, again.test.force_kip);  // deterministic per seed
  spec.seed = 43;
  EXPECT_NE(ds::generate_synthetic_test(p, spec).test.force_kip, noisy.test.force_kip);
  double sum = 0, sum2 = 0;
  const double n = static_cast<double>(noisy.test.size());
  for (std::size_t i = 0; i < noisy.test.size(); ++i) {
    const double e = noisy.test.force_kip[i] - replayed[i];
    sum += e;
    sum2 += e * e;
  }
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  std::printf("noise: mean %.5f kip, std %.5f kip (asked 0.08)\n", mean, sd);
  EXPECT_LT(std::abs(mean), 4 * 0.08 / std::sqrt(n));
  EXPECT_NEAR(sd, 0.08, 0.08 * 4 / std::sqrt(2 * n));  // 4 standard errors of a sample std
}

TEST(SyntheticShapes, JsonRoundTripThroughTheProjectsReader) {
  const auto p = paper_params();
  auto spec = quiet_spec(ds::HiddenShape::backlash);
  spec.noise_std_kip = 0.05;
  spec.name = "synthetic_backlash_seed1";
  const auto gen = ds::generate_synthetic_test(p, spec);
  std::filesystem::create_directories(BRFD_TEST_OUT_DIR);
  const std::string path = std::string(BRFD_TEST_OUT_DIR) + "/synthetic_backlash_seed1.json";
  const std::string truth = std::string(BRFD_TEST_OUT_DIR) + "/synthetic_backlash_seed1.truth.json";
  ds::write_measured_json(gen.test, path);
  ds::write_truth_json(gen, spec, truth);
  const damper::BrfdTest r = damper::read_brfd_test(path);
  EXPECT_EQ(r.name(), "synthetic_backlash_seed1");
  EXPECT_TRUE(r.has_actuator_positions);
  EXPECT_FALSE(r.velocity_derived);  // the velocity column is in in/s and agrees with dx/dt
  EXPECT_NEAR(r.velocity_column_ratio, 1.0, 0.01);
  EXPECT_EQ(r.dt_s, gen.test.dt_s);
  EXPECT_EQ(r.time_s, gen.test.time_s);
  EXPECT_EQ(r.drum_disp_in, gen.test.drum_disp_in);
  EXPECT_EQ(r.force_kip, gen.test.force_kip);
  EXPECT_EQ(r.drum_vel_in_per_s, gen.test.drum_vel_in_per_s);
  EXPECT_EQ(r.actuator1_in, gen.test.actuator1_in);
  EXPECT_EQ(r.actuator2_force_lb, gen.test.actuator2_force_lb);
  // Same keys as the lab files, and no label in the measured file.
  std::ifstream in(path);
  const auto doc = nlohmann::json::parse(in);
  for (const char* key : {"data", "dt", "sampling freq", "displacement units", "time units",
                          "friction force units", "actuator force units"})
    EXPECT_TRUE(doc.contains(key)) << key;
  EXPECT_EQ(doc["sampling freq"].get<long long>(), 1024);
  EXPECT_EQ(doc.size(), 7u);
  std::ifstream tin(truth);
  const auto tdoc = nlohmann::json::parse(tin);
  EXPECT_EQ(tdoc["label"], "backlash");
}

TEST(SyntheticShapes, LabelsAreTheFixedFamilyList) {
  std::vector<std::string> labels;
  for (auto s : ds::all_hidden_shapes()) {
    EXPECT_EQ(ds::hidden_shape_from_string(ds::to_string(s)), s);
    const auto f = ds::effect_family(s);
    EXPECT_NE(std::find(ds::effect_families().begin(), ds::effect_families().end(), f),
              ds::effect_families().end())
        << f;
    if (std::find(labels.begin(), labels.end(), f) == labels.end()) labels.push_back(f);
  }
  EXPECT_EQ(labels.size(), ds::effect_families().size());  // every family is reachable
  EXPECT_EQ(ds::effect_family(ds::HiddenShape::actuator_delay), "actuator_lag");
  try {
    ds::hidden_shape_from_string("stiction");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("stiction"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("backlash"), std::string::npos);
  }
  auto spec = quiet_spec(ds::HiddenShape::asymmetry);
  spec.effect.asymmetry.fraction = 1.5;
  try {
    ds::generate_synthetic_test(paper_params(), spec);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("asymmetry.fraction"), std::string::npos) << e.what();
  }
}

TEST(SyntheticShapes, BacklashForceNearZeroAfterReversalsAndRecoversWithinStatedTravel) {
  const auto p = paper_params();
  auto spec = quiet_spec(ds::HiddenShape::backlash);
  const ds::BacklashShape s = spec.effect.backlash;
  const auto gen = ds::generate_synthetic_test(p, spec);
  const auto& t = gen.test;
  const auto travel = travel_since_reversal(t);
  const auto rev = reversals(t);
  ASSERT_EQ(rev.size(), 14u);  // 7 drum cycles of 0.5 Hz in 14 s
  // Before the first reversal: the base model.
  for (std::size_t i = 0; i < rev[0]; ++i) ASSERT_EQ(t.force_kip[i], gen.base_force_kip[i]);
  const double fc_min = std::min(p.lugre.fc_fwd_kip, p.lugre.fc_bwd_kip);
  int checked = 0;
  for (std::size_t k = 0; k < rev.size(); ++k) {
    const std::size_t end = k + 1 < rev.size() ? rev[k + 1] : t.size();
    const double stroke = travel[end - 1];
    if (stroke < s.free_travel_in + s.contact_travel_in + 0.4) continue;  // ramp strokes too short
    ++checked;
    const double f_rev = t.force_kip[rev[k] - 1];
    EXPECT_GT(std::abs(f_rev), fc_min);  // full friction before the reversal
    double max_free = 0.0;
    std::size_t i_q1 = 0, i_q3 = 0, i_end = 0;
    const double sf = s.free_travel_in, sc = s.contact_travel_in;
    for (std::size_t i = rev[k]; i < end; ++i) {
      if (travel[i] >= s.unload_travel_in && travel[i] < sf)
        max_free = std::max(max_free, std::abs(t.force_kip[i]));
      if (i_q1 == 0 && travel[i] >= sf + 0.25 * sc) i_q1 = i;
      if (i_q3 == 0 && travel[i] >= sf + 0.75 * sc) i_q3 = i;
      if (i_end == 0 && travel[i] >= sf + sc) i_end = i;
    }
    ASSERT_TRUE(i_q1 && i_q3 && i_end);
    // Stage 1: free travel with zero force (after the unloading over s_u).
    EXPECT_LT(max_free, 1e-9) << "reversal at t=" << t.time_s[rev[k]];
    // Stage 2: the band spring force (the force less the viscous part σ2 ξ v the band takes up)
    // stiffens as σ0 ξ: secant stiffness over the first quarter of s_c about 1/7 of the last
    // quarter's (elastic band: ξ²/2 law).
    std::size_t i_start = rev[k];
    while (travel[i_start] < sf) ++i_start;
    auto spring = [&](std::size_t i) {
      const double xi = std::min(1.0, std::max(0.0, (travel[i] - sf) / sc));
      return std::abs(t.force_kip[i] - p.lugre.sigma2_kip_s_per_in * xi * t.drum_vel_in_per_s[i]);
    };
    const double k_first = (spring(i_q1) - spring(i_start)) / (travel[i_q1] - travel[i_start]);
    const double k_last = (spring(i_end) - spring(i_q3)) / (travel[i_end] - travel[i_q3]);
    EXPECT_LT(k_first, 0.3 * k_last) << "t=" << t.time_s[rev[k]];
    // Stage 3 starts at s_f + s_c with about the band's full stiffness σ0 (dF/ds over 0.01 in).
    std::size_t j = i_end;
    while (j < end && travel[j] < travel[i_end] + 0.01) ++j;
    const double k_full = (spring(j) - spring(i_end)) / (travel[j] - travel[i_end]);
    EXPECT_GT(k_last, 0.6 * p.lugre.sigma0_kip_per_in) << "t=" << t.time_s[rev[k]];
    EXPECT_GT(k_full, 0.6 * p.lugre.sigma0_kip_per_in) << "t=" << t.time_s[rev[k]];
    if (checked == 5)
      std::printf("backlash stroke at t=%.3f s: F_rev %.3f kip, stiffness first/last quarter of "
                  "contact %.2f / %.2f kip/in, full %.2f kip/in (sigma0 %.2f)\n",
                  t.time_s[rev[k]], f_rev, k_first, k_last, k_full, p.lugre.sigma0_kip_per_in);
    // Recovered: the force regains the base model's friction level within s_f + s_c plus the
    // base model's own elastic transition 2 Fs/σ0 (the engaged band restarts from zero).
    const double recover = s.free_travel_in + s.contact_travel_in +
                           2.0 * std::max(p.lugre.fs_fwd_kip, p.lugre.fs_bwd_kip) / p.lugre.sigma0_kip_per_in;
    for (std::size_t i = rev[k]; i < end; ++i) {
      if (travel[i] < recover) continue;
      ASSERT_NEAR(t.force_kip[i], gen.base_force_kip[i], 0.1 * std::abs(gen.base_force_kip[i]) + 0.05)
          << "t=" << t.time_s[i] << " travel " << travel[i];
    }
  }
  std::printf("backlash: %d full strokes checked\n", checked);
  EXPECT_GE(checked, 10);
}

TEST(SyntheticShapes, SecondOrderActuatorOvershootAndPeakTimeMatchClosedForm) {
  for (double zeta : {0.15, 0.4, 0.7}) {
    const double fn = 3.0, wn = 2 * kPi * fn, dt = 1.0 / 1024;
    ds::SecondOrderActuator a(fn, zeta, 0.0);
    double peak = 0.0, t_peak = 0.0;
    for (int i = 1; i < 4096; ++i) {
      const double x = a.step(1.0, dt);
      if (x > peak) {
        peak = x;
        t_peak = i * dt;
      }
    }
    const double wd = wn * std::sqrt(1 - zeta * zeta);
    // Sampled peak: within ω_n² (dt/2)²/2 ≈ 4e-5 of the continuous one at 3 Hz.
    EXPECT_NEAR(peak - 1.0, std::exp(-zeta * kPi / std::sqrt(1 - zeta * zeta)), 1e-4) << zeta;
    EXPECT_NEAR(t_peak, kPi / wd, dt) << zeta;
    EXPECT_NEAR(a.position_in(), 1.0, 1e-4);
  }
  // In a generated test the recorded positions are the commands; the model saw the filtered ones.
  const auto p = paper_params();
  const auto gen = ds::generate_synthetic_test(p, quiet_spec(ds::HiddenShape::actuator_second_order));
  double max_pos = 0.0, max_force = 0.0;
  for (std::size_t i = 0; i < gen.test.size(); ++i) {
    max_pos = std::max(max_pos, std::abs(gen.actuator1_effective_in[i] - gen.test.actuator1_in[i]));
    max_force = std::max(max_force, std::abs(gen.test.force_kip[i] - gen.base_force_kip[i]));
    if (gen.test.time_s[i] < 4.5) {  // before the first move
      ASSERT_EQ(gen.test.force_kip[i], gen.base_force_kip[i]);
    }
  }
  std::printf("actuator_second_order: max |x_eff - x_cmd| %.4f in, max force change %.3f kip\n",
              max_pos, max_force);
  EXPECT_GT(max_pos, 0.003);
  EXPECT_GT(max_force, 0.1);
}

TEST(SyntheticShapes, ActuatorDelayIsAPureShift) {
  const auto p = paper_params();
  auto spec = quiet_spec(ds::HiddenShape::actuator_delay);
  spec.effect.actuator_delay.delay_s = 100.0 / 1024;  // whole samples: exact shift
  const auto gen = ds::generate_synthetic_test(p, spec);
  for (std::size_t i = 100; i < gen.test.size(); ++i) {
    ASSERT_DOUBLE_EQ(gen.actuator1_effective_in[i], gen.test.actuator1_in[i - 100]);
    ASSERT_DOUBLE_EQ(gen.actuator2_effective_in[i], gen.test.actuator2_in[i - 100]);
  }
  double max_force = 0.0;
  for (std::size_t i = 0; i < gen.test.size(); ++i)
    max_force = std::max(max_force, std::abs(gen.test.force_kip[i] - gen.base_force_kip[i]));
  EXPECT_GT(max_force, 0.1);
}

namespace {
/// Steady-sliding samples (far from reversals, no actuator move): F - σ2 v is the Stribeck
/// level g(v) of the model, so the ratio of two such levels is the friction factor.
struct SlidingRatio {
  std::vector<double> ratio, x, v;
};
SlidingRatio sliding_ratio(const ds::SyntheticTest& gen, const damper::BrfdParams& p, double min_travel) {
  SlidingRatio r;
  const auto travel = travel_since_reversal(gen.test);
  const double s2 = p.lugre.sigma2_kip_s_per_in;
  for (std::size_t i = 0; i < gen.test.size(); ++i) {
    const double v = gen.test.drum_vel_in_per_s[i];
    if (travel[i] < min_travel || std::abs(v) < 0.5 || gen.test.time_s[i] > 12.0) continue;
    r.ratio.push_back((gen.clean_force_kip[i] - s2 * v) / (gen.base_force_kip[i] - s2 * v));
    r.x.push_back(gen.test.drum_disp_in[i]);
    r.v.push_back(v);
  }
  return r;
}
}  // namespace

TEST(SyntheticShapes, DisplacementFrictionRisesEvenlyWithDrumDisplacement) {
  const auto p = stiff_band_params();
  auto spec = quiet_spec(ds::HiddenShape::displacement_friction);
  spec.harmonic.moves.clear();  // passive: b and Fs are the only friction levels
  const auto gen = ds::generate_synthetic_test(p, spec);
  const auto& s = spec.effect.displacement_friction;
  const auto r = sliding_ratio(gen, p, 0.8);
  ASSERT_GT(r.ratio.size(), 1000u);
  double worst = 0.0, max_ratio = 0.0;
  for (std::size_t k = 0; k < r.ratio.size(); ++k) {
    const double expect = 1.0 + s.gain_per_in_p * std::pow(std::abs(r.x[k]), s.exponent);
    worst = std::max(worst, std::abs(r.ratio[k] / expect - 1.0));
    max_ratio = std::max(max_ratio, r.ratio[k]);
  }
  std::printf("displacement_friction: worst relative deviation from 1+k|x|^p %.4f, max ratio %.3f\n",
              worst, max_ratio);
  EXPECT_LT(worst, 0.03);
  EXPECT_GT(max_ratio, 1.2);  // near |x| = 1 in: 1 + 0.3
}

TEST(SyntheticShapes, VelocityFrictionFollowsTheSteadyRateAndStateLaw) {
  const auto p = stiff_band_params();
  auto spec = quiet_spec(ds::HiddenShape::velocity_friction);
  spec.harmonic.moves.clear();
  const auto gen_memory = ds::generate_synthetic_test(p, spec);  // D_c = 0.05 in (default)
  spec.effect.velocity_friction.memory_length_in = 0.01;         // short memory: near steady
  const auto gen = ds::generate_synthetic_test(p, spec);
  const auto& s = spec.effect.velocity_friction;
  const auto r = sliding_ratio(gen, p, 0.8);
  ASSERT_GT(r.ratio.size(), 1000u);
  // Steady state holds where the state θ keeps up: its relaxation time D_c/v (0.03 s at
  // 1.5 in/s) is short against the time the speed takes to change. Near the stroke ends the
  // speed falls faster than θ follows (the rate-and-state memory), and the ratio lags.
  double worst = 0.0, worst_all = 0.0, lo = 1e9, hi = 0.0, r_fast = 0.0, r_slow = 0.0;
  int n_fast = 0, n_slow = 0;
  for (std::size_t k = 0; k < r.ratio.size(); ++k) {
    const double vs = std::abs(r.v[k]) + s.speed_floor_in_per_s;
    const double expect = 1.0 + (s.a - s.b_rs) * std::log(vs / s.ref_speed_in_per_s);
    const double dev = std::abs(r.ratio[k] / expect - 1.0);
    worst_all = std::max(worst_all, dev);
    if (std::abs(r.v[k]) < 1.5) continue;
    worst = std::max(worst, dev);
    lo = std::min(lo, r.ratio[k]);
    hi = std::max(hi, r.ratio[k]);
    if (std::abs(r.v[k]) > 2.8) r_fast += r.ratio[k], ++n_fast;
    if (std::abs(r.v[k]) < 1.8) r_slow += r.ratio[k], ++n_slow;
  }
  std::printf("velocity_friction: worst deviation from steady state %.4f at |v| >= 1.5 in/s (%.4f "
              "at all speeds), ratio range %.3f-%.3f\n", worst, worst_all, lo, hi);
  EXPECT_LT(worst, 0.01);
  ASSERT_GT(n_fast, 100);
  ASSERT_GT(n_slow, 100);
  // Weakening: (b - a) ln(2.9/1.65) = 0.056 less friction at the fast end.
  EXPECT_NEAR(r_slow / n_slow - r_fast / n_fast, 0.056, 0.015);
  // The longer memory (D_c = 0.05 in) departs further from the steady law at |v| >= 1.5 in/s.
  const auto rm = sliding_ratio(gen_memory, p, 0.8);
  double worst_memory = 0.0;
  for (std::size_t k = 0; k < rm.ratio.size(); ++k) {
    if (std::abs(rm.v[k]) < 1.5) continue;
    const double vs = std::abs(rm.v[k]) + s.speed_floor_in_per_s;
    worst_memory = std::max(worst_memory, std::abs(rm.ratio[k] / (1.0 + (s.a - s.b_rs) * std::log(vs / s.ref_speed_in_per_s)) - 1.0));
  }
  std::printf("velocity_friction: D_c = 0.05 in: worst deviation %.4f at |v| >= 1.5 in/s\n", worst_memory);
  EXPECT_GT(worst_memory, 2.0 * worst);
}

TEST(SyntheticShapes, ResidualStaticForceRelaxesExponentiallyAtRest) {
  const auto p = paper_params();
  auto spec = quiet_spec(ds::HiddenShape::residual_static);
  const auto gen = ds::generate_synthetic_test(p, spec);
  const auto& s = spec.effect.residual_static;
  const std::size_t stop = 14 * 1024;
  const double f_stop = gen.base_force_kip[stop];
  ASSERT_GT(std::abs(f_stop), 0.5);
  for (std::size_t i = stop + 1; i < gen.test.size(); ++i) {
    ASSERT_EQ(gen.base_force_kip[i], f_stop);  // the base model holds its force at rest
    const double tt = (i - stop) * gen.test.dt_s;
    const double expect = f_stop * ((1 - s.relaxed_fraction) + s.relaxed_fraction * std::exp(-tt / s.time_constant_s));
    ASSERT_NEAR(gen.test.force_kip[i], expect, 0.01 * std::abs(f_stop)) << "t=" << gen.test.time_s[i];
  }
  // While sliding the residual is wiped: the force is the base model's (it acts briefly at the
  // drum's reversals, where v passes 0, and is wiped again within ~0.1 in of travel).
  double max_sliding = 0.0;
  const auto travel = travel_since_reversal(gen.test);
  for (std::size_t i = 2048; i < 12288; ++i)
    if (travel[i] > 0.1 && std::abs(gen.test.drum_vel_in_per_s[i]) > 0.1)
      max_sliding = std::max(max_sliding, std::abs(gen.test.force_kip[i] - gen.base_force_kip[i]));
  EXPECT_LT(max_sliding, 1e-3);
}

TEST(SyntheticShapes, ViscousAndAsymmetry) {
  const auto p = paper_params();
  auto spec = quiet_spec(ds::HiddenShape::viscous);
  spec.effect.viscous.exponent = 0.5;
  const auto vis = ds::generate_synthetic_test(p, spec);
  for (std::size_t i = 0; i < vis.test.size(); ++i) {
    const double v = vis.test.drum_vel_in_per_s[i];
    ASSERT_NEAR(vis.test.force_kip[i] - vis.base_force_kip[i],
                0.25 * std::sqrt(std::abs(v)) * (v > 0 ? 1 : (v < 0 ? -1 : 0)), 1e-12);
  }
  spec = quiet_spec(ds::HiddenShape::asymmetry);
  spec.harmonic.moves.clear();
  const auto ps = stiff_band_params();
  const auto asy = ds::generate_synthetic_test(ps, spec);
  const auto r = sliding_ratio(asy, ps, 0.8);
  ASSERT_GT(r.ratio.size(), 1000u);
  for (std::size_t k = 0; k < r.ratio.size(); ++k)
    ASSERT_NEAR(r.ratio[k], r.v[k] > 0 ? 1.2 : 0.8, 0.02) << "v=" << r.v[k];
}

TEST(SyntheticShapes, EveryShapeOnBothMotionsIsReadableAndVisibleAboveNoise) {
  const auto p = paper_params();
  std::filesystem::create_directories(BRFD_TEST_OUT_DIR);
  for (auto motion : {ds::SyntheticSpec::Motion::harmonic, ds::SyntheticSpec::Motion::earthquake}) {
    for (auto shape : ds::all_hidden_shapes()) {
      ds::SyntheticSpec spec;
      spec.motion = motion;
      spec.effect.shape = shape;
      spec.noise_std_kip = 0.05;
      spec.seed = 11;
      const auto gen = ds::generate_synthetic_test(p, spec);
      double se = 0.0, ss = 0.0, mean = 0.0, peak = 0.0;
      for (double f : gen.base_force_kip) mean += f / gen.base_force_kip.size();
      for (std::size_t i = 0; i < gen.test.size(); ++i) {
        const double d = gen.clean_force_kip[i] - gen.base_force_kip[i];
        se += d * d;
        peak = std::max(peak, std::abs(d));
        ss += (gen.base_force_kip[i] - mean) * (gen.base_force_kip[i] - mean);
      }
      const double rms = std::sqrt(se / gen.test.size());
      std::printf("%-10s %-22s label %-22s effect rms %.3f kip, max %.3f kip; rms = %.3f of std(base) %.3f kip\n",
                  motion == ds::SyntheticSpec::Motion::harmonic ? "harmonic" : "earthquake",
                  ds::to_string(shape).c_str(), gen.label.c_str(), rms, peak,
                  rms / std::sqrt(ss / gen.test.size()), std::sqrt(ss / gen.test.size()));
      if (shape == ds::HiddenShape::none)
        EXPECT_EQ(rms, 0.0);
      else
        EXPECT_GT(peak, 4 * spec.noise_std_kip) << ds::to_string(shape);  // above the noise
      const std::string path = std::string(BRFD_TEST_OUT_DIR) + "/roundtrip.json";
      ds::write_measured_json(gen.test, path);
      const auto r = damper::read_brfd_test(path);
      ASSERT_EQ(r.force_kip, gen.test.force_kip);
      ASSERT_FALSE(r.velocity_derived);
    }
  }
}
