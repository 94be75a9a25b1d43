#include "damper/diagnose/diagnose_fit.h"

#include <nlopt.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <cstdlib>

namespace damper {

BrfdParams for_record(BrfdParams p, const BrfdTest& t) {
  if (t.has_actuator_positions) {
    p.semiactive.actuator1_initial_in = t.actuator1_in[0];
    p.semiactive.actuator2_initial_in = t.actuator2_in[0];
  }
  return p;
}

double effective_sample_count(const std::vector<double>& r) {
  const std::size_t n = r.size();
  if (n < 4) return static_cast<double>(n);
  double mean = 0.0;
  for (double x : r) mean += x;
  mean /= static_cast<double>(n);
  double c0 = 0.0;
  for (double x : r) c0 += (x - mean) * (x - mean);
  if (!(c0 > 0.0)) return static_cast<double>(n);
  double tau = 1.0;
  const std::size_t max_lag = n / 4;
  for (std::size_t k = 1; k < max_lag; ++k) {
    double c = 0.0;
    for (std::size_t i = 0; i + k < n; ++i) c += (r[i] - mean) * (r[i + k] - mean);
    const double rho = c / c0;
    if (rho <= 0.0) break;
    tau += 2.0 * rho;
  }
  return std::max(1.0, static_cast<double>(n) / tau);
}

// Every k-th sample of a record, for the effect fits (the model's exact step handles the longer
// sample period; the final before/after numbers use the full rate).
DiagnoseRecord decimate(const DiagnoseRecord& r, std::size_t k) {
  if (k <= 1) return r;
  auto pick = [k](const std::vector<double>& x) {
    std::vector<double> y;
    for (std::size_t i = 0; i < x.size(); i += k) y.push_back(x[i]);
    return y;
  };
  DiagnoseRecord d;
  d.test.path = r.test.path;
  d.test.dt_s = r.test.dt_s * static_cast<double>(k);
  d.test.time_s = pick(r.test.time_s);
  d.test.drum_disp_in = pick(r.test.drum_disp_in);
  d.test.drum_vel_in_per_s = pick(r.test.drum_vel_in_per_s);
  d.test.force_kip = pick(r.test.force_kip);
  d.test.actuator1_in = pick(r.test.actuator1_in);
  d.test.actuator2_in = pick(r.test.actuator2_in);
  d.test.actuator1_force_lb = pick(r.test.actuator1_force_lb);
  d.test.actuator2_force_lb = pick(r.test.actuator2_force_lb);
  d.test.has_actuator_positions = r.test.has_actuator_positions;
  d.test.velocity_derived = r.test.velocity_derived;
  d.seg = r.seg;
  d.seg.train.clear();
  d.seg.regime.clear();
  d.seg.actuators_moving.clear();
  for (std::size_t i = 0; i < r.test.size(); i += k) {
    d.seg.train.push_back(r.seg.train[i]);
    d.seg.regime.push_back(r.seg.regime[i]);
    if (!r.seg.actuators_moving.empty()) d.seg.actuators_moving.push_back(r.seg.actuators_moving[i]);
  }
  auto scale = [k](std::size_t i) { return (i + k - 1) / k; };
  d.seg.passive_end = scale(r.seg.passive_end);
  d.seg.rest_begin = scale(r.seg.rest_begin);
  for (Segmentation::Rest& x : d.seg.rests) {
    x.begin = scale(x.begin);
    x.end = scale(x.end);
  }
  for (std::size_t& x : d.seg.reversals) x = x / k;
  for (Segmentation::Span& sp : d.seg.spans) {
    sp.begin = scale(sp.begin);
    sp.end = scale(sp.end);
  }
  return d;
}

std::vector<double> simulate(const BrfdParams& p, const BrfdTest& t) { return replay_force_kip(p, t, 0, t.size()); }

namespace {

double to_value(const EffectParameter& p, double u) {
  if (!(p.hi > p.lo)) return p.lo;  // a pinned parameter
  u = std::clamp(u, 0.0, 1.0);
  if (p.log_scale) return std::pow(10.0, std::log10(p.lo) + u * (std::log10(p.hi) - std::log10(p.lo)));
  return p.lo + u * (p.hi - p.lo);
}
double to_unit(const EffectParameter& p, double v) {
  if (!(p.hi > p.lo)) return 0.0;  // a pinned parameter
  v = std::clamp(v, p.lo, p.hi);
  if (p.log_scale) return (std::log10(v) - std::log10(p.lo)) / (std::log10(p.hi) - std::log10(p.lo));
  return (v - p.lo) / (p.hi - p.lo);
}

}  // namespace

std::size_t FitSpace::dim() const {
  std::size_t n = 0;
  for (const EffectSpec* s : specs) n += s->parameters.size();
  return n;
}

ModelEffects FitSpace::apply(ModelEffects e, const std::vector<double>& u) const {
  std::size_t k = 0;
  for (const EffectSpec* s : specs) {
    std::vector<double> theta;
    for (const EffectParameter& p : s->parameters) theta.push_back(to_value(p, u[k++]));
    s->set(e, theta);
  }
  return e;
}

std::vector<double> FitSpace::unit_of(const ModelEffects& e, bool use_start) const {
  std::vector<double> u;
  for (const EffectSpec* s : specs) {
    const bool have = s->present(e);
    const std::vector<double> theta = have ? s->get(e) : std::vector<double>{};
    for (std::size_t j = 0; j < s->parameters.size(); ++j) {
      const EffectParameter& p = s->parameters[j];
      u.push_back(to_unit(p, have ? theta[j] : (use_start ? p.start : p.null_value)));
    }
  }
  return u;
}

LugreParams refit_base(const DiagnoseRecord& r, const BrfdParams& start, int evals, const IdentificationOptions& base) {
  IdentificationOptions io = base;
  io.t0_s = r.test.time_s.front();
  io.t1_s = r.seg.passive_end < r.test.size() ? r.test.time_s[r.seg.passive_end] : r.test.time_s.back() + r.test.dt_s;
  io.global_max_evals = 0;
  io.global_runs = 0;
  io.local_max_evals = evals;
  if (!window_does_not_identify(r.test, start, io).empty()) return start.lugre;  // kept, as record_base
  return identify_lugre(r.test, start, io).params.lugre;
}

namespace {

// Fitting SSE of the effect parameters u (base fixed). Only strict improvements move the best.
struct EffectObjective {
  const std::vector<DiagnoseRecord>* recs;
  const std::vector<std::vector<std::uint8_t>>* mask;
  const FitSpace* space;
  ModelState start;
  int evaluations = 0;
  double best = INFINITY;
  std::vector<double> best_u;

  double operator()(const std::vector<double>& u) {
    ModelState trial = start;
    trial.effects = space->apply(start.effects, u);
    double se = 0.0;
    for (std::size_t k = 0; k < recs->size(); ++k) {
      const std::vector<std::uint8_t>& m = (*mask)[k];
      if (std::find(m.begin(), m.end(), 1) == m.end()) continue;
      const std::vector<double> pred = simulate(trial.params(k), (*recs)[k].test);
      const std::vector<double>& f = (*recs)[k].test.force_kip;
      for (std::size_t i = 0; i < f.size(); ++i)
        if (m[i]) se += (pred[i] - f[i]) * (pred[i] - f[i]);
      ++evaluations;
    }
    if (!std::isfinite(se)) se = 1e30;
    if (se < best) {
      best = se;
      best_u = u;
    }
    return se;
  }
};

double effect_objective(const std::vector<double>& u, std::vector<double>& /*grad*/, void* data) {
  return (*static_cast<EffectObjective*>(data))(u);
}

void bobyqa(EffectObjective& obj, std::vector<double> u, int max_evals) {
  const std::size_t n = u.size();
  nlopt::opt opt(nlopt::LN_BOBYQA, static_cast<unsigned>(n));
  opt.set_lower_bounds(std::vector<double>(n, 0.0));
  opt.set_upper_bounds(std::vector<double>(n, 1.0));
  opt.set_min_objective(effect_objective, &obj);
  opt.set_maxeval(max_evals);
  opt.set_xtol_abs(1e-4);
  opt.set_ftol_rel(1e-7);
  for (double& x : u) x = std::clamp(x, 0.0, 1.0);
  std::vector<double> step(n);
  for (std::size_t k = 0; k < n; ++k) step[k] = std::clamp(0.5 * std::max(u[k], 1.0 - u[k]), 0.02, 0.2);
  opt.set_initial_step(step);
  double f = 0.0;
  try {
    opt.optimize(u, f);
  } catch (const nlopt::roundoff_limited&) {
  } catch (const nlopt::forced_stop&) {
  } catch (const std::invalid_argument&) {
  }
}

}  // namespace

namespace {

// The fit procedure from one start (fit_model's file comment in diagnose_fit.h).
ModelState fit_from(const std::vector<DiagnoseRecord>& recs, const ModelState& start, const FitSpace& space,
                    const std::vector<std::vector<std::uint8_t>>& mask, const FitSettings& settings, int* evaluations) {
  ModelState state = start;
  int evals = 0;
  IdentificationOptions io;
  for (int it = 0; it < std::max(1, settings.iterations); ++it) {
    if (space.dim() > 0 && settings.effect_evals > 0) {
      EffectObjective obj{&recs, &mask, &space, state, 0, INFINITY, {}};
      // LN_BOBYQA's quadratic model needs more points in more dimensions: the budget per start is
      // effect_evals for up to 2 parameters and grows in proportion to the dimension beyond.
      const int budget = static_cast<int>(std::lround(settings.effect_evals * std::max(1.0, 0.5 * space.dim())));
      const std::vector<double> u0 = space.unit_of(state.effects, false);
      obj(u0);  // the start (null values, or the previous iteration's) is the reference
      if (it == 0 && settings.scan) {
        // Space-filling scan (the typical values and 6 + 4 dim Halton points, the effects already
        // in the model held at their values) and an axis scan, then LN_BOBYQA from the best point
        // and from the start.
        const std::vector<double> typical = space.unit_of(state.effects, true);
        std::vector<double> best_scan = typical;
        double best_value = obj(typical);
        static const int primes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37};
        const int points = 6 + 4 * static_cast<int>(space.dim());
        for (int q = 1; q <= points; ++q) {
          std::vector<double> u = u0;
          for (std::size_t j = 0; j < u.size() && j < 12; ++j) {
            double h = 0.0, f = 1.0;
            for (int i = q; i > 0; i /= primes[j]) {
              f /= primes[j];
              h += f * (i % primes[j]);
            }
            u[j] = h;
          }
          const double v = obj(u);
          if (v < best_value) {
            best_value = v;
            best_scan = u;
          }
        }
        // One parameter at a time from the start, four levels across its range: a missing effect
        // of another shape often lies near one axis of a family (one exponent, one share), which
        // a space-filling scan in several dimensions samples sparsely.
        for (std::size_t j = 0; j < u0.size(); ++j)
          for (double level : {0.125, 0.375, 0.625, 0.875}) {
            if (std::abs(level - u0[j]) < 0.05) continue;
            std::vector<double> u = u0;
            u[j] = level;
            const double v = obj(u);
            if (v < best_value) {
              best_value = v;
              best_scan = u;
            }
          }
        bobyqa(obj, best_scan, budget);
      }
      bobyqa(obj, u0, budget);
      state.effects = space.apply(state.effects, obj.best_u);
      evals += obj.evaluations;
    }
    if (settings.base == BaseSource::identify && settings.base_refit_evals > 0) {
      for (std::size_t k = 0; k < recs.size(); ++k) {
        state.bases[k].lugre = refit_base(recs[k], state.params(k), settings.base_refit_evals, io);
        evals += settings.base_refit_evals;
      }
    }
  }
  if (evaluations) *evaluations += evals;
  return state;
}

// Squared error over the fitting samples and every record's passive window (where its base is
// identified): what the two starts of fit_model are compared on.
double fit_and_passive_sse(const std::vector<DiagnoseRecord>& recs, const ModelState& state,
                           const std::vector<std::vector<std::uint8_t>>& mask) {
  double se = 0.0;
  for (std::size_t k = 0; k < recs.size(); ++k) {
    const std::vector<double> pred = simulate(state.params(k), recs[k].test);
    const std::vector<double>& f = recs[k].test.force_kip;
    for (std::size_t i = 0; i < f.size(); ++i)
      if (i < recs[k].seg.passive_end || (k < mask.size() && i < mask[k].size() && mask[k][i]))
        se += (pred[i] - f[i]) * (pred[i] - f[i]);
  }
  return std::isfinite(se) ? se : INFINITY;
}

bool same_lugre(const LugreParams& a, const LugreParams& b) {
  return a.sigma0_kip_per_in == b.sigma0_kip_per_in && a.sigma1_kip_s_per_in == b.sigma1_kip_s_per_in &&
         a.sigma2_kip_s_per_in == b.sigma2_kip_s_per_in && a.fs_fwd_kip == b.fs_fwd_kip && a.fs_bwd_kip == b.fs_bwd_kip &&
         a.fc_fwd_kip == b.fc_fwd_kip && a.fc_bwd_kip == b.fc_bwd_kip && a.vs_in_per_s == b.vs_in_per_s;
}

}  // namespace

ModelState fit_model(const std::vector<DiagnoseRecord>& recs, const ModelState& start, const FitSpace& space,
                     const std::vector<std::vector<std::uint8_t>>& mask, const FitSettings& settings, int* evaluations) {
  ModelState a = fit_from(recs, start, space, mask, settings, evaluations);
  if (settings.base != BaseSource::identify || !start.file_lugre || settings.base_refit_evals <= 0) return a;
  ModelState from_file = start;
  bool differs = false;
  for (BrfdParams& b : from_file.bases)
    if (!same_lugre(b.lugre, *start.file_lugre)) {
      b.lugre = *start.file_lugre;
      differs = true;
    }
  if (!differs) return a;
  ModelState b = fit_from(recs, from_file, space, mask, settings, evaluations);
  return fit_and_passive_sse(recs, b, mask) < fit_and_passive_sse(recs, a, mask) ? b : a;
}

ModelState refine_from_starts(const std::vector<DiagnoseRecord>& recs, const ModelState& fitted, const FitSpace& space,
                              const std::vector<std::vector<std::uint8_t>>& mask, const FitSettings& settings,
                              const std::vector<ModelEffects>& starts, int* evaluations) {
  if (space.dim() == 0 || starts.empty()) return fitted;
  const double own = fit_and_passive_sse(recs, fitted, mask);
  double best = own;
  ModelState from = fitted;
  for (const ModelEffects& e : starts) {
    ModelState s = fitted;
    s.effects = space.apply(fitted.effects, space.unit_of(e, false));
    const double v = fit_and_passive_sse(recs, s, mask);
    if (evaluations) ++*evaluations;
    if (v < best) {
      best = v;
      from = s;
    }
  }
  if (!(best < own)) return fitted;
  FitSettings no_scan = settings;
  no_scan.scan = false;
  ModelState refined = fit_from(recs, from, space, mask, no_scan, evaluations);
  return fit_and_passive_sse(recs, refined, mask) < own ? refined : fitted;
}

// LuGre parameters shared by all records, identified on their passive windows with the effects on
// (for model-updated.yaml in identify mode). Same search vector as identification.cc.
LugreParams joint_passive_lugre(const std::vector<DiagnoseRecord>& recs, const BrfdParams& model, const ModelEffects& e,
                                int max_evals) {
  struct Joint {
    const std::vector<DiagnoseRecord>* recs;
    BrfdParams model;
    ModelEffects effects;
    double best = INFINITY;
    LugreParams best_g;
    double operator()(const std::vector<double>& x) {
      const LugreParams g = lugre_from_search_vector(x);
      double se = 0.0;
      for (const DiagnoseRecord& r : *recs) {
        BrfdParams p = for_record(model, r.test);
        p.lugre = g;
        p.effects = effects;
        const std::size_t end = std::max<std::size_t>(2, r.seg.passive_end);
        const std::vector<double> f = replay_force_kip(p, r.test, 0, end);
        for (std::size_t i = 0; i < end; ++i) se += (f[i] - r.test.force_kip[i]) * (f[i] - r.test.force_kip[i]);
      }
      if (!std::isfinite(se)) se = 1e30;
      if (se < best) {
        best = se;
        best_g = g;
      }
      return se;
    }
  };
  // Only the records whose passive windows identify the LuGre parameters (window_does_not_identify,
  // as record_base): a window of 0.3 s at the start of a stroke fixes nothing, and a block fitted on
  // it gave an outside author's records NRMSE 0.54 where the model file's LuGre gives 0.16. None:
  // the model file's block.
  // As identify_lugre, a direction's Fs/Fc (and v_s when both) is kept at the model file's where
  // no usable window slides fast enough to show the Stribeck curve and a record goes faster later
  // (IdentificationOptions::min_stribeck_speeds).
  std::vector<DiagnoseRecord> usable;
  bool slow_fwd = true, slow_bwd = true, faster_fwd = false, faster_bwd = false;
  for (const DiagnoseRecord& r : recs) {
    const BrfdParams p = for_record(model, r.test);
    IdentificationOptions io;
    io.t0_s = r.test.time_s.front();
    io.t1_s = r.seg.passive_end < r.test.size() ? r.test.time_s[r.seg.passive_end] : r.test.time_s.back() + r.test.dt_s;
    if (!window_does_not_identify(r.test, p, io).empty()) continue;
    usable.push_back(r);
    const StribeckShown sh = stribeck_shown(r.test, 0, std::max<std::size_t>(2, r.seg.passive_end), p, io);
    slow_fwd = slow_fwd && sh.window_fwd_in_per_s < sh.shows_in_per_s;
    slow_bwd = slow_bwd && sh.window_bwd_in_per_s < sh.shows_in_per_s;
    faster_fwd = faster_fwd || sh.keep_fwd;  // slow here and faster later
    faster_bwd = faster_bwd || sh.keep_bwd;
  }
  if (usable.empty()) return model.lugre;
  Joint j{&usable, model, e, INFINITY, model.lugre};
  const LugreParams& g = model.lugre;
  const LugreBounds b;
  std::vector<double> lo = {std::log10(b.sigma0_min), b.sigma1_min, b.sigma2_min, b.fc_min,
                            b.fc_min, b.fs_ratio_min, b.fs_ratio_min, std::log10(b.vs_min)};
  std::vector<double> hi = {std::log10(b.sigma0_max), b.sigma1_max, b.sigma2_max, b.fc_max,
                            b.fc_max, b.fs_ratio_max, b.fs_ratio_max, std::log10(b.vs_max)};
  std::vector<double> x = {std::log10(g.sigma0_kip_per_in), g.sigma1_kip_s_per_in, g.sigma2_kip_s_per_in,
                           g.fc_fwd_kip, g.fc_bwd_kip, g.fs_fwd_kip / g.fc_fwd_kip, g.fs_bwd_kip / g.fc_bwd_kip,
                           std::log10(g.vs_in_per_s)};
  for (std::size_t k = 0; k < x.size(); ++k) x[k] = std::clamp(x[k], lo[k], hi[k]);
  // Kept entries: lower = upper bound (NLopt searches the other dimensions).
  const bool keep_fwd = slow_fwd && faster_fwd, keep_bwd = slow_bwd && faster_bwd;
  for (std::size_t k : {std::size_t{5}, std::size_t{6}, std::size_t{7}}) {
    if ((k == 5 && keep_fwd) || (k == 6 && keep_bwd) || (k == 7 && keep_fwd && keep_bwd)) lo[k] = hi[k] = x[k];
  }
  nlopt::opt opt(nlopt::LN_BOBYQA, 8);
  opt.set_lower_bounds(lo);
  opt.set_upper_bounds(hi);
  opt.set_min_objective(
      [](const std::vector<double>& xx, std::vector<double>&, void* d) { return (*static_cast<Joint*>(d))(xx); }, &j);
  opt.set_maxeval(max_evals);
  opt.set_xtol_rel(1e-6);
  double f = 0.0;
  try {
    opt.optimize(x, f);
  } catch (const std::exception&) {
  }
  return j.best_g;
}

}  // namespace damper
