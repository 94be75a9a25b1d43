#include "damper/diagnose/diagnose_bench.h"

#include "common/number_format.h"
#include "damper/data/replay.h"
#include "damper/model/brfd_config.h"
#include "damper/diagnose/diagnose.h"
#include "damper/diagnose/diagnose_fit.h"
#include "damper/model/effects.h"
#include "damper/synthetic/hidden_shapes.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <random>
#include <sstream>
#include <unistd.h>
#include <algorithm>
#include <functional>

namespace damper {

namespace {

using common::format_fixed;

double raised_ramp(double s) { return s <= 0.0 ? 0.0 : s >= 1.0 ? 1.0 : 0.5 - 0.5 * std::cos(M_PI * s); }

constexpr double kMotionS = 12.0, kRestS = 2.0;

// Force of a model on the inputs of `t`, bristle state from 0 (as a test starting unloaded).
std::vector<double> generate(const BrfdParams& p, const BrfdTest& t) {
  return replay_force_kip(p, t, 0, t.size(), ReplayOptions{false});
}

BenchCase library_case(const std::string& effect, const std::string& strength, std::vector<double> theta) {
  BenchCase c;
  c.name = effect + "/" + strength;
  c.family = effect;
  c.truth = [effect, theta](const BrfdTest& t, const BrfdParams& base) {
    BrfdParams p = for_record(base, t);
    effect_spec(effect).set(p.effects, theta);
    return generate(p, t);
  };
  return c;
}

// Own shapes (not library formulas).
// Backlash as a weight on the force over the drum travel s since each reversal: the old band
// unloads linearly over 0.01 in, no force over the gap, then a raised-cosine re-engagement.
BenchCase own_backlash(const std::string& strength, double gap_in, double ramp_in) {
  BenchCase c;
  c.name = "own:backlash_weight/" + strength;
  c.family = "backlash";
  c.truth = [gap_in, ramp_in](const BrfdTest& t, const BrfdParams& base) {
    std::vector<double> f = generate(for_record(base, t), t);
    double travel = 0.0;
    int dir = 0;
    for (std::size_t i = 1; i < t.size(); ++i) {
      const double v = t.drum_vel_in_per_s[i];
      const int d = v > 1e-9 ? 1 : v < -1e-9 ? -1 : 0;
      if (d != 0 && d != dir) {
        dir = d;
        travel = 0.0;
      }
      travel += std::abs(t.drum_disp_in[i] - t.drum_disp_in[i - 1]);
      double w = 1.0;
      if (travel < 0.01) w = 1.0 - travel / 0.01;
      else if (travel < gap_in) w = 0.0;
      else w = raised_ramp((travel - gap_in) / ramp_in);
      if (travel < gap_in + ramp_in) f[i] *= w;
    }
    return f;
  };
  return c;
}

// A pure transport delay of the electric actuators.
BenchCase own_delay(const std::string& strength, double delay_s) {
  BenchCase c;
  c.name = "own:actuator_delay/" + strength;
  c.family = "actuator_lag";
  c.truth = [delay_s](const BrfdTest& t, const BrfdParams& base) {
    BrfdTest d = t;
    const std::size_t k = static_cast<std::size_t>(std::lround(delay_s / t.dt_s));
    for (std::size_t i = 0; i < t.size(); ++i) {
      d.actuator1_in[i] = i >= k ? t.actuator1_in[i - k] : t.actuator1_in[0];
      d.actuator2_in[i] = i >= k ? t.actuator2_in[i - k] : t.actuator2_in[0];
    }
    return generate(for_record(base, t), d);
  };
  return c;
}

// The base model with its friction levels b, Fs scaled at every sample by
// level(i, friction work so far in kip in), the bristle state carried across samples.
std::vector<double> generate_with_level_scale(const BrfdParams& p0, const BrfdTest& t,
                                              const std::function<double(std::size_t, double)>& level) {
  std::vector<double> f(t.size());
  double z = 0.0, work = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    BrfdParams p = p0;
    const double k = level(i, work);
    p.lugre.fc_fwd_kip *= k;
    p.lugre.fc_bwd_kip *= k;
    p.lugre.fs_fwd_kip *= k;
    p.lugre.fs_bwd_kip *= k;
    BrfdModel m(p);
    m.set_bristle_in(z);
    const DamperInput in{t.drum_disp_in[i], t.drum_vel_in_per_s[i], t.actuator1_in[i], t.actuator2_in[i]};
    f[i] = i == 0 ? m.force_kip(z, in) : m.step(in, t.dt_s);
    z = m.bristle_in();
    work += std::abs(f[i] * t.drum_vel_in_per_s[i]) * t.dt_s;
  }
  return f;
}

// Friction levels b, Fs x (1 + a d^2): even in the drum displacement.
BenchCase own_friction_d2(const std::string& strength, double a) {
  BenchCase c;
  c.name = "own:friction_d2/" + strength;
  c.family = "self_energizing";
  c.truth = [a](const BrfdTest& t, const BrfdParams& base) {
    return generate_with_level_scale(for_record(base, t), t, [&](std::size_t i, double) {
      return 1.0 + a * t.drum_disp_in[i] * t.drum_disp_in[i];
    });
  };
  return c;
}

// Lining wear slackening the band: friction levels b, Fs / (1 + a W) (hyperbolic, not the
// library's linear 1 - w W), W the friction work done so far, integral of |F v| dt (kip in).
BenchCase own_lining_wear(const std::string& strength, double a) {
  BenchCase c;
  c.name = "own:lining_wear/" + strength;
  c.family = "pretension";
  c.truth = [a](const BrfdTest& t, const BrfdParams& base) {
    return generate_with_level_scale(for_record(base, t), t,
                                     [a](std::size_t, double work) { return 1.0 / (1.0 + a * work); });
  };
  return c;
}

// The held force relaxes hyperbolically after the drum stops: F (1 - rho s/(s + tau)).
BenchCase own_rest_creep(const std::string& strength, double rho, double tau_s) {
  BenchCase c;
  c.name = "own:rest_creep/" + strength;
  c.family = "residual_static";
  c.truth = [rho, tau_s](const BrfdTest& t, const BrfdParams& base) {
    std::vector<double> f = generate(for_record(base, t), t);
    for (std::size_t i = 0; i < t.size(); ++i) {
      const double s = t.time_s[i] - kMotionS;
      if (s > 0.0) f[i] *= 1.0 - rho * s / (s + tau_s);
    }
    return f;
  };
  return c;
}

// Leading/trailing brake factor of capstan form (not the library's hyperbola g/(1 − λ g)): the
// friction level g(v) × e^(+λ g) moving forward and e^(−λ g) backward, g the base model's Stribeck
// level with the actuators where they are (Euler-Eytelwein: the tension ratio e^(μθ) with μ
// following the level; the stiction peak amplified most). A factor by the kinetic level Fc alone
// was tried first: with this drive's short clamping pulses Fc hardly moves, and the factor is a
// difference of level by direction (named asymmetry at the noise floor, 4 of 4).
BenchCase own_brake_factor(const std::string& strength, double lambda_per_kip) {
  BenchCase c;
  c.name = "own:brake_factor/" + strength;
  c.family = "self_energizing";
  c.truth = [lambda_per_kip](const BrfdTest& t, const BrfdParams& base) {
    const BrfdParams p = for_record(base, t);
    const BrfdModel clamp(p);
    return generate_with_level_scale(p, t, [&](std::size_t i, double) {
      const DamperInput in{t.drum_disp_in[i], t.drum_vel_in_per_s[i], t.actuator1_in[i], t.actuator2_in[i]};
      const double s = t.drum_vel_in_per_s[i] >= 0.0 ? 1.0 : -1.0;
      return std::exp(s * lambda_per_kip * clamp.stribeck_kip(in));
    });
  };
  return c;
}

// Flash temperature by the load of exponential form (not the library's 1 − c Fc |v|^n_T on Fc):
// both levels b, Fs × e^(−c Fc |v|^0.5), Fc the Eq. (4) kinetic level of the direction.
BenchCase own_flash_load(const std::string& strength, double c_per_kip) {
  BenchCase c;
  c.name = "own:flash_load/" + strength;
  c.family = "velocity";
  c.truth = [c_per_kip](const BrfdTest& t, const BrfdParams& base) {
    const BrfdParams p = for_record(base, t);
    const BrfdModel clamp(p);
    return generate_with_level_scale(p, t, [&](std::size_t i, double) {
      const DamperInput in{t.drum_disp_in[i], t.drum_vel_in_per_s[i], t.actuator1_in[i], t.actuator2_in[i]};
      return std::exp(-c_per_kip * clamp.kinetic_friction_kip(in) * std::sqrt(std::abs(t.drum_vel_in_per_s[i])));
    });
  };
  return c;
}

BenchCase none_case(bool identify) {
  BenchCase c;
  c.name = identify ? "none/identify" : "none/model";
  c.family = "none";
  c.identify = identify;
  c.truth = [](const BrfdTest& t, const BrfdParams& base) { return generate(for_record(base, t), t); };
  return c;
}

double nrmse_vs(const std::vector<double>& truth, const std::vector<double>& pred) {
  double m = 0.0, se = 0.0, var = 0.0;
  for (double x : truth) m += x;
  m /= static_cast<double>(truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    se += (pred[i] - truth[i]) * (pred[i] - truth[i]);
    var += (truth[i] - m) * (truth[i] - m);
  }
  return var > 0.0 ? std::sqrt(se / var) : 0.0;
}

}  // namespace

BrfdParams bench_base_model() {
  BrfdParams p;
  p.kind = DamperKind::semiactive;
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

const std::vector<BenchDrive>& bench_drive_set() {
  static const std::vector<BenchDrive> drives = {
      {1.0, {{3.5, 0.03, true, false}, {6.5, 0.03, false, true}, {7.5, 0.015, true, true}}},
      {0.8, {{4.5, 0.03, false, true}, {8.5, 0.025, true, false}, {9.5, 0.02, true, true}}}};
  return drives;
}

DamperInput bench_drive_input(double time, const BenchDrive& drive, const BrfdParams& base, double motion_s) {
  const double w = M_PI, tr = 2.0;
  double env = 0.0, denv = 0.0;
  if (time < motion_s) {
    if (time < tr) {
      env = raised_ramp(time / tr);
      denv = 0.5 * M_PI / tr * std::sin(M_PI * time / tr);
    } else if (time > motion_s - tr) {
      env = raised_ramp((motion_s - time) / tr);
      denv = -0.5 * M_PI / tr * std::sin(M_PI * (motion_s - time) / tr);
    } else {
      env = 1.0;
    }
  }
  DamperInput in;
  in.drum_disp_in = drive.amplitude_in * env * std::sin(w * time);
  in.drum_vel_in_per_s = drive.amplitude_in * (denv * std::sin(w * time) + env * w * std::cos(w * time));
  in.actuator1_in = base.semiactive.actuator1_initial_in;
  in.actuator2_in = base.semiactive.actuator2_initial_in;
  for (const ActuatorPulse& p : drive.pulses) {
    if (time < p.t0_s || time >= p.t0_s + 1.0) continue;
    const double dx = -p.amplitude_in * std::sin(2.0 * M_PI * (time - p.t0_s));
    if (p.actuator1) in.actuator1_in += dx;
    if (p.actuator2) in.actuator2_in += dx;
  }
  return in;
}

BrfdTest bench_drive(const BenchDrive& drive, const BrfdParams& base, double rate_hz, double motion_s, double rest_s) {
  BrfdTest t;
  t.dt_s = 1.0 / rate_hz;
  t.has_actuator_positions = true;
  const std::size_t n = static_cast<std::size_t>(std::lround((motion_s + rest_s) * rate_hz));
  for (std::size_t i = 0; i < n; ++i) {
    const double time = static_cast<double>(i) * t.dt_s;
    const DamperInput in = bench_drive_input(time, drive, base, motion_s);
    t.time_s.push_back(time);
    t.drum_disp_in.push_back(in.drum_disp_in);
    t.drum_vel_in_per_s.push_back(in.drum_vel_in_per_s);
    t.actuator1_in.push_back(in.actuator1_in);
    t.actuator2_in.push_back(in.actuator2_in);
    t.actuator1_force_lb.push_back(0.0);
    t.actuator2_force_lb.push_back(0.0);
  }
  return t;
}

std::vector<BrfdTest> bench_drives(const BrfdParams& base, double rate_hz) {
  std::vector<BrfdTest> out;
  for (std::size_t v = 0; v < bench_drive_set().size(); ++v) {
    BrfdTest t = bench_drive(bench_drive_set()[v], base, rate_hz, kMotionS, kRestS);
    t.path = "bench/drive" + std::string(1, static_cast<char>('A' + v)) + ".json";
    out.push_back(std::move(t));
  }
  return out;
}

std::vector<BenchCase> bench_cases(bool quick) {
  std::vector<BenchCase> c;
  if (quick) {
    c.push_back(library_case("backlash", "strong", {0.06, 0.04, 2.0, 4.0, 0.0, 0.0, 0.1, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 5.0, 0.15, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0}));
    c.push_back(library_case("actuator_lag", "strong", {0.05, 0.15, 0.5, 0.0, 2.0, 1.0, 1.0, 0.0}));
    c.push_back(own_backlash("weak", 0.04, 0.1));
    c.push_back(own_friction_d2("strong", 0.3));
    c.push_back(none_case(false));
    return c;
  }
  c.push_back(library_case("backlash", "weak", {0.03, 0.0, 1.0, 1.0, 0.0, 0.0, 0.1, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 5.0, 0.15, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0}));
  // A slack band whose lining stays on the drum: the viscous force goes on through the slack.
  c.push_back(library_case("backlash", "viscous", {0.06, 0.0, 1.0, 1.0, 1.0, 0.0, 0.1, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 5.0, 0.15, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0}));
  c.push_back(library_case("backlash", "strong", {0.06, 0.04, 2.0, 4.0, 0.0, 0.0, 0.1, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 5.0, 0.15, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0}));
  // The grip lost at a reversal (half of it) and taken up over 0.08 in of travel, no slack.
  c.push_back(library_case("backlash", "takeup", {0.0, 0.0, 1.0, 1.0, 0.0, 0.5, 0.08, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 5.0, 0.15, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0}));
  // Drive-line play of 2 x 0.05 in, the band unloading over it (e^(-20 s)).
  c.push_back(library_case("backlash", "play", {0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.1, 0.0, 0.05, 20.0, 0.5, 0.0, 0.0, 0.0, 5.0, 0.15, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0}));
  // The grip lost at a reversal in proportion to the stroke before it, up to 1.5 in (band stretch
  // stored over the stroke), the band force scaled with it.
  c.push_back(library_case("backlash", "by_stroke", {0.0, 0.0, 1.0, 1.0, 0.0, 0.6, 0.1, 1.0, 0.0, 0.0, 0.5, 1.5, 0.0, 0.0, 5.0, 0.15, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0}));
  // An impact ring at each re-engagement: 0.3 kip, 8 Hz, decaying in 0.1 s, a quarter of it in phase
  // with the reversal's force step.
  // The band stiffness collapsed at each reversal (to a fifth, 0.015 in after the turn) and re-established over 0.12 in of travel,
  // the sliding levels kept (the gradual re-engagement of Cao et al. 2015).
  c.push_back(library_case("backlash", "reengagement", {0.0, 0.0, 1.0, 1.0, 0.0, 0.8, 0.12, 1.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 5.0, 0.15, 0.0, 0.0, 0.0, 0.015, 0.0, 0.0, 0.0}));
  // A slack band (2 x 0.05 in) whose play's state before the record is not known: the first motion
  // takes it up, and the slack acts from the first turn of the drum on.
  c.push_back(library_case("backlash", "first_motion", {0.05, 0.0, 1.0, 1.0, 0.0, 0.0, 0.1, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 5.0, 0.15, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0}));
  c.push_back(library_case("backlash", "impact", {0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.1, 0.0, 0.0, 0.0, 0.5, 0.0, 0.3, -0.1, 8.0, 0.1, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0}));
  // A slack that grows with the load before each reversal: 0.006 in per kip (about 0.015-0.03 in
  // after the drives' 2.5-5 kip strokes).
  c.push_back(library_case("backlash", "load_slack", {0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.1, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 5.0, 0.15, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.006}));
  c.push_back(library_case("residual_static", "weak", {0.4, 0.2, 1.0, 0.0, 1.0, 0.0, 0.0, 3.0, 0.5, 0.0}));
  c.push_back(library_case("residual_static", "strong", {0.8, 0.1, 1.0, 0.0, 1.0, 0.0, 0.0, 3.0, 0.5, 0.0}));
  // The held force relaxes by 30 % (stress relaxation); recovers 60 % of the way to a set level.
  c.push_back(library_case("residual_static", "relaxation", {0.0, 0.4, 0.3, 0.0, 1.0, 0.0, 0.0, 3.0, 0.5, 0.0}));
  c.push_back(library_case("residual_static", "set_level", {0.0, 0.5, 0.6, 1.0, 1.0, 0.0, 0.0, 3.0, 0.5, 0.0}));
  // A stretched settling (β = 0.4) of 40 % of the held force: fast at first, a long tail.
  c.push_back(library_case("residual_static", "stretched", {0.0, 0.6, 0.4, 0.0, 0.4, 0.0, 0.0, 3.0, 0.5, 0.0}));
  // A ring-down of 0.5 kip at 4 Hz, decaying in 0.4 s, after each stop (the rig's compliance).
  c.push_back(library_case("residual_static", "ring", {1.0, 100.0, 0.0, 0.0, 1.0, 0.0, 0.5, 4.0, 0.4, 0.0}));
  // Andrade's transient creep at rest (relaxation_tail -1, β 1/3): no levelling off over a rest.
  c.push_back(library_case("residual_static", "andrade", {0.0, 60.0, 1.0, 0.0, 1.0 / 3.0, 0.0, 0.0, 3.0, 0.5, -1.0}));
  c.push_back(library_case("actuator_lag", "weak", {0.06, 0.0, 1.0, 0.0, 2.0, 1.0, 1.0, 0.0}));
  c.push_back(library_case("actuator_lag", "strong", {0.05, 0.15, 0.5, 0.0, 2.0, 1.0, 1.0, 0.0}));
  // A transport delay of 0.08 s; the actuators slewing at no more than 0.1 in/s.
  c.push_back(library_case("actuator_lag", "delay", {0.0, 0.0, 1.0, 0.08, 2.0, 1.0, 1.0, 0.0}));
  c.push_back(library_case("actuator_lag", "rate_limit", {0.0, 0.0, 1.0, 0.0, 0.1, 1.0, 1.0, 0.0}));
  // Half the clamping at once, half creeping after it with τ 0.8 s (a Zener element).
  c.push_back(library_case("actuator_lag", "partial", {0.8, 0.0, 1.0, 0.0, 2.0, 0.5, 1.0, 0.0}));
  // Tightens with τ 0.05 s, releases (actuators extending) four times slower.
  c.push_back(library_case("actuator_lag", "one_way", {0.05, 0.0, 1.0, 0.0, 2.0, 1.0, 4.0, 0.0}));
  // The clamping rings after each actuator motion: a second-order response of period 1.1 s, ζ 0.3
  // (its envelope decays over 0.6 s, after the actuators stopped).
  c.push_back(library_case("actuator_lag", "ringing", {0.0, 1.1, 0.3, 0.0, 2.0, 1.0, 1.0, 0.0}));
  // Play in each actuator's drive, half-width 0.006 in (a fifth of the larger episodes' travel).
  c.push_back(library_case("actuator_lag", "play", {0.0, 0.0, 1.0, 0.0, 2.0, 1.0, 1.0, 0.006}));
  c.push_back(library_case("asymmetry", "weak", {0.08, 0.15, 0.0, 0.0, 0.0, 0.5, 0.0, 1.0, 0.0, 3000.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0}));
  c.push_back(library_case("asymmetry", "strong", {0.15, 0.3, 0.0, 0.0, 0.0, 0.5, 0.0, 1.0, 0.0, 3000.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0}));
  c.push_back(library_case("asymmetry", "speed", {0.0, 0.0, 0.35, 0.5, 0.0, 0.5, 0.0, 1.0, 0.0, 3000.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0}));  // Stribeck speed and σ2 by direction
  c.push_back(library_case("asymmetry", "motion", {0.0, 0.0, 0.0, 0.0, 0.5, 0.5, 0.0, 1.0, 0.0, 3000.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0}));  // band stiffness by direction of motion
  // One band differs: the backward band's Stribeck speed × 1.6, the forward band as modelled.
  c.push_back(library_case("asymmetry", "one_sided", {0.0, 0.0, -0.3, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 3000.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0}));
  // One band's own lining: the forward band's friction rising as 0.1 |v|^0.5 (the backward band as
  // modelled); the backward band fading with its own friction work (30 % over ~40 kip·in), cooling
  // with a 5 s time constant.
  c.push_back(library_case("asymmetry", "band_speed", {0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.05, 0.5, 0.0, 3000.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0}));
  c.push_back(library_case("asymmetry", "band_fade", {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, -0.004, 3000.0, 0.2, 1.0, 0.0, 0.0, 0.0, 1.0}));
  // The forward band's run-in on Eq. (4)'s Fc only (Fs kept): its level rises 0.5 % per kip in of its own work, saturating.
  c.push_back(library_case("asymmetry", "run_in_kinetic", {0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, -0.005, 40.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0}));
  // The forward band's lining periodic in the drum position: its level × (1 + 0.4 cos(2π x/0.8 in)) (twenty-sixth session).
  c.push_back(library_case("asymmetry", "lining_wave", {0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 3000.0, 0.0, 1.0, 0.0, 0.2, 0.0, 0.8}));
  c.push_back(library_case("velocity", "weak", {1.2, 0.1, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 1.0, 0.0, 0.5, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.5}));
  c.push_back(library_case("velocity", "strong", {1.0, 0.2, -0.08, 1.0, 0.05, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 1.0, 0.0, 0.5, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.5}));
  // Velocity-neutral rate-and-state (a = -s: only the transient after a change of slip rate), a
  // quadratic viscous force and a lagged Stribeck term.
  c.push_back(library_case("velocity", "transient", {2.0, 0.0, -0.3, 1.0, 0.2, 0.3, 0.08, 0.15, 2.0, 0.0, 0.0, 1.0, 0.0, 0.5, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.5}));
  // A shear-thinning film in place of part of the viscous force: -0.3 v + 0.4 sgn(v) |v|^0.5.
  c.push_back(library_case("velocity", "film", {2.0, -0.3, 0.0, 1.0, 0.0, 0.0, 0.4, 0.0, 0.5, 0.0, 0.0, 1.0, 0.0, 0.5, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.5}));
  // Frictional memory of the whole friction-velocity curve: the Stribeck term and the viscous force
  // see the velocity 0.1 s late.
  c.push_back(library_case("velocity", "memory", {2.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.1, 2.0, 1.0, 0.0, 1.0, 0.0, 0.5, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.5}));
  // Flash heating: the levels fall by 30 % of (1 - 0.8/|v|) above 0.8 in/s (Rice 2006).
  c.push_back(library_case("velocity", "flash", {2.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.3, 0.8, 0.0, 0.5, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.5}));
  // Flash temperature by the load (Archard 1959): Fc × (1 − 0.08 Fc |v|), low Péclet number.
  c.push_back(library_case("velocity", "flash_load", {2.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 1.0, 0.08, 1.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.5}));
  // The regularized steady-state rate law on Eq. (4)'s Fc only: Fc (1 + 0.15 ln(1 + |v|/0.3 in/s)), Fs kept.
  c.push_back(library_case("velocity", "rate_kinetic", {2.0, 0.0, 0.0, 0.3, 0.0, 0.15, 0.0, 0.0, 2.0, 0.0, 0.0, 1.0, 0.0, 0.5, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.5}));
  // A friction peak over log speed (viscoelastic lining, Grosch 1963): Fc × (1 + 0.25 e^(−ln²(|v|/2)/(2 · 0.7²))), Fs kept.
  c.push_back(library_case("velocity", "peak", {2.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 1.0, 0.0, 0.5, 0.0, 0.0, 0.0, 0.25, 2.0, 0.7, 0.0, 0.5}));
  // A power law of the speed on both levels (third body): g x (1 + 0.15 |v|^0.4), 15 % at 1 in/s.
  c.push_back(library_case("velocity", "power", {2.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 1.0, 0.0, 0.5, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.15, 0.4}));
  c.push_back(library_case("pretension", "weak", {0.5, 0.5, 0.0, 1.0, 3000.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0}));
  c.push_back(library_case("pretension", "strong", {1.0, 0.8, 0.0, 1.0, 3000.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0}));
  c.push_back(library_case("pretension", "clamping", {0.0, 0.0, 0.0, 0.6, 3000.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0}));  // a saturating contact, Fc = b N^0.6
  // Thermal fade: the friction work stored as heat, conducted away with a 5 s time constant.
  c.push_back(library_case("pretension", "fade", {0.0, 0.0, 0.004, 1.0, 3000.0, 0.2, 1.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0}));
  // The band's own pre-tension loosens with the wear (40 % over about 50 kip·in of friction work);
  // the actuators keep their increment.
  c.push_back(library_case("pretension", "loosening", {0.0, 0.0, 0.008, 1.0, 50.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0}));
  // Eq. (4) bent with its slope at the pre-tension kept (Box-Cox, q = 2, k = 1/2: the capstan's
  // exponential to second order).
  c.push_back(library_case("pretension", "curved", {0.0, 0.0, 0.0, 2.0, 3000.0, 0.0, 1.0, 0.5, 0.0, 1.0, 0.0, 0.0, 0.0}));
  // The two actuators' clamping not additive: ΔFc += c u1 u2 (with the drives' two-actuator pulses,
  // 0.015-0.02 in, about 1.5-2.4 kip at their peak).
  // A kink at the pre-tension: releasing below it the clamping is 0.6 as steep as tightening.
  c.push_back(library_case("pretension", "kinked", {0.0, 0.0, 0.0, 1.0, 3000.0, 0.0, 1.0, 1.0, 0.0, 0.6, 0.0, 0.0, 0.0}));
  // A band that takes tension only above its set point: releasing, 0.05 as steep as tightening (twenty-sixth session).
  c.push_back(library_case("pretension", "tension_only", {0.0, 0.0, 0.0, 1.0, 3000.0, 0.0, 1.0, 1.5, 0.0, 0.05, 0.0, 0.0, 0.0}));
  c.push_back(library_case("pretension", "coupling", {0.0, 0.0, 0.0, 1.0, 3000.0, 0.0, 1.0, 1.0, 6000.0, 1.0, 0.0, 0.0, 0.0}));
  // Each actuator's band stretched along an exponential (Fung) law, 25 /in of tightening travel:
  // at 0.03 in of travel its term is 1.4 times Eq. (4)'s, released by 0.03 in 0.7 times.
  c.push_back(library_case("pretension", "band_stretch", {0.0, 0.0, 0.0, 1.0, 3000.0, 0.0, 1.0, 1.0, 0.0, 1.0, 25.0, 0.0, 0.0}));
  // Each actuator's band saturating alike both ways, tanh(30 t)/30: at 0.03 in of travel either
  // way its term is 0.79 times Eq. (4)'s (twenty-fifth session).
  c.push_back(library_case("pretension", "band_saturation", {0.0, 0.0, 0.0, 1.0, 3000.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 0.0, 30.0}));
  c.push_back(library_case("self_energizing", "weak", {-0.1, 0.08, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.3, 0.0}));
  c.push_back(library_case("self_energizing", "strong", {-0.15, 0.1, 0.15, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.3, 0.0}));
  c.push_back(library_case("self_energizing", "servo", {0.0, 0.0, 0.0, 1.0, 0.3, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.3, 0.0}));  // band-force feedback only
  c.push_back(library_case("self_energizing", "wrap", {0.7, -0.6, 0.3, 2.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.3, 0.0}));   // strong wrap: ~ capstan e^(±κd)
  // Self-servo per kip of band force, the same gain both ways: g (1 + 0.06 |F|).
  c.push_back(library_case("self_energizing", "servo_per_kip", {0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.06, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.3, 0.0}));
  c.push_back(library_case("self_energizing", "spring", {0.0, 0.0, 0.0, 1.0, 0.0, 0.6, 0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.3, 0.0}));  // band-stretch spring in parallel
  // Each band's own spring: the one stretched backward at 0.3 of the forward one's rate. (The bench
  // records start at the drum's zero, as the measured tests do, so drum_start_share is not judged here.)
  c.push_back(library_case("self_energizing", "band_springs", {0.0, 0.0, 0.0, 1.0, 0.0, 0.6, 0.0, 0.0, 0.3, 1.0, 0.0, 1.0, 0.0, 0.0, 0.3, 0.0}));
  // A leading/trailing self-servo: +0.06 per kip of band force moving forward, −0.06 backward.
  c.push_back(library_case("self_energizing", "servo_by_direction", {0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.06, 0.0, 1.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.3, 0.0}));
  // The leading/trailing brake factor by the level on Eq. (4)'s Fc only: Fc/(1 ∓ 0.05 Fc), Fs kept.
  c.push_back(library_case("self_energizing", "brake_factor", {0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, -1.0, 0.05, 0.0, 0.0, 0.0, 0.3, 0.0}));
  // A capstan wrap by the drum position on Eq. (4)'s Fc only, from the start (Fs kept: stiction_share 0).
  c.push_back(library_case("self_energizing", "wrap_kinetic", {0.5, -0.5, 0.12, 2.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.3, 0.0}));
  // The wrap built up over each stroke since the reversal, backward only, on Fc only: Fc (1 + 0.5 (1 − e^(−s/0.4 in))).
  c.push_back(library_case("self_energizing", "stroke_wrap", {0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.5, 0.4, 0.0}));
  // The self-servo per kip through a 0.15 s lag, tightening only: g (1 + 0.06 max(0, sgn(v) y)) (twenty-sixth session).
  c.push_back(library_case("self_energizing", "lagged_servo", {0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.06, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.3, 0.15}));
  c.push_back(library_case("transition_shape", "weak", {2.5, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.5, 0.0, 0.5, 0.0, 0.15, 0.4, 0.0, 0.15, 0.4, 0.0, 1.0, 1.0, 0.0, 0.5, 1.0}));
  c.push_back(library_case("transition_shape", "strong", {5.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.5, 0.0, 0.5, 0.0, 0.15, 0.4, 0.0, 0.15, 0.4, 0.0, 1.0, 1.0, 0.0, 0.5, 1.0}));
  c.push_back(library_case("transition_shape", "smooth", {0.5, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.5, 0.0, 0.5, 0.0, 0.15, 0.4, 0.0, 0.15, 0.4, 0.0, 1.0, 1.0, 0.0, 0.5, 1.0}));  // a rounder transition than LuGre
  // Elasto-plastic pre-sliding: elastic up to 40 % of the friction level, elastic unloading.
  c.push_back(library_case("transition_shape", "presliding", {1.0, 0.9, 0.4, 1.0, 0.0, 1.0, 1.0, 0.0, 0.5, 0.0, 0.5, 0.0, 0.15, 0.4, 0.0, 0.15, 0.4, 0.0, 1.0, 1.0, 0.0, 0.5, 1.0}));
  // Elastic up to 30 % of the friction level, slip full from 61.5 % on (Dupont's z_max below the
  // steady state; unloading as LuGre).
  c.push_back(library_case("transition_shape", "breakaway", {1.0, 0.0, 0.3, 1.0, 0.0, 1.0, 0.45, 0.0, 0.5, 0.0, 0.5, 0.0, 0.15, 0.4, 0.0, 0.15, 0.4, 0.0, 1.0, 1.0, 0.0, 0.5, 1.0}));
  // Dahl's own exponent: dF/dx = σ0 |1 − F/g sgn v|^2.5 sgn(·), a slow rounded approach to sliding.
  c.push_back(library_case("transition_shape", "dahl", {1.0, 0.0, 0.0, 2.5, 0.0, 1.0, 1.0, 0.0, 0.5, 0.0, 0.5, 0.0, 0.15, 0.4, 0.0, 0.15, 0.4, 0.0, 1.0, 1.0, 0.0, 0.5, 1.0}));
  // Two contact elements: half the friction carried by one 5 times softer (Maxwell-slip).
  c.push_back(library_case("transition_shape", "two_element", {1.0, 0.0, 0.0, 1.0, 0.5, 0.2, 1.0, 0.0, 0.5, 0.0, 0.5, 0.0, 0.15, 0.4, 0.0, 0.15, 0.4, 0.0, 1.0, 1.0, 0.0, 0.5, 1.0}));
  // LuGre's micro-damping fading with the speed (Canudas de Wit et al. 1995), σ1' = 2 kip s/in, v_d = 0.4 in/s.
  c.push_back(library_case("transition_shape", "micro_damping", {1.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 2.0, 0.4, 0.0, 0.5, 0.0, 0.15, 0.4, 0.0, 0.15, 0.4, 0.0, 1.0, 1.0, 0.0, 0.5, 1.0}));
  // Bliman-Sorine's stiction peak in the travel domain: the fast element over-reaches by θ, a slow one
  // pulls back over ℓ2 (blind set 31 t19)
  c.push_back(library_case("transition_shape", "overshoot", {1.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.5, 0.7, 0.5, 0.0, 0.15, 0.4, 0.0, 0.15, 0.4, 0.0, 1.0, 1.0, 0.0, 0.5, 1.0}));
  // A stiction bump in the travel since each reversal: the loaded band force × (1 + 0.8 B(s)), B rising
  // over 0.052 in and falling over 0.13 in of travel, peak 1 (blind set 32 t02)
  c.push_back(library_case("transition_shape", "stiction_bump", {1.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.5, 0.0, 0.5, 0.8, 0.13, 0.4, 0.0, 0.15, 0.4, 0.0, 1.0, 1.0, 0.0, 0.5, 1.0}));
  // Bliman-Sorine's travel pulse beside the bristle: 0.6 Fc (w1 − w2)/(2 P_max), w_j following sgn v
  // over 0.03 and 0.12 in of travel (blind set 33 t19)
  c.push_back(library_case("transition_shape", "travel_pulse", {1.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.5, 0.0, 0.5, 0.0, 0.15, 0.4, 0.6, 0.12, 0.25, 0.0, 1.0, 1.0, 0.0, 0.5, 1.0}));
  // An Iwan bank carrying 40 % of the band force: 16 elasto-plastic elements, Iwan's uniform density
  // of slip travels (blind sets 30 t25, 31 t27, 32 t21, 33 t15 wrote such banks)
  c.push_back(library_case("transition_shape", "iwan_bank", {1.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.5, 0.0, 0.5, 0.0, 0.15, 0.4, 0.0, 0.15, 0.4, 0.4, 1.0, 1.0, 0.0, 0.5, 1.0}));
  // Linear slip weakening since the reversal (Ida 1972; Palmer & Rice 1973): the levels × (1 + 0.6 (1 − s/0.5 in)).
  c.push_back(library_case("transition_shape", "slip_weakening", {1.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.5, 0.0, 0.5, 0.0, 0.15, 0.4, 0.0, 0.15, 0.4, 0.0, 1.0, 1.0, 0.6, 0.5, 1.0}));
  c.push_back(own_backlash("weak", 0.04, 0.1));
  c.push_back(own_backlash("strong", 0.08, 0.1));
  c.push_back(own_delay("weak", 0.05));
  c.push_back(own_delay("strong", 0.1));
  c.push_back(own_friction_d2("weak", 0.15));
  c.push_back(own_friction_d2("strong", 0.3));
  c.push_back(own_lining_wear("weak", 0.001));
  c.push_back(own_lining_wear("strong", 0.003));
  c.push_back(own_rest_creep("weak", 0.3, 0.3));
  c.push_back(own_rest_creep("strong", 0.6, 0.2));
  c.push_back(own_brake_factor("weak", 0.02));
  c.push_back(own_brake_factor("strong", 0.05));
  c.push_back(own_flash_load("weak", 0.04));
  c.push_back(own_flash_load("strong", 0.1));
  c.push_back(none_case(false));
  c.push_back(none_case(true));
  return c;
}

namespace {

// The paper's semi-active model as in configs/brfd-semiactive.yaml (the base of damper/synthetic).
BrfdParams paper_semiactive_model() {
  BrfdParams p;
  p.kind = DamperKind::semiactive;
  p.lugre.sigma0_kip_per_in = 15.36;
  p.lugre.sigma1_kip_s_per_in = 0.0;
  p.lugre.sigma2_kip_s_per_in = 0.5;
  p.lugre.fs_fwd_kip = 7.116;
  p.lugre.fs_bwd_kip = 3.760;
  p.lugre.fc_fwd_kip = 2.648;
  p.lugre.fc_bwd_kip = 1.253;
  p.lugre.vs_in_per_s = 1.3;
  p.semiactive.actuator1_initial_in = 0.655;
  p.semiactive.actuator2_initial_in = 0.8559;
  return p;
}

std::string library_family(const std::string& label) {
  if (label == "displacement_friction") return "self_energizing";
  if (label == "velocity_friction" || label == "viscous") return "velocity";
  return label;
}

}  // namespace

std::vector<BenchCase> hidden_shape_cases(bool quick, bool earthquake) {
  namespace ds = synthetic;
  std::vector<BenchCase> out;
  const BrfdParams base = paper_semiactive_model();
  for (ds::HiddenShape shape : ds::all_hidden_shapes()) {
    for (double strength : {0.5, 1.0}) {
      if (shape == ds::HiddenShape::none && strength != 1.0) continue;
      if (quick && strength != 1.0) continue;
      BenchCase c;
      c.name = std::string(earthquake ? "hidden-eq:" : "hidden:") + ds::to_string(shape) + (shape == ds::HiddenShape::none ? "" : strength == 1.0 ? "/strong" : "/weak");
      c.family = library_family(ds::effect_family(shape));
      c.base = base;
      c.records = [shape, strength, base, earthquake](unsigned seed, double noise) {
        std::vector<std::pair<BrfdTest, std::vector<double>>> recs;
        for (int test : {1, 4}) {
          ds::SyntheticSpec spec;
          spec.harmonic.moves = ds::paper_harmonic_moves(test);
          if (earthquake) spec.motion = ds::SyntheticSpec::Motion::earthquake;
          spec.effect.shape = shape;
          spec.effect.strength_scale = strength;
          spec.noise_std_kip = noise;
          spec.seed = seed + static_cast<unsigned>(test);
          spec.name = "hidden_test" + std::to_string(test);
          ds::SyntheticTest g = ds::generate_synthetic_test(base, spec);
          recs.emplace_back(std::move(g.test), std::move(g.clean_force_kip));
        }
        return recs;
      };
      out.push_back(std::move(c));
    }
  }
  return out;
}

std::string bench_final_line(const BenchResult& r) {
  std::ostringstream o;
  o << "trials=" << r.trials.size() << " correct=" << r.correct << " wrong=" << r.wrong
    << " false_positive=" << r.false_positive;
  return o.str();
}

BenchResult run_diagnose_bench(const BenchOptions& bo) {
  auto log = [&bo](const std::string& s) {
    if (bo.log) bo.log(s);
  };
  BenchResult res;
  const BrfdParams base = bench_base_model();
  // 512 Hz records, fits at diagnose's 256 Hz. (The CI subset at 256 Hz with fits at 128 Hz was
  // measured too: the coarser fits leave a discretization residual that velocity or pretension then
  // explained as a second effect in 2 of 5 trials.)
  const std::vector<BrfdTest> drives = bench_drives(base, 512.0);
  std::vector<BenchCase> cases;
  if (!bo.only_hidden_shapes) cases = bench_cases(bo.quick);
  if (bo.hidden_shapes || bo.only_hidden_shapes) {
    if (bo.hidden_motion != "harmonic" && bo.hidden_motion != "earthquake")
      throw std::invalid_argument("diagnose bench: hidden_motion '" + bo.hidden_motion + "' (harmonic or earthquake)");
    const std::vector<BenchCase> h = hidden_shape_cases(bo.quick, bo.hidden_motion == "earthquake");
    cases.insert(cases.end(), h.begin(), h.end());
  }
  cases.insert(cases.end(), bo.extra.begin(), bo.extra.end());
  const std::vector<double> noise = bo.quick ? std::vector<double>{0.05} : bo.noise_kip;
  const int seeds = bo.quick ? 1 : bo.seeds;
  const std::string model_path =
      (std::filesystem::temp_directory_path() / ("diagnose-bench-base-" + std::to_string(::getpid()) + ".yaml")).string();
  std::ofstream csv;
  if (!bo.out_dir.empty()) {
    std::filesystem::create_directories(bo.out_dir);
    csv.open((std::filesystem::path(bo.out_dir) / "bench.csv").string());
    csv << "case,family,seed,noise_kip,named,gap_before,gap_after,correct,false_positive,seconds\n";
  }
  log("case                              seed noise   named                          gap before -> after  verdict");
  for (const BenchCase& c : cases) {
    bool run = bo.only.empty();
    for (const std::string& p : bo.only) run = run || c.name.rfind(p, 0) == 0;
    if (!run) continue;
    for (double sigma : noise) {
      for (int s = 0; s < seeds; ++s) {
        const auto t0 = std::chrono::steady_clock::now();
        const unsigned seed = 1000u * static_cast<unsigned>(s + 1) + static_cast<unsigned>(std::lround(sigma * 1000));
        std::vector<BrfdTest> recs;
        std::vector<std::vector<double>> clean;
        if (c.records) {
          for (auto& rc : c.records(seed, sigma)) {
            recs.push_back(std::move(rc.first));
            clean.push_back(std::move(rc.second));
          }
        } else {
          recs = drives;
          std::mt19937 rng(seed);
          std::normal_distribution<double> nd(0.0, sigma);
          for (BrfdTest& t : recs) {
            clean.push_back(c.truth(t, base));
            t.force_kip = clean.back();
            for (double& f : t.force_kip) f += nd(rng);
          }
        }
        {
          std::ofstream f(model_path);
          f << brfd_params_to_yaml(c.base ? *c.base : base);
        }
        DiagnoseOptions o;
        o.model_path = model_path;
        o.measured_tests = recs;
        if (bo.base != "model" && bo.base != "identify")
          throw std::invalid_argument("diagnose bench: base '" + bo.base + "' (model or identify)");
        const bool identify = c.identify || bo.base == "identify";
        o.base = identify ? BaseSource::identify : BaseSource::model;
        o.figures = false;
        o.max_effects = 3;
        o.seed = seed;
        o.effect_evals = bo.effect_evals;
        o.fit_rate_hz = bo.fit_rate_hz;
        o.threads = bo.threads;
        if (bo.verbose) o.log = bo.log;
        if (identify) {
          o.base_identification.global_runs = 1;
          o.base_identification.global_max_evals = 1500;
          o.base_identification.local_max_evals = 500;
          o.base_refit_evals = 60;
        }
        const DiagnoseResult r = run_diagnose(o);
        BenchTrial tr;
        tr.case_name = c.name;
        tr.family = c.family;
        tr.seed = seed;
        tr.noise_kip = sigma;
        for (const std::string& a : r.added) tr.named += (tr.named.empty() ? "" : ",") + a;
        if (tr.named.empty()) tr.named = "none";
        for (std::size_t k = 0; k < r.records.size(); ++k) {
          tr.gap_before += nrmse_vs(clean[k], r.records[k].model_before_kip) / static_cast<double>(r.records.size());
          tr.gap_after += nrmse_vs(clean[k], r.records[k].model_after_kip) / static_cast<double>(r.records.size());
        }
        if (c.family == "none") {
          tr.correct = tr.named == "none";
          tr.false_positive = !tr.correct;
        } else {
          tr.correct = tr.named == c.family && tr.gap_after <= 0.5 * tr.gap_before;
        }
        tr.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::ostringstream line;
        line << std::left << std::setw(34) << c.name << std::setw(5) << s + 1 << std::setw(8) << format_fixed(sigma, 3)
             << std::setw(31) << tr.named << std::right << std::setw(6) << format_fixed(tr.gap_before, 4) << " -> "
             << std::setw(6) << format_fixed(tr.gap_after, 4) << "  " << (tr.correct ? "correct" : "WRONG") << " ("
             << format_fixed(tr.seconds, 1) << " s)";
        log(line.str());
        if (csv) {
          csv << c.name << ',' << c.family << ',' << seed << ',' << sigma << ',' << '"' << tr.named << '"' << ','
              << tr.gap_before << ',' << tr.gap_after << ',' << tr.correct << ',' << tr.false_positive << ','
              << tr.seconds << '\n';
        }
        res.correct += tr.correct ? 1 : 0;
        res.wrong += tr.correct ? 0 : 1;
        res.false_positive += tr.false_positive ? 1 : 0;
        res.trials.push_back(tr);
      }
    }
  }
  std::filesystem::remove(model_path);
  // Confusion matrix: hidden family (rows) x what was named (columns).
  std::vector<std::string> cols;
  for (const EffectSpec& e : effect_library()) cols.push_back(e.name);
  cols.push_back("none");
  cols.push_back("several");
  std::map<std::string, std::map<std::string, int>> m;
  std::vector<std::string> rows;
  for (const BenchTrial& t : res.trials) {
    if (std::find(rows.begin(), rows.end(), t.family) == rows.end()) rows.push_back(t.family);
    const std::string col = t.named.find(',') != std::string::npos ? "several" : t.named;
    ++m[t.family][col];
  }
  log("");
  log("confusion matrix (rows: hidden family, columns: named; several = more than one effect):");
  std::ostringstream head;
  head << std::left << std::setw(17) << "hidden \\ named";
  for (const std::string& c : cols) head << std::right << std::setw(9) << c.substr(0, 8);
  head << std::setw(9) << "correct";
  log(head.str());
  for (const std::string& r : rows) {
    std::ostringstream l;
    l << std::left << std::setw(17) << r;
    int n = 0, ok = 0;
    for (const std::string& c : cols) {
      const int v = m[r].count(c) ? m[r][c] : 0;
      n += v;
      l << std::right << std::setw(9) << (v ? std::to_string(v) : ".");
    }
    for (const BenchTrial& t : res.trials)
      if (t.family == r && t.correct) ++ok;
    l << std::setw(9) << (std::to_string(ok) + "/" + std::to_string(n));
    log(l.str());
  }
  log(bench_final_line(res));
  return res;
}

}  // namespace damper
