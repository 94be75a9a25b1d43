// Control laws in the hybrid step loop (in-process substructure, the four shipped records):
// passive_off is today's passive run number for number; Lyapunov dissipates at least what
// passive_off does on each record and its switching rule holds at every step; clipped-optimal
// lowers J1 below both passive laws on at least 3 of 4 records (3-story); the electric
// actuators never leave their stroke nor exceed their velocity limit (from the time histories).
#include "control/friction_inverse.h"
#include "control/motion_fit.h"
#include "damper/model/brfd_config.h"
#include "run_process.h"
#include "server/run/hybrid_run.h"
#include "test_paths.h"

#include "structure/ground_motion.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

namespace {

using server::RunConfig;

const std::vector<std::string> kRecords{"ImperialValley1940_ElCentroArray9_180_NS_RSN6.AT2",
                                        "Kocaeli1999_Duzce_270_RSN1158.AT2",
                                        "Northridge1994_RinaldiReceivingSta_228_RSN1063.AT2",
                                        "Northridge1994_SylmarConverterSta_142_RSN1084.AT2"};

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  int col(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return static_cast<int>(i);
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
};

Csv read_csv(const std::string& path) {
  Csv c;
  std::ifstream f(path);
  std::string line, cell;
  std::getline(f, line);
  std::stringstream h(line);
  while (std::getline(h, cell, ',')) c.header.push_back(cell);
  while (std::getline(f, line)) {
    std::vector<double> row;
    std::stringstream s(line);
    while (std::getline(s, cell, ',')) row.push_back(std::stod(cell));
    c.rows.push_back(row);
  }
  return c;
}

RunConfig config(const std::string& file, const std::string& record, const std::string& law, double duration_s,
                 const std::string& out) {
  RunConfig c = server::load_run_config(test_paths::source_dir() + "/configs/" + file);
  c.record.path = test_paths::source_dir() + "/records/" + record;
  // At most the record's own length (Rinaldi is 19.9 s): a longer duration is refused (issue 14).
  c.record.duration_s = std::min(duration_s, structure::read_ground_motion(c.record.path, 1.0).duration_s());
  c.transport.kind = "in_process";
  c.output.dir = out;
  if (law.empty())
    c.control = control::ControlConfig{};
  else
    c.control.law = control::law_from_string(law);
  return c;
}

server::RunSummary run(const RunConfig& c) {
  server::InProcessSubstructure sub(c.damper_model);
  server::RunSummary s = server::run_hybrid(c, sub, "test");
  EXPECT_EQ(s.status, "ok") << s.error;
  return s;
}

/// Stroke and velocity limits of every damper's actuators over a whole run (time history).
void expect_actuators_within_limits(const RunConfig& c, const std::string& what) {
  const Csv h = read_csv(c.output.dir + "/time_history.csv");
  const damper::ElectricActuatorParams& a = c.damper_model.electric_actuators;
  for (std::size_t k = 1; k <= c.building.dampers.size(); ++k) {
    for (int j = 1; j <= 2; ++j) {
      const int col = h.col("damper" + std::to_string(k) + "_actuator" + std::to_string(j) + "_in");
      double worst_rate = 0.0, lo = 1e9, hi = -1e9;
      for (std::size_t r = 0; r < h.rows.size(); ++r) {
        const double x = h.rows[r][col];
        lo = std::min(lo, x);
        hi = std::max(hi, x);
        if (r > 0) worst_rate = std::max(worst_rate, std::abs(x - h.rows[r - 1][col]) / c.dt_s);
      }
      EXPECT_GE(lo, a.min_in) << what;
      EXPECT_LE(hi, a.max_in) << what;
      EXPECT_LE(worst_rate, a.velocity_limit_in_per_s * (1 + 1e-6)) << what;
    }
  }
}

/// The Lyapunov law's rule (control/controller.h) recomputed from a time history: the targets of
/// row r come from the force of row r-1, the drum velocity v = (d_r - d_{r-1})/dt and the
/// quadratic fit of the drum displacement over the window ending at row r. Release (least
/// friction) when F·v < 0, or when the drum decelerates (v̂ â < 0) with |v̂| < v_s + lead T_rel |â|;
/// otherwise the most friction. Returns the friction wanted; *ahead says whether the release is
/// the one ahead of a predicted reversal.
double lyapunov_friction(const Csv& h, std::size_t r, int drum, int force, const RunConfig& c,
                         const control::FrictionInverse& inv, const control::QuadraticMotionFit& fit, bool* ahead) {
  const double d = h.rows[r][drum], v = (d - h.rows[r - 1][drum]) / c.dt_s;
  const control::FrictionRange range = inv.range(v, d);
  bool release = h.rows[r - 1][force] * v < 0.0;
  *ahead = false;
  const std::size_t n = static_cast<std::size_t>(fit.samples());
  if (!release && c.control.reversal_lead > 0.0 && r >= n) {
    double vh = 0.0, ah = 0.0;
    fit.estimate([&](int i) { return h.rows[r + 1 - n + static_cast<std::size_t>(i)][drum]; }, vh, ah);
    const double lead_s = c.control.reversal_lead * inv.release_time_s(v, d);
    if (vh * ah < 0.0 && std::abs(vh) < inv.stribeck_velocity_in_per_s() + lead_s * std::abs(ah)) release = *ahead = true;
  }
  return release ? range.min_kip : range.max_kip;
}

control::QuadraticMotionFit motion_fit_of(const RunConfig& c) {
  return control::QuadraticMotionFit(std::max(3, static_cast<int>(std::lround(c.control.motion_window_s / c.dt_s))), c.dt_s);
}

TEST(ControlLoop, PassiveOffReproducesTheUncontrolledRunNumberForNumber) {
  for (const char* file : {"three-story-controlled.yaml", "ten-story-controlled.yaml"}) {
    const RunConfig plain = config(file, kRecords[0], "", 8.0, test_support::fresh_temp_dir("plain"));
    const RunConfig off = config(file, kRecords[0], "passive_off", 8.0, test_support::fresh_temp_dir("off"));
    const server::RunSummary a = run(plain), b = run(off);
    const Csv ha = read_csv(plain.output.dir + "/time_history.csv"), hb = read_csv(off.output.dir + "/time_history.csv");
    ASSERT_EQ(ha.rows.size(), hb.rows.size());
    ASSERT_GT(hb.header.size(), ha.header.size());  // + targets, positions, desired Fc
    for (std::size_t r = 0; r < ha.rows.size(); ++r)
      for (std::size_t j = 0; j < ha.header.size(); ++j) ASSERT_EQ(ha.rows[r][j], hb.rows[r][j]) << file << " row " << r;
    EXPECT_EQ(a.damper_energy_kip_in, b.damper_energy_kip_in);
    EXPECT_EQ(a.peak_drift_in, b.peak_drift_in);
    EXPECT_EQ(b.actuator_travel_in.sum(), 0.0);
  }
}

TEST(ControlLoop, LyapunovDissipatesAtLeastPassiveOffOnEachRecordAndFollowsItsSwitchingRule) {
  // Ten-story, three semi-active dampers, 20 s of each record (docs/control.md has the
  // three-story building and the band-brake model too).
  for (const std::string& rec : kRecords) {
    const RunConfig off = config("ten-story-controlled.yaml", rec, "passive_off", 20.0, test_support::fresh_temp_dir("lo"));
    const RunConfig lya = config("ten-story-controlled.yaml", rec, "lyapunov", 20.0, test_support::fresh_temp_dir("ly"));
    ASSERT_EQ(lya.control.reversal_lead, 1.0);  // the shipped default
    const server::RunSummary a = run(off), b = run(lya);
    const double ea = a.damper_energy_kip_in.sum(), eb = b.damper_energy_kip_in.sum();
    std::cout << rec << ": damper energy passive_off " << ea << " kip-in (" << 100 * ea / a.input_energy_kip_in
              << " % of input), lyapunov " << eb << " kip-in (" << 100 * eb / b.input_energy_kip_in << " % of input)\n";
    // The issue: at least passive_off's dissipated energy on each record. Measured (20 s):
    // +2.8 % El Centro, +19 % Duzce, +20 % Rinaldi, +28 % Sylmar (without the release ahead
    // of the reversal El Centro was -2.4 %: the clamped band gave its stored energy back).
    EXPECT_GE(eb, ea) << rec;
    EXPECT_GT(eb / b.input_energy_kip_in, ea / a.input_energy_kip_in) << rec;
    expect_actuators_within_limits(lya, rec + " lyapunov");

    // Switching rule, step by step (lyapunov_friction above), at every damper-step.
    const Csv h = read_csv(lya.output.dir + "/time_history.csv");
    const control::FrictionInverse inv(lya.damper_model, lya.control.min_kinetic_friction_kip);
    const control::QuadraticMotionFit fit = motion_fit_of(lya);
    const double max_move = lya.damper_model.electric_actuators.velocity_limit_in_per_s * lya.dt_s;
    long checked = 0, unsaturated = 0, ahead = 0, clamped = 0;
    for (std::size_t k = 1; k <= 3; ++k) {
      const std::string d = "damper" + std::to_string(k);
      const int drum = h.col(d + "_drum_disp_in"), force = h.col(d + "_force_kip"), fc = h.col(d + "_desired_fc_kip");
      const int x1 = h.col(d + "_actuator1_in"), x2 = h.col(d + "_actuator2_in");
      for (std::size_t r = 2; r < h.rows.size(); ++r) {
        bool early = false;
        const double want = lyapunov_friction(h, r, drum, force, lya, inv, fit, &early);
        const double v = (h.rows[r][drum] - h.rows[r - 1][drum]) / lya.dt_s;
        ASSERT_NEAR(h.rows[r][fc], want, 1e-9) << rec << " " << d << " row " << r;
        ++checked;
        ahead += early;
        clamped += want == inv.range(v, h.rows[r][drum]).max_kip;
        // Where the actuators are not at their velocity limit, the friction they give (Eq. 4 at
        // the positions reached) moves toward the commanded level, never away from it.
        const double m1 = std::abs(h.rows[r][x1] - h.rows[r - 1][x1]), m2 = std::abs(h.rows[r][x2] - h.rows[r - 1][x2]);
        if (m1 < 0.999 * max_move && m2 < 0.999 * max_move) {
          ++unsaturated;
          const double before = inv.kinetic_friction_kip(h.rows[r - 1][x1], h.rows[r - 1][x2], v);
          const double after = inv.kinetic_friction_kip(h.rows[r][x1], h.rows[r][x2], v);
          ASSERT_LE(std::abs(after - want), std::abs(before - want) + 1e-9) << rec << " " << d << " row " << r;
        }
      }
    }
    std::cout << "  switching rule holds at all " << checked << " damper-steps (" << clamped << " clamped, " << ahead
              << " released ahead of a reversal); friction moves toward it at all " << unsaturated
              << " steps off the velocity limit\n";
    // All three branches are taken.
    EXPECT_GT(ahead, 100) << rec;
    EXPECT_GT(clamped, checked / 10) << rec;
    EXPECT_LT(clamped + ahead, checked - checked / 10) << rec;
  }
}

TEST(ControlLoop, ClippedOptimalLowersPeakDriftOnTheThreeStoryBuilding) {
  int below_both = 0, below_off = 0, below_worse = 0;
  for (const std::string& rec : kRecords) {
    std::map<std::string, server::RunSummary> s;
    for (const char* law : {"passive_off", "passive_on", "clipped_optimal"}) {
      const RunConfig c = config("three-story-controlled.yaml", rec, law, 20.0, test_support::fresh_temp_dir(law));
      s[law] = run(c);
      expect_actuators_within_limits(c, rec + " " + law);
    }
    const double off = s["passive_off"].criteria.j1, on = s["passive_on"].criteria.j1, co = s["clipped_optimal"].criteria.j1;
    std::cout << rec << ": J1 passive_off " << off << ", passive_on " << on << ", clipped_optimal " << co << "\n";
    below_both += co < off && co < on;
    below_off += co < off;
    below_worse += co < std::max(off, on);
  }
  std::cout << "clipped_optimal J1 below both passive laws on " << below_both << " of 4 records, below passive_off on "
            << below_off << ", below the worse passive law on " << below_worse << "\n";
  // The issue asks for "below both on >= 3 of 4". Measured with the band-brake damper and
  // force weight 0.01 (20 s): 3 of 4 (Duzce, Rinaldi, Sylmar); on El Centro passive_on is best
  // and clipped-optimal is 1.6 % above passive_off (docs/control.md, with the semi-active model's
  // 2 of 4).
  EXPECT_GE(below_both, 3);
  EXPECT_GE(below_off, 3);
}

}  // namespace

namespace {

// The band-brake model (the runs' default damper, damper/model/band_brake_model.h) under
// control: its actuators set the slack-end tension (B2); the inverse of (B1)-(B3) gives the
// targets (control/friction_inverse.h).
TEST(ControlLoop, BandBrakeModelPassiveOffIsThePlainRunAndLyapunovSwitchesAtEveryStep) {
  const damper::BrfdParams bb = damper::load_brfd_params(test_paths::source_dir() + "/configs/brfd-band-brake.yaml");
  ASSERT_EQ(bb.kind, damper::DamperKind::band_brake);
  auto with_band_brake = [&](RunConfig c) {
    c.damper_model = bb;
    return c;
  };
  const RunConfig plain = with_band_brake(config("three-story-controlled.yaml", kRecords[3], "", 8.0, test_support::fresh_temp_dir("bbp")));
  const RunConfig off =
      with_band_brake(config("three-story-controlled.yaml", kRecords[3], "passive_off", 8.0, test_support::fresh_temp_dir("bbo")));
  const RunConfig lya =
      with_band_brake(config("three-story-controlled.yaml", kRecords[3], "lyapunov", 8.0, test_support::fresh_temp_dir("bbl")));
  const server::RunSummary a = run(plain), b = run(off), l = run(lya);
  const Csv ha = read_csv(plain.output.dir + "/time_history.csv"), hb = read_csv(off.output.dir + "/time_history.csv");
  ASSERT_EQ(ha.rows.size(), hb.rows.size());
  for (std::size_t r = 0; r < ha.rows.size(); ++r)
    for (std::size_t j = 0; j < ha.header.size(); ++j) ASSERT_EQ(ha.rows[r][j], hb.rows[r][j]) << "row " << r;
  EXPECT_EQ(a.damper_energy_kip_in, b.damper_energy_kip_in);
  expect_actuators_within_limits(lya, "band brake lyapunov");
  EXPECT_GT(l.actuator_travel_in.sum(), 0.1);

  const Csv h = read_csv(lya.output.dir + "/time_history.csv");
  const control::FrictionInverse inv(bb, lya.control.min_kinetic_friction_kip);
  const control::QuadraticMotionFit fit = motion_fit_of(lya);
  EXPECT_EQ(inv.stribeck_velocity_in_per_s(), 0.0);  // the capstan friction has no speed term
  const int drum = h.col("damper1_drum_disp_in"), force = h.col("damper1_force_kip"), fc = h.col("damper1_desired_fc_kip");
  long on = 0, ahead = 0;
  for (std::size_t r = 2; r < h.rows.size(); ++r) {
    bool early = false;
    const double want = lyapunov_friction(h, r, drum, force, lya, inv, fit, &early);
    ASSERT_NEAR(h.rows[r][fc], want, 1e-9) << "row " << r;
    const double d = h.rows[r][drum], v = (d - h.rows[r - 1][drum]) / lya.dt_s;
    on += want == inv.range(v, d).max_kip;
    ahead += early;
  }
  // Every branch is taken (the band's stored force opposes the motion after each reversal; the
  // drum decelerates toward each reversal).
  EXPECT_GT(on, 100);
  EXPECT_GT(ahead, 100);
  EXPECT_LT(on + ahead, static_cast<long>(h.rows.size()) - 100);
}

}  // namespace
