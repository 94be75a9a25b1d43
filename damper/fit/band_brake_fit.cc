#include "damper/fit/band_brake_fit.h"

#include "damper/fit/staged_search.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace damper {

BandBrakeInput band_brake_input_at(const BrfdTest& test, std::size_t i, const BandBrakeParams& p) {
  return input_at(test, i, p.actuator1_initial_in, p.actuator2_initial_in);
}

BandBrakeReplay replay_band_brake(const BandBrakeParams& params, const BrfdTest& test,
                                  std::size_t begin, std::size_t end) {
  BandBrakeModel model(params);
  BandBrakeReplay r;
  const std::size_t n = end - begin;
  r.force_kip.resize(n);
  r.actuator1_kip.resize(n);
  r.actuator2_kip.resize(n);
  {
    const BandBrakeInput in0 = band_brake_input_at(test, begin, params);
    const BandTensions t = model.tensions(in0);
    const double f0 = std::clamp(test.force_kip[begin], -t.fc_bwd_kip, t.fc_fwd_kip);
    model.set_stretch_in(model.stretch_for_force(f0));
  }
  for (std::size_t i = begin; i < end; ++i) {
    const BandBrakeInput in = band_brake_input_at(test, i, params);
    r.force_kip[i - begin] = i == begin ? model.force_kip(model.stretch_in(), in) : model.step(in, test.dt_s);
    const std::array<double, 2> c = model.actuator_forces_kip(model.stretch_in(), in);
    r.actuator1_kip[i - begin] = c[0];
    r.actuator2_kip[i - begin] = c[1];
  }
  return r;
}

std::array<double, 4> actuator_tension_from_eq4_gains(const BandBrakeParams& p,
                                                      const std::array<double, 4>& g) {
  const double ef = BandBrakeModel::capstan_ratio(p.friction_coefficient, p.wrap_angle_fwd_rad);
  const double eb = BandBrakeModel::capstan_ratio(p.friction_coefficient, p.wrap_angle_bwd_rad);
  const double df = p.lever_ratio * (ef - 1.0), db = p.lever_ratio * (eb - 1.0);
  return {-g[0] / df, -g[1] / df, -g[2] / db, -g[3] / db};
}

namespace {

constexpr int kShared = 9;  // θf, θb, κ, L, log10 k_b, h, δ, c, log10 n

struct WindowStats {
  double force_var = 1.0, cell_var = 1.0;
};

struct Problem {
  const std::vector<FitWindow>* windows;
  std::vector<WindowStats> stats;
  BandBrakeParams start;
  const BandBrakeFitOptions* opt;
  int groups = 1;

  BandBrakeParams params_for(const std::vector<double>& x, int group) const {
    BandBrakeParams p = start;
    p.wrap_angle_fwd_rad = x[0];
    p.wrap_angle_bwd_rad = x[1];
    p.wrap_change_rad_per_in = x[2];
    p.lever_ratio = x[3];
    p.band_stiffness_kip_per_in = std::pow(10.0, x[4]);
    p.band_hardening_per_in = x[5];
    p.backlash_in = x[6];
    p.viscous_kip_s_per_in = x[7];
    p.transition_exponent = std::pow(10.0, x[8]);
    p.slack_tension_fwd_kip = std::pow(10.0, x[kShared + 2 * group]);
    p.slack_tension_bwd_kip = std::pow(10.0, x[kShared + 2 * group + 1]);
    if (opt->eq4_gains_kip_per_in) p.actuator_tension_kip_per_in = actuator_tension_from_eq4_gains(p, *opt->eq4_gains_kip_per_in);
    return p;
  }

  double cost(const std::vector<double>& x) {
    double total = 0.0;
    const std::vector<FitWindow>& w = *windows;
    for (std::size_t k = 0; k < w.size(); ++k) {
      BandBrakeParams p = params_for(x, groups == 1 ? 0 : static_cast<int>(k));
      p.slack_tension_fwd_kip *= w[k].pretension_scale;
      p.slack_tension_bwd_kip *= w[k].pretension_scale;
      const BandBrakeReplay r = replay_band_brake(p, *w[k].test, w[k].begin, w[k].end);
      double se = 0.0, sc = 0.0;
      for (std::size_t i = w[k].begin; i < w[k].end; ++i) {
        const double e = r.force_kip[i - w[k].begin] - w[k].test->force_kip[i];
        se += e * e;
        const double e1 = r.actuator1_kip[i - w[k].begin] - 1e-3 * w[k].test->actuator1_force_lb[i];
        const double e2 = r.actuator2_kip[i - w[k].begin] - 1e-3 * w[k].test->actuator2_force_lb[i];
        sc += 0.5 * (e1 * e1 + e2 * e2);
      }
      const double n = static_cast<double>(w[k].end - w[k].begin);
      total += se / n / stats[k].force_var + opt->cell_weight * sc / n / stats[k].cell_var;
    }
    return total / static_cast<double>(w.size());
  }
};

double variance(const std::vector<double>& v, std::size_t b, std::size_t e, double scale) {
  double s = 0.0, s2 = 0.0;
  for (std::size_t i = b; i < e; ++i) {
    s += scale * v[i];
    s2 += scale * v[i] * scale * v[i];
  }
  const double n = static_cast<double>(e - b);
  return std::max(s2 / n - (s / n) * (s / n), 1e-12);
}

}  // namespace

BandBrakeFitResult identify_band_brake(const std::vector<FitWindow>& windows,
                                       const BandBrakeParams& start, const BandBrakeFitOptions& opt) {
  if (windows.empty()) throw std::invalid_argument("band-brake identification: no data windows");
  Problem problem{&windows, {}, start, &opt, 1};
  for (const FitWindow& w : windows) {
    if (!w.test || w.end > w.test->size() || w.end < w.begin + 100)
      throw std::invalid_argument("band-brake identification: window of " +
                                  (w.test ? w.test->path : std::string("?")) + " holds fewer than 100 samples");
    WindowStats s;
    s.force_var = variance(w.test->force_kip, w.begin, w.end, 1.0);
    s.cell_var = 0.5 * (variance(w.test->actuator1_force_lb, w.begin, w.end, 1e-3) +
                        variance(w.test->actuator2_force_lb, w.begin, w.end, 1e-3));
    problem.stats.push_back(s);
  }
  problem.groups = opt.per_window_slack ? static_cast<int>(windows.size()) : 1;
  const BandBrakeBounds& b = opt.bounds;
  std::vector<double> lo = {b.wrap_min_rad, b.wrap_min_rad, -b.wrap_change_max_rad_per_in, b.lever_min,
                            std::log10(b.stiffness_min), 0.0, 0.0, 0.0, 0.0};
  std::vector<double> hi = {b.wrap_max_rad, b.wrap_max_rad, b.wrap_change_max_rad_per_in, b.lever_max,
                            std::log10(b.stiffness_max), b.hardening_max_per_in, b.backlash_max_in, b.viscous_max,
                            std::log10(b.exponent_max)};
  std::vector<double> x = {start.wrap_angle_fwd_rad, start.wrap_angle_bwd_rad, start.wrap_change_rad_per_in,
                           start.lever_ratio, std::log10(start.band_stiffness_kip_per_in),
                           start.band_hardening_per_in, start.backlash_in, start.viscous_kip_s_per_in,
                           std::log10(start.transition_exponent)};
  for (int g = 0; g < problem.groups; ++g) {
    lo.push_back(std::log10(b.slack_min_kip));
    lo.push_back(std::log10(b.slack_min_kip));
    hi.push_back(std::log10(b.slack_max_kip));
    hi.push_back(std::log10(b.slack_max_kip));
    x.push_back(std::log10(start.slack_tension_fwd_kip));
    x.push_back(std::log10(start.slack_tension_bwd_kip));
  }
  const StagedSearchResult found =
      staged_search([&problem](const std::vector<double>& x) { return problem.cost(x); }, x, lo, hi,
                    {opt.global_max_evals, opt.global_runs, opt.local_max_evals, opt.seed, 1e-9});

  BandBrakeFitResult r;
  r.params = problem.params_for(found.x, 0);
  for (int g = 0; g < problem.groups; ++g) {
    const BandBrakeParams p = problem.params_for(found.x, g);
    r.slack_per_window.push_back({p.slack_tension_fwd_kip, p.slack_tension_bwd_kip});
  }
  r.cost = found.cost;
  r.evaluations = found.evaluations;
  r.algorithm = found.algorithm;
  return r;
}

std::string describe(const BandBrakeParams& p) {
  std::ostringstream o;
  o << std::setprecision(4);
  const double ef = BandBrakeModel::capstan_ratio(p.friction_coefficient, p.wrap_angle_fwd_rad);
  const double eb = BandBrakeModel::capstan_ratio(p.friction_coefficient, p.wrap_angle_bwd_rad);
  o << "mu = " << p.friction_coefficient << ", wrap fwd/bwd = " << p.wrap_angle_fwd_rad << " / "
    << p.wrap_angle_bwd_rad << " rad (capstan ratio " << ef << " / " << eb << "), kappa = "
    << p.wrap_change_rad_per_in << " rad/in, lever = " << p.lever_ratio << ", slack tension fwd/bwd = "
    << 1e3 * p.slack_tension_fwd_kip << " / " << 1e3 * p.slack_tension_bwd_kip << " lb (Fc "
    << p.lever_ratio * p.slack_tension_fwd_kip * (ef - 1) << " / " << p.lever_ratio * p.slack_tension_bwd_kip * (eb - 1)
    << " kip), band stiffness = " << p.band_stiffness_kip_per_in << " kip/in, hardening = "
    << p.band_hardening_per_in << " /in, backlash = " << p.backlash_in << " in, viscous = "
    << p.viscous_kip_s_per_in << " kip s/in, exponent n = " << p.transition_exponent << ", actuator tension k = [" << p.actuator_tension_kip_per_in[0] << ", "
    << p.actuator_tension_kip_per_in[1] << ", " << p.actuator_tension_kip_per_in[2] << ", "
    << p.actuator_tension_kip_per_in[3] << "] kip/in";
  return o.str();
}

}  // namespace damper
