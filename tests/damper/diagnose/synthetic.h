#pragma once
// Synthetic "measured" BRFD records for the diagnose tests: the model itself (optionally with a
// hidden effect) driven like the paper's semi-active validation tests -- a 0.5 Hz, 1 in drum
// sinusoid ramped up and down, electric actuator motions (harmonic retract/extend, 1 s) on some
// drum strokes, then the drum at rest (the benchmark's first drive, diagnose_bench.h) -- with
// white noise on the force. Written as 8-column
// semi-active JSON files so that they go through the real reader.
#include "damper/data/brfd_data.h"
#include "damper/data/replay.h"
#include "damper/diagnose/diagnose_bench.h"
#include "damper/model/brfd_model.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>

namespace diagnose_test {

struct SyntheticOptions {
  double rate_hz = 512.0;     // sample rate
  double motion_s = 12.0;     // drum motion: 0.5 Hz sinusoid, 2 s ramps up and down
  double rest_s = 2.0;        // drum at rest after the motion
  double amplitude_in = 1.0;
  double noise_kip = 0.05;    // std of the white noise added to the force
  unsigned seed = 11;
};

// Base model of the synthetic tests: the benchmark's (LuGre values close to those identified on
// the real tests, Tables 1-2 of the paper for Eq. (4)).
inline damper::BrfdParams synthetic_base() { return damper::bench_base_model(); }

// Drum displacement/velocity and actuator positions at time t: the first drive of the
// benchmark (damper::bench_drive_set()) with the amplitude and motion length of `o`.
inline damper::DamperInput synthetic_input(double t, const SyntheticOptions& o, const damper::BrfdParams& p) {
  damper::BenchDrive drive = damper::bench_drive_set()[0];
  drive.amplitude_in = o.amplitude_in;
  return damper::bench_drive_input(t, drive, p, o.motion_s);
}

// Simulates `truth` on the synthetic drive (bristle state from 0) and adds noise.
inline damper::BrfdTest make_record(const damper::BrfdParams& truth, const SyntheticOptions& o = {}) {
  damper::BenchDrive drive = damper::bench_drive_set()[0];
  drive.amplitude_in = o.amplitude_in;
  damper::BrfdTest t = damper::bench_drive(drive, truth, o.rate_hz, o.motion_s, o.rest_s);
  std::mt19937 rng(o.seed);
  std::normal_distribution<double> noise(0.0, o.noise_kip);
  t.force_kip = damper::replay_force_kip(truth, t, 0, t.size(), damper::ReplayOptions{false});
  for (double& f : t.force_kip) f += noise(rng);
  return t;
}

// Writes an 8-column semi-active JSON file (velocity column in in/s).
inline void write_json(const damper::BrfdTest& t, const std::string& path) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f.precision(17);
  f << "{\"dt\": " << t.dt_s << ", \"sampling freq\": " << 1.0 / t.dt_s << ", \"data\": [";
  char buf[512];
  for (std::size_t i = 0; i < t.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%s[%.17g, %.17g, %.17g, %.17g, %.17g, %.17g, 0, 0]", i ? ", " : "", t.time_s[i],
                  t.drum_disp_in[i], t.force_kip[i], t.drum_vel_in_per_s[i], t.actuator1_in[i], t.actuator2_in[i]);
    f << buf;
  }
  f << "]}\n";
}

}  // namespace diagnose_test
