// Reading, split and regimes of `diagnose` (damper/diagnose/diagnose_data.h) on a synthetic record with a
// known drive, and the recorded-run CSV reader.
#include "damper/diagnose/diagnose_data.h"
#include "damper/diagnose/diagnose_select.h"
#include "synthetic.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace damper {
namespace {

using diagnose_test::make_record;
using diagnose_test::synthetic_base;

std::string temp_dir(const std::string& name) {
  const std::filesystem::path d = std::filesystem::temp_directory_path() / name;
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d.string();
}

TEST(DiagnoseData, SplitAndRegimesFollowTheDrive) {
  const BrfdTest t = make_record(synthetic_base());
  const Segmentation s = segment_record(t);
  const double dt = t.dt_s;
  // Passive window: until actuator 1 starts to retract at 3.5 s.
  EXPECT_NEAR(s.passive_end * dt, 3.5, 0.05);
  EXPECT_TRUE(s.actuated);
  // 0.5 Hz for 12 s: reversals at the displacement extrema, 0.5, 1.5, ... 11.5 s outside the
  // 2 s ramps (the ramps shift them).
  EXPECT_GE(s.reversals.size(), 10u);
  for (std::size_t r : s.reversals) {
    const double t_r = r * dt;
    if (t_r > 2.0 && t_r < 10.0) {
      EXPECT_NEAR(t_r - std::round(t_r - 0.5) - 0.5, 0.0, 0.01) << t_r;
    }
  }
  // Rest from about 12 s, split in halves: first training, second held-out.
  EXPECT_NEAR(s.rest_begin * dt, 12.0, 0.4);
  EXPECT_EQ(s.regime.back(), Regime::after_stop);
  EXPECT_EQ(s.train.back(), 0);
  EXPECT_EQ(s.train[s.rest_begin + 10], 1);
  // Training before the first actuator motion, then drum cycles alternate.
  for (std::size_t i = 0; i < s.passive_end; ++i) ASSERT_EQ(s.train[i], 1);
  std::size_t heldout = 0, flips = 0;
  for (std::size_t i = 1; i < t.size(); ++i) {
    heldout += s.train[i] ? 0 : 1;
    flips += s.train[i] != s.train[i - 1] ? 1 : 0;
  }
  EXPECT_GT(heldout * dt, 3.0);
  EXPECT_GE(flips, 5u);
  // Regimes at chosen instants: right after the reversal at 5.5 s, sliding at 6.0 s (|v| max),
  // actuators moving at 4.25 s, sticking just before the reversal at 9.5 s.
  auto at = [&](double time) { return s.regime[static_cast<std::size_t>(std::lround(time / dt))]; };
  EXPECT_EQ(at(5.55), Regime::reversal);
  EXPECT_EQ(at(6.0), Regime::sliding);
  EXPECT_EQ(at(4.25), Regime::actuators);
  EXPECT_EQ(at(9.47), Regime::sticking);
  // The drum's own state ignores the actuators: where they move the drum slides or sticks, and
  // everywhere else it is the exclusive regime.
  std::size_t sliding_under_actuators = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (s.regime[i] == Regime::actuators) {
      ASSERT_TRUE(s.drum_regime[i] == Regime::sliding || s.drum_regime[i] == Regime::sticking) << i;
      ASSERT_EQ(s.actuators_moving[i], 1) << i;
      sliding_under_actuators += s.drum_regime[i] == Regime::sliding ? 1 : 0;
    } else {
      ASSERT_EQ(s.drum_regime[i], s.regime[i]) << i;
    }
  }
  EXPECT_EQ(s.drum_regime[static_cast<std::size_t>(std::lround(4.25 / dt))], Regime::sliding);
  EXPECT_GT(sliding_under_actuators * dt, 0.5);
}

// The band re-loading mask: a triangle wave of the drum (±1 in at 1 in/s, reversals every 2 s)
// and a force that, after each reversal, stays at its old sign for 0.4 in of travel and then
// changes sign linearly (a band that unloads late, as this device's bands do: Fc/σ0 ≈ 0.2-0.5 in).
// The mask must hold exactly from the force's zero crossing until the drum has travelled
// reversal_travel_in (0.25 in) beyond it, and nowhere else.
TEST(DiagnoseData, BandReloadingStartsWhereTheForceChangesSign) {
  BrfdTest t;
  t.dt_s = 1.0 / 1000.0;
  const int n = 8001;  // 8 s: reversals at 1, 3, 5, 7 s
  for (int i = 0; i < n; ++i) {
    const double time = i * t.dt_s;
    const double phase = std::fmod(time + 1.0, 4.0);  // 0..4 s: up 0..2, down 2..4
    const double d = phase < 2.0 ? -1.0 + phase : 3.0 - phase;
    const double v = phase < 2.0 ? 1.0 : -1.0;
    const double since = std::fmod(time - 1.0 + 4.0, 2.0);  // travel since the last reversal (in)
    const double sign = v;                                 // the new direction of sliding
    const double f = time < 1.0 ? 2.0 : (since < 0.4 ? -sign * 2.0 * (1.0 - since / 0.4) : sign * 2.0 * std::min(1.0, (since - 0.4) / 0.2));
    t.time_s.push_back(time);
    t.drum_disp_in.push_back(d);
    t.drum_vel_in_per_s.push_back(v);
    t.force_kip.push_back(f);
  }
  const Segmentation s = segment_record(t);
  ASSERT_EQ(s.band_reloading.size(), t.size());
  for (int i = 0; i < n; ++i) {
    const double time = i * t.dt_s;
    if (time < 1.2 || time > 7.9) continue;  // the first stroke and the ends
    const double since = std::fmod(time - 1.0 + 4.0, 2.0);
    const double after_crossing = since - 0.4;  // drum travel beyond the zero crossing, in
    if (std::abs(after_crossing) < 0.02 || std::abs(after_crossing - 0.25) < 0.02) continue;  // the edges (0.01 s average)
    const bool expected = after_crossing > 0.0 && after_crossing < 0.25;
    EXPECT_EQ(s.band_reloading[i] != 0, expected) << "t = " << time << " s, " << after_crossing << " in after the crossing";
  }
}

// Rests between strokes: the drum goes 0 -> 1 in (1 s), stops 0.6 s, comes back to 0 (1 s), pauses
// 0.05 s (with the slow ends of its strokes, still shorter than min_rest_s 0.2 s: not a rest), goes to -0.5 in (0.5 s) and stops for 1.5 s.
// The stops of at least 0.2 s within rest_band_in (0.01 in, here with a 0.004 in encoder flicker)
// are rests and the after_stop regime, although the drum moves again after the first; the short
// pause is not; the final rest is the last rest; the start of the next stroke, still inside
// rest_band_in, is not rest. Fails if only the final rest counts, or if a stop (the final one
// included) is not trimmed to the samples where the drum is still.
TEST(DiagnoseData, StopsBetweenStrokesAreRestsLikeTheFinalOne) {
  BrfdTest t;
  t.dt_s = 1.0 / 1000.0;
  struct Leg {
    double duration_s, from_in, to_in;
  };
  const std::vector<Leg> legs{{1.0, 0.0, 1.0}, {0.6, 1.0, 1.0}, {1.0, 1.0, 0.0}, {0.05, 0.0, 0.0}, {0.5, 0.0, -0.5}, {1.5, -0.5, -0.5}};
  double time = 0.0;
  for (const Leg& leg : legs) {
    const int steps = static_cast<int>(std::lround(leg.duration_s / t.dt_s));
    for (int k = 0; k < steps; ++k) {
      const double u = static_cast<double>(k) / steps;  // smooth stroke: half a cosine
      const double d = leg.from_in + (leg.to_in - leg.from_in) * 0.5 * (1.0 - std::cos(M_PI * u));
      const double v = (leg.to_in - leg.from_in) * 0.5 * M_PI / leg.duration_s * std::sin(M_PI * u);
      t.time_s.push_back(time);
      t.drum_disp_in.push_back(d + 0.004 * ((t.time_s.size() % 3) - 1.0));
      t.drum_vel_in_per_s.push_back(v);
      t.force_kip.push_back(v >= 0.0 ? 1.0 : -1.0);
      time += t.dt_s;
    }
  }
  const Segmentation s = segment_record(t);
  ASSERT_EQ(s.rests.size(), 2u);
  // The stop at 1 in: 1.0-1.6 s, extended by the slow ends of the strokes around it.
  EXPECT_NEAR(s.rests[0].begin * t.dt_s, 1.0, 0.12);
  EXPECT_NEAR(s.rests[0].end * t.dt_s, 1.6, 0.12);
  // The final rest: from where the excitation ends, trimmed like the stops to where the drum is
  // still (the slow end of the last stroke is motion).
  const double still = SegmentationOptions{}.rest_speed_in_per_s;
  EXPECT_GT(s.rests[1].begin, s.rest_begin);
  EXPECT_LE(std::abs(t.drum_vel_in_per_s[s.rests[1].begin]), still);
  EXPECT_GT(std::abs(t.drum_vel_in_per_s[s.rests[1].begin - 1]), still);
  EXPECT_EQ(s.rests[1].end, t.size());
  auto at = [&](double time_s) { return s.regime[static_cast<std::size_t>(std::lround(time_s / t.dt_s))]; };
  EXPECT_EQ(at(1.3), Regime::after_stop);  // resting between strokes
  EXPECT_EQ(at(1.8), Regime::reversal);    // moving again: right after the reversal
  // 0.03 s into the next stroke the drum is still within 0.01 in of the stop but moves at 0.15 in/s:
  // motion, not rest.
  EXPECT_EQ(at(1.63), Regime::reversal);
  EXPECT_NE(at(2.625), Regime::after_stop);  // the 0.05 s pause
  EXPECT_EQ(at(4.0), Regime::after_stop);  // the final rest
  // A 0.5 kip step in the residual during the stop between strokes sits in after_stop.
  std::vector<double> r(t.size(), 0.0);
  for (std::size_t i = s.rests[0].begin + 100; i + 100 < s.rests[0].end; ++i) r[i] = 0.5;
  const RegimeEnergy e = localize(r, s, t.dt_s, SegmentationOptions{});
  EXPECT_GT(e.energy[static_cast<int>(Regime::after_stop)] / e.total(), 0.9);  // the rest: the step's edges, chatter
}

TEST(DiagnoseData, LocalizeAttributesEnergyToRegimesAndChatter) {
  const BrfdTest t = make_record(synthetic_base());
  const Segmentation s = segment_record(t);
  const SegmentationOptions o;
  // A constant offset after the drum stops: all of it in after_stop.
  std::vector<double> r(t.size(), 0.0);
  for (std::size_t i = s.rest_begin + 200; i < t.size(); ++i) r[i] = 0.5;
  RegimeEnergy e = localize(r, s, t.dt_s, o);
  EXPECT_GT(e.energy[static_cast<int>(Regime::after_stop)] / e.total(), 0.97);
  // A 40 Hz oscillation: chatter.
  for (std::size_t i = 0; i < t.size(); ++i) r[i] = 0.3 * std::sin(2 * M_PI * 40.0 * t.time_s[i]);
  e = localize(r, s, t.dt_s, o);
  EXPECT_GT(e.energy[static_cast<int>(Regime::chatter)] / e.total(), 0.95);
}

TEST(DiagnoseData, ReadsARecordedPhysicalRun) {
  const std::string dir = temp_dir("diagnose_data_csv");
  {
    std::ofstream f(dir + "/physical.csv");
    f.precision(17);
    f << "step,sim_time_s,target_in,compensated_in,command_in,measured_in,force_kip,actuator1_in,actuator2_in,"
         "actuator1_force_lb,actuator2_force_lb,ats_a0,ats_a1_s,ats_a2_s2,frame_sequence,acked_command_sequence,"
         "command_sequence\n";
    for (int i = 0; i < 1024; ++i) {
      const double t = i / 1024.0;
      f << i << ',' << t << ",0,0,0," << std::sin(M_PI * t) << ',' << 2 * std::cos(M_PI * t) << ",0.655,0.8559,30,40,1,0,0,"
        << i << ',' << i << ',' << i << '\n';
    }
  }
  const BrfdTest t = read_measured_record(dir);  // the run folder
  ASSERT_EQ(t.size(), 1024u);
  EXPECT_NEAR(t.dt_s, 1.0 / 1024.0, 1e-12);
  EXPECT_TRUE(t.has_actuator_positions);
  EXPECT_TRUE(t.velocity_derived);
  EXPECT_NEAR(t.drum_vel_in_per_s[512], M_PI * std::cos(M_PI * 0.5), 0.01);
  EXPECT_NEAR(t.force_kip[10], 2 * std::cos(M_PI * 10 / 1024.0), 1e-9);
  EXPECT_EQ(expand_measured_paths({dir}).size(), 1u);

  // A bad value names the row and the column.
  {
    std::ofstream f(dir + "/bad.csv");
    f << "time_s,drum_disp_in,measured_force_kip\n";
    for (int i = 0; i < 200; ++i) f << i / 1024.0 << ',' << 0.001 * i << ',' << (i == 150 ? "nan" : "1.0") << '\n';
  }
  try {
    read_measured_record(dir + "/bad.csv");
    FAIL() << "expected BrfdDataError";
  } catch (const BrfdDataError& e) {
    EXPECT_NE(std::string(e.what()).find("row 151, column 2 (measured_force_kip)"), std::string::npos) << e.what();
  }
  {
    std::ofstream f(dir + "/nocols.csv");
    f << "a,b\n1,2\n";
  }
  EXPECT_THROW(read_measured_record(dir + "/nocols.csv"), BrfdDataError);
}

// The level a rest starts from (levels_at_stops), on a record that strokes 0 -> 1 in (1 s), stops
// 1 s, strokes back (1 s) and rests 1.5 s. The residual is 0.8 kip while the drum moves; at the stop
// between strokes it is a constant 0.3 kip (an offset carried into the rest: no change at rest);
// over the final rest it creeps linearly from 0.3 kip by 0.2 kip/s (a change at rest). Closed forms:
// over the first half-width of the moving average after each stop the level is NaN (the average
// still holds the stroke); after it, the change l - c is 0 at the first stop, and at the final rest
// equals the creep since the middle of the level's window, r(i) - r(settled + (w - 1)/2), because a
// centred average leaves a linear ramp unchanged. Outside rests the level is 0. Fails if the level
// is taken from the stop itself (the stroke's 0.8 kip then shows as a change at rest) or if the
// NaN half-width is dropped.
TEST(DiagnoseData, LevelAtAStopIsTakenOnceTheAverageHasLeftTheStroke) {
  BrfdTest t;
  t.dt_s = 1.0 / 1000.0;
  struct Leg {
    double duration_s, from_in, to_in;
  };
  const std::vector<Leg> legs{{1.0, 0.0, 1.0}, {1.0, 1.0, 1.0}, {1.0, 1.0, 0.0}, {1.5, 0.0, 0.0}};
  double time = 0.0;
  for (const Leg& leg : legs) {
    const int steps = static_cast<int>(std::lround(leg.duration_s / t.dt_s));
    for (int k = 0; k < steps; ++k) {
      const double u = static_cast<double>(k) / steps;
      t.time_s.push_back(time);
      t.drum_disp_in.push_back(leg.from_in + (leg.to_in - leg.from_in) * 0.5 * (1.0 - std::cos(M_PI * u)));
      t.drum_vel_in_per_s.push_back((leg.to_in - leg.from_in) * 0.5 * M_PI / leg.duration_s * std::sin(M_PI * u));
      t.force_kip.push_back(0.0);
      time += t.dt_s;
    }
  }
  const SegmentationOptions so;
  const Segmentation s = segment_record(t);
  ASSERT_EQ(s.rests.size(), 2u);
  const Segmentation::Rest stop = s.rests[0], last = s.rests[1];
  const double creep_kip_per_s = 0.2;
  std::vector<double> r(t.size(), 0.8);
  for (std::size_t i = stop.begin; i < stop.end; ++i) r[i] = 0.3;
  for (std::size_t i = last.begin; i < last.end; ++i) r[i] = 0.3 + creep_kip_per_s * (i - last.begin) * t.dt_s;
  const std::vector<double> l = low_frequency_part(r, t.dt_s, so);
  const std::vector<double> c = levels_at_stops(l, s, t.dt_s, so);
  ASSERT_EQ(c.size(), t.size());
  const std::size_t half = static_cast<std::size_t>(std::lround(0.5 * so.chatter_window_s / t.dt_s));
  const std::size_t w = static_cast<std::size_t>(kStopLevelS / t.dt_s);
  // The stroke's end is still in the average over the first half-width after the stop.
  EXPECT_GT(l[stop.begin] - 0.3, 0.2);
  std::size_t in_rest = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const bool resting = (i >= stop.begin && i < stop.end) || i >= last.begin;
    if (!resting) {
      EXPECT_EQ(c[i], 0.0) << "sample " << i << " is not at rest";
      continue;
    }
    const std::size_t begin = i >= last.begin ? last.begin : stop.begin;
    if (i < begin + half) {
      EXPECT_TRUE(std::isnan(c[i])) << "sample " << i - begin << " of a rest, inside the average's half-width";
      continue;
    }
    ASSERT_FALSE(std::isnan(c[i])) << "sample " << i - begin << " of a rest";
    ++in_rest;
    if (i < stop.end) {
      if (i + half < stop.end) {
        EXPECT_NEAR(l[i] - c[i], 0.0, 1e-12) << "a held offset is no change at rest (sample " << i - begin << ")";
      }
    } else if (i + half < t.size()) {
      const double expected = r[i] - r[begin + half + (w - 1) / 2] - (w % 2 == 0 ? 0.5 * creep_kip_per_s * t.dt_s : 0.0);
      EXPECT_NEAR(l[i] - c[i], expected, 1e-9) << "the creep since the level's window (sample " << i - begin << ")";
    }
  }
  EXPECT_GT(in_rest, 1500u);
}

}  // namespace
}  // namespace damper
