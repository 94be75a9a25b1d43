#pragma once
// Synthetic "measured" BRFD records for the diagnose tests: the model itself (optionally with a
// hidden effect) driven like the paper's semi-active validation tests -- a 0.5 Hz, 1 in drum
// sinusoid ramped up and down, electric actuator motions (harmonic retract/extend, 1 s) on some
// drum strokes, then the drum at rest -- with white noise on the force. Written as 8-column
// semi-active JSON files so that they go through the real reader.
#include "damper/data/brfd_data.h"
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

// Base model of the synthetic tests: LuGre values close to those identified on the real tests,
// Tables 1-2 of the paper for Eq. (4).
inline damper::BrfdParams synthetic_base() {
  damper::BrfdParams p;
  p.kind = damper::DamperKind::semiactive;
  p.lugre.sigma0_kip_per_in = 30.0;
  p.lugre.sigma1_kip_s_per_in = 0.01;
  p.lugre.sigma2_kip_s_per_in = 0.1;
  p.lugre.fc_fwd_kip = 3.0;
  p.lugre.fc_bwd_kip = 2.2;
  p.lugre.fs_fwd_kip = 4.0;
  p.lugre.fs_bwd_kip = 3.0;
  p.lugre.vs_in_per_s = 0.6;
  p.semiactive.actuator1_initial_in = 0.655;
  p.semiactive.actuator2_initial_in = 0.8559;
  return p;
}

// Raised-cosine ramp 0 -> 1 over [0, 1].
inline double ramp(double s) { return s <= 0.0 ? 0.0 : s >= 1.0 ? 1.0 : 0.5 - 0.5 * std::cos(M_PI * s); }

// Drum displacement/velocity and actuator positions at time t.
inline damper::DamperInput synthetic_input(double t, const SyntheticOptions& o, const damper::BrfdParams& p) {
  damper::DamperInput in;
  const double w = M_PI;  // 0.5 Hz
  double env = 0.0, denv = 0.0;
  const double tr = 2.0, T = o.motion_s;
  if (t < T) {
    if (t < tr) {
      env = ramp(t / tr);
      denv = 0.5 * M_PI / tr * std::sin(M_PI * t / tr);
    } else if (t > T - tr) {
      env = ramp((T - t) / tr);
      denv = -0.5 * M_PI / tr * std::sin(M_PI * (T - t) / tr);
    } else {
      env = 1.0;
    }
  }
  in.drum_disp_in = o.amplitude_in * env * std::sin(w * t);
  in.drum_vel_in_per_s = o.amplitude_in * (denv * std::sin(w * t) + env * w * std::cos(w * t));
  // Actuators: x = x' - A sin(2 pi (t - t0)) over one second: retract, then extend.
  auto pulse = [t](double t0, double a) { return t >= t0 && t < t0 + 1.0 ? -a * std::sin(2.0 * M_PI * (t - t0)) : 0.0; };
  in.actuator1_in = p.semiactive.actuator1_initial_in + pulse(3.5, 0.03) + pulse(7.5, 0.015);  // forward strokes
  in.actuator2_in = p.semiactive.actuator2_initial_in + pulse(6.5, 0.03) + pulse(7.5, 0.015);  // backward, forward
  return in;
}

// Simulates `truth` on the synthetic drive and adds noise.
inline damper::BrfdTest make_record(const damper::BrfdParams& truth, const SyntheticOptions& o = {}) {
  damper::BrfdTest t;
  t.dt_s = 1.0 / o.rate_hz;
  const std::size_t n = static_cast<std::size_t>(std::lround((o.motion_s + o.rest_s) * o.rate_hz));
  damper::BrfdModel model(truth);
  std::mt19937 rng(o.seed);
  std::normal_distribution<double> noise(0.0, o.noise_kip);
  t.has_actuator_positions = true;
  for (std::size_t i = 0; i < n; ++i) {
    const double time = static_cast<double>(i) * t.dt_s;
    const damper::DamperInput in = synthetic_input(time, o, truth);
    const double f = i == 0 ? model.force_kip(model.bristle_in(), in) : model.step(in, t.dt_s);
    t.time_s.push_back(time);
    t.drum_disp_in.push_back(in.drum_disp_in);
    t.drum_vel_in_per_s.push_back(in.drum_vel_in_per_s);
    t.force_kip.push_back(f + noise(rng));
    t.actuator1_in.push_back(in.actuator1_in);
    t.actuator2_in.push_back(in.actuator2_in);
    t.actuator1_force_lb.push_back(0.0);
    t.actuator2_force_lb.push_back(0.0);
  }
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
