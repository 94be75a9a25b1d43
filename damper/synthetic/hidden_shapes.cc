#include "damper/synthetic/hidden_shapes.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <random>
#include <stdexcept>

namespace damper::synthetic {

namespace {

constexpr double kPi = 3.14159265358979323846;

struct ShapeInfo {
  HiddenShape shape;
  const char* name;
  const char* family;
};

const ShapeInfo kShapes[] = {
    {HiddenShape::none, "none", "none"},
    {HiddenShape::backlash, "backlash", "backlash"},
    {HiddenShape::actuator_second_order, "actuator_second_order", "actuator_lag"},
    {HiddenShape::actuator_delay, "actuator_delay", "actuator_lag"},
    {HiddenShape::displacement_friction, "displacement_friction", "displacement_friction"},
    {HiddenShape::velocity_friction, "velocity_friction", "velocity_friction"},
    {HiddenShape::residual_static, "residual_static", "residual_static"},
    {HiddenShape::viscous, "viscous", "viscous"},
    {HiddenShape::asymmetry, "asymmetry", "asymmetry"},
};

const ShapeInfo& info(HiddenShape shape) {
  for (const ShapeInfo& s : kShapes)
    if (s.shape == shape) return s;
  throw std::invalid_argument("unknown hidden shape");
}

void require(bool ok, const std::string& field, double value, const std::string& rule) {
  if (!ok)
    throw std::invalid_argument("synthetic spec: " + field + " = " + std::to_string(value) +
                                " (must be " + rule + ")");
}

/// Friction levels b and Fs scaled by separate factors per direction (b_of_velocity too).
BrfdParams scaled_friction(const BrfdParams& base, double fwd_factor, double bwd_factor) {
  BrfdParams p = base;
  p.lugre.fc_fwd_kip *= fwd_factor;
  p.lugre.fs_fwd_kip *= fwd_factor;
  p.lugre.fc_bwd_kip *= bwd_factor;
  p.lugre.fs_bwd_kip *= bwd_factor;
  for (double& b : p.b_of_velocity.fwd_kip) b *= fwd_factor;
  for (double& b : p.b_of_velocity.bwd_kip) b *= bwd_factor;
  return p;
}

DamperInput input_of(const BrfdTest& t, const std::vector<double>& a1,
                     const std::vector<double>& a2, std::size_t i) {
  DamperInput in;
  in.drum_disp_in = t.drum_disp_in[i];
  in.drum_vel_in_per_s = t.drum_vel_in_per_s[i];
  in.actuator1_in = a1[i];
  in.actuator2_in = a2[i];
  return in;
}

/// Replays the model over the inputs with the replay convention of damper/replay.cc: the force
/// at sample 0 from the initial bristle state, then one step() per sample with sample i's
/// input held. `params_at(i)` gives the (possibly time-varying) parameters; the bristle state
/// is carried across parameter changes.
std::vector<double> run_model(const std::function<BrfdParams(std::size_t)>& params_at,
                              double initial_force_kip, const BrfdTest& t,
                              const std::vector<double>& a1, const std::vector<double>& a2) {
  const std::size_t n = t.size();
  std::vector<double> f(n);
  BrfdModel first(params_at(0));
  double z = first.bristle_for_force(initial_force_kip);
  f[0] = first.force_kip(z, input_of(t, a1, a2, 0));
  for (std::size_t i = 1; i < n; ++i) {
    BrfdModel m(params_at(i));
    m.set_bristle_in(z);
    f[i] = m.step(input_of(t, a1, a2, i), t.dt_s);
    z = m.bristle_in();
  }
  return f;
}

std::vector<double> run_model(const BrfdParams& params, double initial_force_kip,
                              const BrfdTest& t, const std::vector<double>& a1,
                              const std::vector<double>& a2) {
  const std::size_t n = t.size();
  std::vector<double> f(n);
  BrfdModel model(params);
  model.set_bristle_in(model.bristle_for_force(initial_force_kip));
  f[0] = model.force_kip(model.bristle_in(), input_of(t, a1, a2, 0));
  for (std::size_t i = 1; i < n; ++i) f[i] = model.step(input_of(t, a1, a2, i), t.dt_s);
  return f;
}

/// Three-stage backlash (BacklashShape).
std::vector<double> backlash_force(const BrfdParams& params, const BacklashShape& s,
                                   double initial_force_kip, const BrfdTest& t,
                                   const std::vector<double>& a1, const std::vector<double>& a2) {
  const std::size_t n = t.size();
  std::vector<double> f(n);
  BrfdModel engaged(params);
  engaged.set_bristle_in(engaged.bristle_for_force(initial_force_kip));
  f[0] = engaged.force_kip(engaged.bristle_in(), input_of(t, a1, a2, 0));
  // The record starts with a loaded band: engaged until the first reversal.
  int dir = 0;
  bool after_reversal = false;
  double x_rev = 0.0, f_rev = 0.0;
  for (std::size_t i = 1; i < n; ++i) {
    DamperInput in = input_of(t, a1, a2, i);
    const double v = in.drum_vel_in_per_s;
    const int d = v > 0.0 ? 1 : (v < 0.0 ? -1 : 0);
    if (d != 0 && d != dir) {
      if (dir != 0) {  // a reversal (not the first motion from rest)
        after_reversal = true;
        x_rev = t.drum_disp_in[i - 1];
        f_rev = f[i - 1];
        engaged.set_bristle_in(0.0);  // the band goes slack
      }
      dir = d;
    }
    if (!after_reversal) {
      f[i] = engaged.step(in, t.dt_s);
      continue;
    }
    const double travel = std::abs(in.drum_disp_in - x_rev);
    const double u = std::max(0.0, 1.0 - travel / s.unload_travel_in);
    const double unloading = f_rev * u * u;
    if (travel < s.free_travel_in) {
      in.drum_vel_in_per_s = 0.0;  // free travel: the band does not move with the drum
      engaged.step(in, t.dt_s);
      f[i] = unloading;
    } else {
      // Contact stage: the band takes up the drum velocity progressively, ξ v, so the band
      // stiffness seen by the drum rises as σ0 ξ; full take-up (stage 3) at ξ = 1.
      const double xi = std::min(1.0, (travel - s.free_travel_in) / s.contact_travel_in);
      in.drum_vel_in_per_s = xi * v;
      f[i] = unloading + engaged.step(in, t.dt_s);
    }
  }
  return f;
}

/// Residual static force relaxing at rest (ResidualStaticShape), on top of the model force.
std::vector<double> residual_static_force(const std::vector<double>& fm, const ResidualStaticShape& s,
                                          const BrfdTest& t) {
  std::vector<double> f(fm.size());
  double delta = 0.0;
  f[0] = fm[0];
  for (std::size_t i = 1; i < fm.size(); ++i) {
    const double v = t.drum_vel_in_per_s[i];
    const double r = v / s.rest_speed_in_per_s;
    const double w = std::exp(-r * r);
    const double k = w / s.time_constant_s + (1.0 - w) * std::abs(v) / s.wipe_travel_in;
    const double target = (w * (-s.relaxed_fraction * fm[i]) / s.time_constant_s) / k;
    delta = target + (delta - target) * std::exp(-k * t.dt_s);
    f[i] = fm[i] + delta;
  }
  return f;
}

double harmonic_envelope(const HarmonicProfile& p, double t, double& rate) {
  const double ramp = 1.0 / p.frequency_hz;
  rate = 0.0;
  if (t <= 0.0 || t >= p.motion_end_s) return 0.0;
  if (t < ramp) {
    rate = 1.0 / ramp;
    return t / ramp;
  }
  if (t > p.motion_end_s - ramp) {
    rate = -1.0 / ramp;
    return (p.motion_end_s - t) / ramp;
  }
  return 1.0;
}

double earthquake_envelope(const EarthquakeProfile& p, double t, double& rate) {
  rate = 0.0;
  if (t <= 0.0 || t >= p.motion_end_s) return 0.0;
  double e, de;
  if (t < p.rise_end_s) {
    e = (t / p.rise_end_s) * (t / p.rise_end_s);
    de = 2.0 * t / (p.rise_end_s * p.rise_end_s);
  } else if (t < p.strong_end_s) {
    e = 1.0;
    de = 0.0;
  } else {
    e = std::exp(-p.decay_per_s * (t - p.strong_end_s));
    de = -p.decay_per_s * e;
  }
  const double taper_len = p.taper_s;
  const double taper_start = p.motion_end_s - taper_len;
  if (t > taper_start) {
    const double ph = kPi * (t - taper_start) / taper_len;
    const double c = 0.5 * (1.0 + std::cos(ph));
    const double dc = -0.5 * std::sin(ph) * kPi / taper_len;
    de = de * c + e * dc;
    e *= c;
  }
  rate = de;
  return e;
}

void commanded_actuators(const std::vector<ActuatorMove>& moves, const BrfdParams& params,
                         const std::vector<double>& time_s, std::vector<double>& a1,
                         std::vector<double>& a2) {
  a1.assign(time_s.size(), params.semiactive.actuator1_initial_in);
  a2.assign(time_s.size(), params.semiactive.actuator2_initial_in);
  for (const ActuatorMove& m : moves) {
    require(m.period_s > 0.0, "actuator move period_s", m.period_s, "> 0");
    for (std::size_t i = 0; i < time_s.size(); ++i) {
      const double tau = time_s[i] - m.start_s;
      if (tau < 0.0 || tau > m.period_s) continue;
      const double dx = -m.amplitude_in * std::sin(2.0 * kPi * tau / m.period_s);
      if (m.actuator1) a1[i] += dx;
      if (m.actuator2) a2[i] += dx;
    }
  }
}

}  // namespace

const std::vector<HiddenShape>& all_hidden_shapes() {
  static const std::vector<HiddenShape> all = [] {
    std::vector<HiddenShape> v;
    for (const ShapeInfo& s : kShapes) v.push_back(s.shape);
    return v;
  }();
  return all;
}

std::string to_string(HiddenShape shape) { return info(shape).name; }

HiddenShape hidden_shape_from_string(const std::string& name) {
  std::string valid;
  for (const ShapeInfo& s : kShapes) {
    if (name == s.name) return s.shape;
    valid += (valid.empty() ? "" : ", ") + std::string(s.name);
  }
  throw std::invalid_argument("unknown hidden shape '" + name + "' (valid: " + valid + ")");
}

std::string effect_family(HiddenShape shape) { return info(shape).family; }

const std::vector<std::string>& effect_families() {
  static const std::vector<std::string> f{"backlash",          "actuator_lag",    "displacement_friction",
                                          "velocity_friction", "residual_static", "viscous",
                                          "asymmetry",         "none"};
  return f;
}

std::vector<ActuatorMove> paper_harmonic_moves(int test_number, double frequency_hz) {
  if (test_number < 1 || test_number > 6)
    throw std::invalid_argument("paper harmonic test number " + std::to_string(test_number) +
                                " (Table 3 has tests 1-6)");
  const bool forward = test_number % 2 == 1;
  const bool act1 = test_number <= 2 || test_number >= 5;
  const bool act2 = test_number >= 3;
  const double amplitude = test_number >= 5 ? 0.015 : 0.03;
  const double period = 1.0 / frequency_hz;
  std::vector<ActuatorMove> moves;
  for (int k = forward ? 1 : 2; k <= (forward ? 3 : 4); ++k) {
    ActuatorMove m;
    m.start_s = (k + (forward ? 0.75 : 0.25)) * period;
    m.period_s = 0.5 * period;
    m.amplitude_in = amplitude;
    m.actuator1 = act1;
    m.actuator2 = act2;
    moves.push_back(m);
  }
  return moves;
}

void harmonic_motion(const HarmonicProfile& p, const std::vector<double>& time_s,
                     std::vector<double>& disp_in, std::vector<double>& vel_in_per_s) {
  require(p.frequency_hz > 0.0, "harmonic.frequency_hz", p.frequency_hz, "> 0");
  require(p.motion_end_s >= 2.0 / p.frequency_hz, "harmonic.motion_end_s", p.motion_end_s,
          ">= two drum periods (ramp up and down)");
  const double w = 2.0 * kPi * p.frequency_hz;
  disp_in.resize(time_s.size());
  vel_in_per_s.resize(time_s.size());
  for (std::size_t i = 0; i < time_s.size(); ++i) {
    const double t = time_s[i];
    double de;
    const double e = harmonic_envelope(p, t, de);
    disp_in[i] = p.amplitude_in * e * std::sin(w * t);
    vel_in_per_s[i] = p.amplitude_in * (de * std::sin(w * t) + e * w * std::cos(w * t));
  }
}

void earthquake_motion(const EarthquakeProfile& p, std::uint64_t seed,
                       const std::vector<double>& time_s, std::vector<double>& disp_in,
                       std::vector<double>& vel_in_per_s) {
  require(p.components >= 1, "earthquake.components", p.components, ">= 1");
  require(p.max_freq_hz > p.min_freq_hz && p.min_freq_hz > 0.0, "earthquake.max_freq_hz",
          p.max_freq_hz, "> min_freq_hz > 0");
  require(p.motion_end_s > p.strong_end_s && p.strong_end_s >= p.rise_end_s && p.rise_end_s > 0.0,
          "earthquake.motion_end_s", p.motion_end_s, "> strong_end_s >= rise_end_s > 0");
  require(p.peak_in > 0.0, "earthquake.peak_in", p.peak_in, "> 0");
  require(p.taper_s > 0.0 && p.taper_s <= p.motion_end_s - p.strong_end_s, "earthquake.taper_s",
          p.taper_s, "in (0, motion_end_s - strong_end_s]");
  std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32), 0x5eedu};
  std::mt19937_64 rng(seq);
  std::uniform_real_distribution<double> phase(0.0, 2.0 * kPi);
  const double wg = 2.0 * kPi * p.dominant_freq_hz, zg = p.ground_damping;
  const double wf = 2.0 * kPi * p.highpass_freq_hz, zf = p.highpass_damping;
  const double w0 = 2.0 * kPi * p.min_freq_hz, w1 = 2.0 * kPi * p.max_freq_hz;
  const double dw = (w1 - w0) / p.components;
  std::vector<double> amp(p.components), omega(p.components), phi(p.components);
  for (int k = 0; k < p.components; ++k) {
    const double w = w0 + (k + 0.5) * dw;
    const double w2 = w * w;
    const double kt = (wg * wg * wg * wg + 4.0 * zg * zg * wg * wg * w2) /
                      ((wg * wg - w2) * (wg * wg - w2) + 4.0 * zg * zg * wg * wg * w2);
    const double cp = w2 * w2 / ((wf * wf - w2) * (wf * wf - w2) + 4.0 * zf * zf * wf * wf * w2);
    omega[k] = w;
    amp[k] = std::sqrt(2.0 * kt * cp * dw);
    phi[k] = phase(rng);
  }
  disp_in.assign(time_s.size(), 0.0);
  vel_in_per_s.assign(time_s.size(), 0.0);
  double peak = 0.0;
  for (std::size_t i = 0; i < time_s.size(); ++i) {
    const double t = time_s[i];
    double de;
    const double e = earthquake_envelope(p, t, de);
    if (e == 0.0 && de == 0.0) continue;
    double s = 0.0, ds = 0.0;
    for (int k = 0; k < p.components; ++k) {
      const double ph = omega[k] * t + phi[k];
      s += amp[k] * std::cos(ph);
      ds -= amp[k] * omega[k] * std::sin(ph);
    }
    disp_in[i] = e * s;
    vel_in_per_s[i] = de * s + e * ds;
    peak = std::max(peak, std::abs(disp_in[i]));
  }
  const double scale = peak > 0.0 ? p.peak_in / peak : 0.0;
  // Residual drift: a smooth step (3u² - 2u³) of residual_drift_in over the taper, held after.
  const double t0 = p.motion_end_s - p.taper_s;
  for (std::size_t i = 0; i < time_s.size(); ++i) {
    disp_in[i] *= scale;
    vel_in_per_s[i] *= scale;
    const double u = std::clamp((time_s[i] - t0) / p.taper_s, 0.0, 1.0);
    disp_in[i] += p.residual_drift_in * u * u * (3.0 - 2.0 * u);
    if (u > 0.0 && u < 1.0) vel_in_per_s[i] += p.residual_drift_in * 6.0 * u * (1.0 - u) / p.taper_s;
  }
}

SecondOrderActuator::SecondOrderActuator(double natural_freq_hz, double damping_ratio,
                                         double initial_in)
    : wn_(2.0 * kPi * natural_freq_hz), zeta_(damping_ratio), x_(initial_in) {
  require(natural_freq_hz > 0.0, "actuator_second_order.natural_freq_hz", natural_freq_hz, "> 0");
  require(damping_ratio > 0.0, "actuator_second_order.damping_ratio", damping_ratio, "> 0");
}

double SecondOrderActuator::step(double command_in, double dt_s) {
  constexpr int kSub = 8;
  const double h = dt_s / kSub;
  auto acc = [&](double x, double v) {
    return wn_ * wn_ * (command_in - x) - 2.0 * zeta_ * wn_ * v;
  };
  for (int s = 0; s < kSub; ++s) {
    const double k1x = v_, k1v = acc(x_, v_);
    const double k2x = v_ + 0.5 * h * k1v, k2v = acc(x_ + 0.5 * h * k1x, v_ + 0.5 * h * k1v);
    const double k3x = v_ + 0.5 * h * k2v, k3v = acc(x_ + 0.5 * h * k2x, v_ + 0.5 * h * k2v);
    const double k4x = v_ + h * k3v, k4v = acc(x_ + h * k3x, v_ + h * k3v);
    x_ += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
    v_ += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
  }
  return x_;
}

SyntheticTest generate_synthetic_test(const BrfdParams& params, const SyntheticSpec& spec) {
  require(spec.dt_s > 0.0 && spec.dt_s <= 0.01, "dt_s", spec.dt_s, "in (0, 0.01]");
  require(spec.noise_std_kip >= 0.0, "noise_std_kip", spec.noise_std_kip, ">= 0");
  require(spec.effect.strength_scale >= 0.0, "effect.strength_scale", spec.effect.strength_scale,
          ">= 0");
  const bool harmonic = spec.motion == SyntheticSpec::Motion::harmonic;
  const double duration = harmonic ? spec.harmonic.duration_s : spec.earthquake.duration_s;
  const double motion_end = harmonic ? spec.harmonic.motion_end_s : spec.earthquake.motion_end_s;
  require(duration >= motion_end, "duration_s", duration, ">= motion_end_s");

  SyntheticTest out;
  out.shape = spec.effect.shape;
  out.label = effect_family(spec.effect.shape);
  BrfdTest& t = out.test;
  t.path = spec.name + ".json";
  t.dt_s = spec.dt_s;
  t.has_actuator_positions = true;
  t.velocity_derived = false;
  t.velocity_column_ratio = 1.0;
  const std::size_t n = static_cast<std::size_t>(std::llround(duration / spec.dt_s)) + 1;
  t.time_s.resize(n);
  for (std::size_t i = 0; i < n; ++i) t.time_s[i] = static_cast<double>(i) * spec.dt_s;
  if (harmonic) {
    harmonic_motion(spec.harmonic, t.time_s, t.drum_disp_in, t.drum_vel_in_per_s);
    commanded_actuators(spec.harmonic.moves, params, t.time_s, t.actuator1_in, t.actuator2_in);
  } else {
    earthquake_motion(spec.earthquake, spec.seed, t.time_s, t.drum_disp_in, t.drum_vel_in_per_s);
    commanded_actuators(spec.earthquake.moves, params, t.time_s, t.actuator1_in, t.actuator2_in);
  }
  t.notes.push_back("synthetic test (damper/synthetic): hidden effect withheld, seed " +
                    std::to_string(spec.seed));

  // Effective actuator positions (what tensions the bands).
  const HiddenEffect& fx = spec.effect;
  const double g = fx.strength_scale;
  out.actuator1_effective_in = t.actuator1_in;
  out.actuator2_effective_in = t.actuator2_in;
  if (fx.shape == HiddenShape::actuator_second_order) {
    const double fn = fx.actuator_second_order.natural_freq_hz / std::max(g, 1e-9);
    SecondOrderActuator f1(fn, fx.actuator_second_order.damping_ratio, t.actuator1_in[0]);
    SecondOrderActuator f2(fn, fx.actuator_second_order.damping_ratio, t.actuator2_in[0]);
    for (std::size_t i = 1; i < n; ++i) {
      out.actuator1_effective_in[i] = f1.step(t.actuator1_in[i], t.dt_s);
      out.actuator2_effective_in[i] = f2.step(t.actuator2_in[i], t.dt_s);
    }
  } else if (fx.shape == HiddenShape::actuator_delay) {
    const double delay = fx.actuator_delay.delay_s * g;
    require(delay >= 0.0, "actuator_delay.delay_s", delay, ">= 0");
    for (std::size_t i = 0; i < n; ++i) {
      const double k = (t.time_s[i] - delay) / t.dt_s;  // fractional sample index
      if (k <= 0.0) {
        out.actuator1_effective_in[i] = t.actuator1_in[0];
        out.actuator2_effective_in[i] = t.actuator2_in[0];
        continue;
      }
      const std::size_t k0 = static_cast<std::size_t>(k);
      const double a = k - static_cast<double>(k0);
      const std::size_t k1 = std::min(k0 + 1, n - 1);
      out.actuator1_effective_in[i] = (1 - a) * t.actuator1_in[k0] + a * t.actuator1_in[k1];
      out.actuator2_effective_in[i] = (1 - a) * t.actuator2_in[k0] + a * t.actuator2_in[k1];
    }
  }

  const std::vector<double>& a1r = t.actuator1_in;
  const std::vector<double>& a2r = t.actuator2_in;
  const std::vector<double>& a1e = out.actuator1_effective_in;
  const std::vector<double>& a2e = out.actuator2_effective_in;
  const double f0 = spec.initial_force_kip;
  out.base_force_kip = run_model(params, f0, t, a1r, a2r);

  switch (fx.shape) {
    case HiddenShape::none:
      out.clean_force_kip = out.base_force_kip;
      break;
    case HiddenShape::actuator_second_order:
    case HiddenShape::actuator_delay:
      out.clean_force_kip = run_model(params, f0, t, a1e, a2e);
      break;
    case HiddenShape::backlash: {
      BacklashShape s = fx.backlash;
      s.free_travel_in *= g;
      require(s.free_travel_in > 0.0, "backlash.free_travel_in", s.free_travel_in, "> 0");
      require(s.contact_travel_in > 0.0, "backlash.contact_travel_in", s.contact_travel_in, "> 0");
      require(s.unload_travel_in > 0.0, "backlash.unload_travel_in", s.unload_travel_in, "> 0");
      s.unload_travel_in = std::min(s.unload_travel_in, s.free_travel_in);
      out.clean_force_kip = backlash_force(params, s, f0, t, a1r, a2r);
      break;
    }
    case HiddenShape::displacement_friction: {
      const DisplacementFrictionShape& s = fx.displacement_friction;
      const double k = s.gain_per_in_p * g;
      require(k > -1.0, "displacement_friction.gain_per_in_p", k, "> -1");
      require(s.exponent > 0.0, "displacement_friction.exponent", s.exponent, "> 0");
      out.clean_force_kip = run_model(
          [&](std::size_t i) {
            const double phi = std::max(0.05, 1.0 + k * std::pow(std::abs(t.drum_disp_in[i]), s.exponent));
            return scaled_friction(params, phi, phi);
          },
          f0, t, a1r, a2r);
      break;
    }
    case HiddenShape::velocity_friction: {
      const VelocityFrictionShape& s = fx.velocity_friction;
      require(s.ref_speed_in_per_s > 0.0, "velocity_friction.ref_speed_in_per_s", s.ref_speed_in_per_s, "> 0");
      require(s.memory_length_in > 0.0, "velocity_friction.memory_length_in", s.memory_length_in, "> 0");
      require(s.speed_floor_in_per_s > 0.0, "velocity_friction.speed_floor_in_per_s",
              s.speed_floor_in_per_s, "> 0");
      const double a = s.a * g, b = s.b_rs * g;
      std::vector<double> phi(n);
      double theta = s.memory_length_in / s.ref_speed_in_per_s;  // steady state at v0: φ = 1
      for (std::size_t i = 0; i < n; ++i) {
        const double vs = std::abs(t.drum_vel_in_per_s[i]) + s.speed_floor_in_per_s;
        if (i > 0) {  // aging law, exact for a held speed: θ → D_c/v*
          const double th_ss = s.memory_length_in / vs;
          theta = th_ss + (theta - th_ss) * std::exp(-vs * t.dt_s / s.memory_length_in);
        }
        const double f = 1.0 + a * std::log(vs / s.ref_speed_in_per_s) +
                         b * std::log(s.ref_speed_in_per_s * theta / s.memory_length_in);
        phi[i] = std::clamp(f, 0.2, 3.0);
      }
      out.clean_force_kip = run_model(
          [&](std::size_t i) { return scaled_friction(params, phi[i], phi[i]); }, f0, t, a1r, a2r);
      break;
    }
    case HiddenShape::residual_static: {
      ResidualStaticShape s = fx.residual_static;
      s.relaxed_fraction *= g;
      require(s.relaxed_fraction >= 0.0 && s.relaxed_fraction <= 1.0, "residual_static.relaxed_fraction",
              s.relaxed_fraction, "in [0, 1]");
      require(s.time_constant_s > 0.0, "residual_static.time_constant_s", s.time_constant_s, "> 0");
      require(s.rest_speed_in_per_s > 0.0, "residual_static.rest_speed_in_per_s", s.rest_speed_in_per_s, "> 0");
      require(s.wipe_travel_in > 0.0, "residual_static.wipe_travel_in", s.wipe_travel_in, "> 0");
      out.clean_force_kip = residual_static_force(out.base_force_kip, s, t);
      break;
    }
    case HiddenShape::viscous: {
      const ViscousShape& s = fx.viscous;
      require(s.exponent > 0.0, "viscous.exponent", s.exponent, "> 0");
      const double c = s.coefficient_kip_s_per_in * g;
      out.clean_force_kip = out.base_force_kip;
      for (std::size_t i = 0; i < n; ++i) {
        const double v = t.drum_vel_in_per_s[i];
        out.clean_force_kip[i] += c * std::pow(std::abs(v), s.exponent) * (v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0));
      }
      break;
    }
    case HiddenShape::asymmetry: {
      const double al = fx.asymmetry.fraction * g;
      require(al > -1.0 && al < 1.0, "asymmetry.fraction", al, "in (-1, 1)");
      out.clean_force_kip = run_model(scaled_friction(params, 1.0 + al, 1.0 - al), f0, t, a1r, a2r);
      break;
    }
  }

  // Measured force: clean + seeded Gaussian noise.
  std::mt19937_64 rng(spec.seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  t.force_kip.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    t.force_kip[i] = out.clean_force_kip[i] + spec.noise_std_kip * noise(rng);

  // Band tensions from the paper's scaling factors (Table 2), lb.
  const auto& c = params.semiactive.scaling;
  t.actuator1_force_lb.resize(n);
  t.actuator2_force_lb.resize(n);
  bool forward = true;
  for (std::size_t i = 0; i < n; ++i) {
    if (t.drum_vel_in_per_s[i] != 0.0) forward = t.drum_vel_in_per_s[i] > 0.0;
    const double f = std::abs(out.clean_force_kip[i]) * 1000.0;
    t.actuator1_force_lb[i] = f / (forward ? c[0] : c[2]);
    t.actuator2_force_lb[i] = f / (forward ? c[1] : c[3]);
  }
  return out;
}

void write_measured_json(const BrfdTest& test, const std::string& path) {
  if (!test.has_actuator_positions || test.actuator1_in.size() != test.size() ||
      test.actuator2_in.size() != test.size() || test.actuator1_force_lb.size() != test.size() ||
      test.actuator2_force_lb.size() != test.size())
    throw std::invalid_argument(path + ": write_measured_json needs the 8-column semi-active fields");
  nlohmann::json doc;
  nlohmann::json data = nlohmann::json::array();
  for (std::size_t i = 0; i < test.size(); ++i)
    data.push_back({test.time_s[i], test.drum_disp_in[i], test.force_kip[i], test.drum_vel_in_per_s[i],
                    test.actuator1_in[i], test.actuator2_in[i], test.actuator1_force_lb[i],
                    test.actuator2_force_lb[i]});
  doc["data"] = std::move(data);
  doc["dt"] = test.dt_s;
  const double fs = 1.0 / test.dt_s;
  if (fs == std::round(fs))
    doc["sampling freq"] = static_cast<long long>(fs);  // 1024, an integer as in the lab files
  else
    doc["sampling freq"] = fs;
  doc["displacement units"] = "in";
  doc["time units"] = "s";
  doc["friction force units"] = "kip";
  doc["actuator force units"] = "lb";
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open for writing");
  out << doc.dump();
  out.close();
  if (!out) throw std::runtime_error(path + ": write failed");
}

void write_truth_json(const SyntheticTest& test, const SyntheticSpec& spec, const std::string& path) {
  nlohmann::json doc;
  doc["label"] = test.label;
  doc["shape"] = to_string(test.shape);
  doc["seed"] = spec.seed;
  doc["noise_std_kip"] = spec.noise_std_kip;
  doc["strength_scale"] = spec.effect.strength_scale;
  doc["motion"] = spec.motion == SyntheticSpec::Motion::harmonic ? "harmonic" : "earthquake";
  doc["measured_file"] = test.test.path;
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open for writing");
  out << doc.dump(2) << "\n";
  out.close();
  if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace damper::synthetic
