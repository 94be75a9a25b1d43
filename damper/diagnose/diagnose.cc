#include "damper/diagnose/diagnose.h"

#include "damper/model/brfd_config.h"
#include "damper/diagnose/diagnose_report.h"
#include "damper/fit/identification.h"

#include <nlopt.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace damper {

ErrorMetrics masked_error(const std::vector<double>& measured, const std::vector<double>& predicted,
                          const std::vector<std::uint8_t>& mask, std::uint8_t want) {
  ErrorMetrics m;
  double se = 0.0, sum = 0.0, sum2 = 0.0;
  double lo = INFINITY, hi = -INFINITY;
  std::size_t n = 0;
  for (std::size_t i = 0; i < measured.size(); ++i) {
    if (mask[i] != want) continue;
    const double e = predicted[i] - measured[i];
    se += e * e;
    sum += measured[i];
    sum2 += measured[i] * measured[i];
    lo = std::min(lo, measured[i]);
    hi = std::max(hi, measured[i]);
    ++n;
  }
  m.samples = n;
  if (n == 0) return m;
  const double nn = static_cast<double>(n);
  m.rmse_kip = std::sqrt(se / nn);
  const double var = std::max(0.0, sum2 / nn - (sum / nn) * (sum / nn));
  m.nrmse_std = var > 0.0 ? m.rmse_kip / std::sqrt(var) : INFINITY;
  m.nrmse_range = hi > lo ? m.rmse_kip / (hi - lo) : INFINITY;
  return m;
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

std::string diagnose_final_line(const DiagnoseResult& r) {
  std::ostringstream o;
  std::string names;
  for (const std::string& a : r.added) names += (names.empty() ? "" : ",") + a;
  o << std::setprecision(4) << "effects=" << (names.empty() ? "none" : names)
    << " nrmse_before=" << r.nrmse_before_mean << " nrmse_after=" << r.nrmse_after_mean
    << " nrmse_after_max=" << r.nrmse_after_max;
  return o.str();
}

namespace {

struct Record {
  BrfdTest test;
  Segmentation seg;
};

struct Sse {
  double train = 0.0, held = 0.0;
  std::size_t n_train = 0, n_held = 0;
  double train_rmse() const { return n_train ? std::sqrt(train / static_cast<double>(n_train)) : 0.0; }
  double held_rmse() const { return n_held ? std::sqrt(held / static_cast<double>(n_held)) : 0.0; }
};

BrfdParams with_effects(BrfdParams base, const ModelEffects& e) {
  base.effects = e;
  return base;
}

std::vector<double> simulate(const BrfdParams& p, const BrfdTest& t) { return replay_force_kip(p, t, 0, t.size()); }

void accumulate(const std::vector<double>& pred, const Record& r, Sse& s) {
  const std::vector<double>& m = r.test.force_kip;
  for (std::size_t i = 0; i < m.size(); ++i) {
    const double e = pred[i] - m[i];
    if (r.seg.train[i]) {
      s.train += e * e;
      ++s.n_train;
    } else {
      s.held += e * e;
      ++s.n_held;
    }
  }
}

// The state of the model during the selection: a base per record (LuGre from passive data,
// x'_k from the record) and the effects shared by all records.
struct ModelState {
  std::vector<BrfdParams> bases;
  ModelEffects effects;
};

Sse evaluate(const std::vector<Record>& recs, const ModelState& s, bool train_only = false) {
  Sse total;
  for (std::size_t k = 0; k < recs.size(); ++k) {
    if (train_only) {
      // Training SSE only: the held-out samples are still simulated (their inputs drive the
      // state) but their measured force is never looked at.
      const std::vector<double> pred = simulate(with_effects(s.bases[k], s.effects), recs[k].test);
      const std::vector<double>& m = recs[k].test.force_kip;
      for (std::size_t i = 0; i < m.size(); ++i) {
        if (!recs[k].seg.train[i]) continue;
        const double e = pred[i] - m[i];
        total.train += e * e;
        ++total.n_train;
      }
    } else {
      accumulate(simulate(with_effects(s.bases[k], s.effects), recs[k].test), recs[k], total);
    }
  }
  return total;
}

// Every k-th sample of a record, for the effect fits (the model's exact step handles the longer
// sample period; the final before/after numbers use the full rate).
Record decimate(const Record& r, std::size_t k) {
  if (k <= 1) return r;
  auto pick = [k](const std::vector<double>& x) {
    std::vector<double> y;
    for (std::size_t i = 0; i < x.size(); i += k) y.push_back(x[i]);
    return y;
  };
  Record d;
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
  for (std::size_t i = 0; i < r.test.size(); i += k) {
    d.seg.train.push_back(r.seg.train[i]);
    d.seg.regime.push_back(r.seg.regime[i]);
  }
  auto scale = [k](std::size_t i) { return (i + k - 1) / k; };
  d.seg.passive_end = scale(r.seg.passive_end);
  d.seg.rest_begin = scale(r.seg.rest_begin);
  for (std::size_t& x : d.seg.reversals) x = x / k;
  for (Segmentation::Span& sp : d.seg.spans) {
    sp.begin = scale(sp.begin);
    sp.end = scale(sp.end);
  }
  return d;
}

// The parameters being fitted: all parameters of a list of effects, in unit coordinates.
struct FitSpace {
  std::vector<const EffectSpec*> specs;

  std::size_t dim() const {
    std::size_t n = 0;
    for (const EffectSpec* s : specs) n += s->parameters.size();
    return n;
  }
  static double to_value(const EffectParameter& p, double u) {
    u = std::clamp(u, 0.0, 1.0);
    if (p.log_scale) return std::pow(10.0, std::log10(p.lo) + u * (std::log10(p.hi) - std::log10(p.lo)));
    return p.lo + u * (p.hi - p.lo);
  }
  static double to_unit(const EffectParameter& p, double v) {
    v = std::clamp(v, p.lo, p.hi);
    if (p.log_scale) return (std::log10(v) - std::log10(p.lo)) / (std::log10(p.hi) - std::log10(p.lo));
    return (v - p.lo) / (p.hi - p.lo);
  }
  ModelEffects apply(ModelEffects e, const std::vector<double>& u) const {
    std::size_t k = 0;
    for (const EffectSpec* s : specs) {
      std::vector<double> theta;
      for (const EffectParameter& p : s->parameters) theta.push_back(to_value(p, u[k++]));
      s->set(e, theta);
    }
    return e;
  }
  std::vector<double> unit_of(const ModelEffects& e) const {
    std::vector<double> u;
    for (const EffectSpec* s : specs) {
      const std::vector<double> theta = s->present(e) ? s->get(e) : std::vector<double>{};
      for (std::size_t j = 0; j < s->parameters.size(); ++j) {
        const EffectParameter& p = s->parameters[j];
        u.push_back(to_unit(p, theta.empty() ? p.null_value : theta[j]));
      }
    }
    return u;
  }
  std::vector<double> unit_of_start(const ModelEffects& e, bool use_start) const {
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
};

// Re-identifies the LuGre parameters of a record on its passive window with the effects on
// (local LN_BOBYQA from `start`). Passive data only.
LugreParams refit_base(const Record& r, const BrfdParams& start, int evals, const DiagnoseOptions& o) {
  IdentificationOptions io = o.base_identification;
  io.t0_s = r.test.time_s.front();
  io.t1_s = r.seg.passive_end < r.test.size() ? r.test.time_s[r.seg.passive_end] : r.test.time_s.back() + r.test.dt_s;
  io.global_max_evals = 0;
  io.local_max_evals = evals;
  return identify_lugre(r.test, start, io).params.lugre;
}

// True if the effects change the model's force on the record's passive window (then the base
// must be re-identified with them).
bool changes_passive_window(const Record& r, const BrfdParams& base, const ModelEffects& a, const ModelEffects& b) {
  const std::size_t end = std::max<std::size_t>(2, std::min(r.seg.passive_end, r.test.size()));
  const std::vector<double> fa = replay_force_kip(with_effects(base, a), r.test, 0, end);
  const std::vector<double> fb = replay_force_kip(with_effects(base, b), r.test, 0, end);
  for (std::size_t i = 0; i < end; ++i)
    if (std::abs(fa[i] - fb[i]) > 1e-9) return true;
  return false;
}

// Training SSE as a function of the effect parameters. In identify mode every trial re-identifies
// each record's base on its passive window with the trial effects (nested, deterministic: always
// from the same starting base), so the base never sees actuated or held-out samples.
struct Objective {
  const std::vector<Record>* recs;
  const FitSpace* space;
  const DiagnoseOptions* options;
  ModelState start;  // bases to start from; effects not fitted here
  int evaluations = 0;
  double best = INFINITY;
  std::vector<double> best_u;
  ModelState best_state;

  double operator()(const std::vector<double>& u) {
    ModelState trial = start;
    trial.effects = space->apply(start.effects, u);
    if (options->base == BaseSource::identify) {
      for (std::size_t k = 0; k < recs->size(); ++k) {
        if (changes_passive_window((*recs)[k], start.bases[k], start.effects, trial.effects))
          trial.bases[k].lugre = refit_base((*recs)[k], with_effects(start.bases[k], trial.effects),
                                            options->base_refit_evals, *options);
      }
    }
    const Sse s = evaluate(*recs, trial, true);
    ++evaluations;
    const double v = std::isfinite(s.train) ? s.train : 1e30;
    if (v < best) {
      best = v;
      best_u = u;
      best_state = trial;
    }
    return v;
  }
};

double nlopt_objective(const std::vector<double>& u, std::vector<double>& /*grad*/, void* data) {
  return (*static_cast<Objective*>(data))(u);
}

void bobyqa(Objective& obj, std::vector<double> u, int max_evals) {
  const std::size_t n = u.size();
  nlopt::opt opt(nlopt::LN_BOBYQA, static_cast<unsigned>(n));
  opt.set_lower_bounds(std::vector<double>(n, 0.0));
  opt.set_upper_bounds(std::vector<double>(n, 1.0));
  opt.set_min_objective(nlopt_objective, &obj);
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

struct FitOutcome {
  ModelState state;
  int evaluations = 0;
};

// Fits the parameters of `space` on the training samples, LN_BOBYQA from each start.
FitOutcome fit_space(const std::vector<Record>& recs, const ModelState& start, const FitSpace& space,
                     const std::vector<std::vector<double>>& starts, int evals, const DiagnoseOptions& o) {
  Objective obj{&recs, &space, &o, start, 0, INFINITY, {}, start};
  for (const std::vector<double>& u0 : starts) bobyqa(obj, u0, evals);
  FitOutcome out;
  out.state = obj.best_state;
  out.evaluations = obj.evaluations;
  return out;
}

std::vector<double> heldout_residual(const std::vector<double>& pred, const Record& r) {
  std::vector<double> out;
  for (std::size_t i = 0; i < pred.size(); ++i)
    if (!r.seg.train[i]) out.push_back(pred[i] - r.test.force_kip[i]);
  return out;
}

// LuGre parameters shared by all records, identified on their passive windows with the effects on
// (for model-updated.yaml in identify mode). Same search vector as identification.cc.
LugreParams joint_passive_lugre(const std::vector<Record>& recs, const BrfdParams& model, const ModelEffects& e,
                                int max_evals) {
  struct Joint {
    const std::vector<Record>* recs;
    BrfdParams model;
    ModelEffects effects;
    double best = INFINITY;
    LugreParams best_g;
    double operator()(const std::vector<double>& x) {
      const LugreParams g = lugre_from_search_vector(x);
      double se = 0.0;
      for (const Record& r : *recs) {
        BrfdParams p = model;
        p.lugre = g;
        p.effects = effects;
        if (r.test.has_actuator_positions) {
          p.semiactive.actuator1_initial_in = r.test.actuator1_in[0];
          p.semiactive.actuator2_initial_in = r.test.actuator2_in[0];
        }
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
  Joint j{&recs, model, e, INFINITY, model.lugre};
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

std::string fmt(double v, int prec = 4) {
  std::ostringstream o;
  o << std::setprecision(prec) << v;
  return o.str();
}

}  // namespace

DiagnoseResult run_diagnose(const DiagnoseOptions& o) {
  std::vector<std::string> lines;
  auto log = [&](const std::string& s) {
    lines.push_back(s);
    if (o.log) o.log(s);
  };
  DiagnoseResult result;
  const BrfdParams model = o.model_path.empty() ? BrfdParams{} : load_brfd_params(o.model_path);
  result.initial_effects = model.effects;

  // Candidates.
  std::vector<const EffectSpec*> library;
  if (o.candidates.empty()) {
    for (const EffectSpec& s : effect_library()) library.push_back(&s);
  } else {
    for (const std::string& name : o.candidates) library.push_back(&effect_spec(name));
  }

  // 1. Records, split, regimes, base parameters from passive data.
  std::vector<Record> recs;
  ModelState before;
  before.effects = model.effects;
  for (const std::string& path : expand_measured_paths(o.measured)) {
    Record r;
    r.test = read_measured_record(path, o.read);
    for (const std::string& n : r.test.notes) log(n);
    if (r.test.has_actuator_positions && o.actuator_smoothing_s > 0.0) {
      const int hw = static_cast<int>(std::lround(0.5 * o.actuator_smoothing_s / r.test.dt_s));
      if (hw > 0) {
        r.test.actuator1_in = centered_moving_average(r.test.actuator1_in, hw);
        r.test.actuator2_in = centered_moving_average(r.test.actuator2_in, hw);
      }
    }
    r.seg = segment_record(r.test, o.segmentation);
    BrfdParams base = model;
    if (r.test.has_actuator_positions) {
      base.semiactive.actuator1_initial_in = r.test.actuator1_in[0];
      base.semiactive.actuator2_initial_in = r.test.actuator2_in[0];
    }
    const double t_passive = r.seg.passive_end < r.test.size() ? r.test.time_s[r.seg.passive_end]
                                                                : r.test.time_s.back() + r.test.dt_s;
    if (o.base == BaseSource::identify) {
      IdentificationOptions io = o.base_identification;
      io.t0_s = r.test.time_s.front();
      io.t1_s = t_passive;
      const IdentificationResult id = identify_lugre(r.test, base, io);
      base.lugre = id.params.lugre;
      log(r.test.name() + ": base LuGre identified on the passive window 0-" + fmt(t_passive) +
          " s (residual there " + fmt(id.residual.rmse_kip) + " kip RMSE)");
    }
    double train_s = 0.0, held_s = 0.0;
    for (std::uint8_t t : r.seg.train) (t ? train_s : held_s) += r.test.dt_s;
    std::ostringstream sp;
    sp << r.test.name() << ": " << r.test.size() << " samples at " << fmt(1.0 / r.test.dt_s) << " Hz, passive window 0-"
       << fmt(t_passive) << " s" << (r.seg.actuated ? " (before the first actuator motion)" : " (actuators never move)")
       << ", " << r.seg.reversals.size() << " reversals, rest from "
       << (r.seg.rest_begin < r.test.size() ? fmt(r.test.time_s[r.seg.rest_begin]) + " s" : std::string("- (none)"))
       << "; training " << fmt(train_s, 3) << " s, held-out " << fmt(held_s, 3) << " s";
    log(sp.str());
    before.bases.push_back(base);
    RecordReport rep;
    rep.name = r.test.name();
    rep.path = r.test.path;
    rep.dt_s = r.test.dt_s;
    rep.passive_end_s = t_passive;
    rep.train_s = train_s;
    rep.heldout_s = held_s;
    rep.base_params = with_effects(base, model.effects);
    result.records.push_back(rep);
    recs.push_back(std::move(r));
  }
  log(std::string("base parameters: ") +
      (o.base == BaseSource::identify ? "LuGre identified on each record's passive window (re-identified there "
                                        "whenever effects change)"
                                      : "the --model file as is (x'_1, x'_2 from each record's first row)"));
  if (!model.effects.empty()) log("the --model file already holds effects: " + model.effects.names());

  // 2. Residual of the model as it is, localized.
  std::vector<std::vector<double>> pred_before(recs.size());
  RegimeEnergy energy_all;
  for (std::size_t k = 0; k < recs.size(); ++k) {
    pred_before[k] = simulate(with_effects(before.bases[k], before.effects), recs[k].test);
    std::vector<double> res(pred_before[k].size());
    for (std::size_t i = 0; i < res.size(); ++i) res[i] = pred_before[k][i] - recs[k].test.force_kip[i];
    result.records[k].energy_before = localize(res, recs[k].seg, recs[k].test.dt_s, o.segmentation);
    energy_all += result.records[k].energy_before;
    const std::vector<ResidualWindow> w =
        residual_windows(recs[k].test.name(), recs[k].test.time_s, res, recs[k].seg, recs[k].test.dt_s, o.segmentation);
    result.top_windows.insert(result.top_windows.end(), w.begin(), w.end());
  }
  std::sort(result.top_windows.begin(), result.top_windows.end(),
            [](const ResidualWindow& a, const ResidualWindow& b) { return a.energy > b.energy; });
  if (result.top_windows.size() > 10) result.top_windows.resize(10);
  log("");
  log("== Where the model disagrees (residual = model - measured, before) ==");
  for (const std::string& l : format_regime_table(result.records, energy_all)) log(l);
  log("time windows holding the most residual energy:");
  for (const std::string& l : format_windows(result.top_windows, energy_all.total())) log(l);

  // 3-4. Greedy forward selection of effects, on records decimated to about fit_rate_hz.
  std::vector<Record> frecs;
  for (const Record& r : recs) {
    const std::size_t k = std::max<std::size_t>(
        1, static_cast<std::size_t>(std::floor(1.0 / (r.test.dt_s * std::max(1.0, o.fit_rate_hz)) + 1e-9)));
    frecs.push_back(decimate(r, k));
  }
  ModelState current = before;
  Sse cur = evaluate(frecs, current);
  auto neff_of = [&frecs](const ModelState& s) {
    double n = 0.0;
    for (std::size_t k = 0; k < frecs.size(); ++k)
      n += effective_sample_count(heldout_residual(simulate(with_effects(s.bases[k], s.effects), frecs[k].test), frecs[k]));
    return n;
  };
  log("");
  log("== Candidate effects (fitted on training samples, scored on held-out samples) ==");
  log("model as it is: train RMSE " + fmt(cur.train_rmse()) + " kip, held-out RMSE " + fmt(cur.held_rmse()) + " kip");
  if (cur.n_held == 0) throw std::invalid_argument("the records hold no held-out samples (too short to split)");
  for (int round = 1; round <= o.max_effects; ++round) {
    std::vector<const EffectSpec*> todo;
    for (const EffectSpec* s : library)
      if (!s->present(current.effects)) todo.push_back(s);
    if (todo.empty()) {
      result.stop_reason = "every candidate effect is in the model";
      break;
    }
    const double n_eff = neff_of(current);
    if (round == 1) result.effective_samples = n_eff;
    std::vector<CandidateScore> scores;
    std::vector<ModelState> states;
    for (const EffectSpec* spec : todo) {
      FitSpace space{{spec}};
      const std::vector<std::vector<double>> starts = {space.unit_of_start(current.effects, false),
                                                       space.unit_of_start(current.effects, true)};
      FitOutcome fit = fit_space(frecs, current, space, starts, o.effect_evals, o);
      const Sse s = evaluate(frecs, fit.state);
      CandidateScore c;
      c.round = round;
      c.effect = spec->name;
      for (const EffectParameter& p : spec->parameters) c.parameter_names.push_back(p.name);
      c.theta = spec->get(fit.state.effects);
      c.train_rmse_kip = s.train_rmse();
      c.heldout_rmse_kip = s.held_rmse();
      c.heldout_gain = 1.0 - s.held_rmse() / cur.held_rmse();
      c.delta_bic = n_eff * std::log(s.held / cur.held) + static_cast<double>(spec->parameters.size()) * std::log(n_eff);
      c.evaluations = fit.evaluations;
      for (std::size_t k = 0; k < frecs.size(); ++k) {
        const std::vector<double> pred = simulate(with_effects(fit.state.bases[k], fit.state.effects), frecs[k].test);
        std::vector<double> res(pred.size());
        for (std::size_t i = 0; i < res.size(); ++i) res[i] = pred[i] - frecs[k].test.force_kip[i];
        std::vector<std::uint8_t> held(res.size());
        for (std::size_t i = 0; i < res.size(); ++i) held[i] = frecs[k].seg.train[i] ? 0 : 1;
        c.heldout_energy += localize(res, frecs[k].seg, frecs[k].test.dt_s, o.segmentation, &held);
      }
      scores.push_back(c);
      states.push_back(fit.state);
    }
    std::size_t best = 0;
    for (std::size_t k = 1; k < scores.size(); ++k)
      if (scores[k].delta_bic < scores[best].delta_bic) best = k;
    const bool accept = scores[best].delta_bic <= o.bic_threshold && scores[best].heldout_gain >= o.min_improvement;
    scores[best].accepted = accept;
    // Held-out residual energy per regime of the current model, for the evidence line.
    RegimeEnergy cur_energy;
    for (std::size_t k = 0; k < frecs.size(); ++k) {
      const std::vector<double> pred = simulate(with_effects(current.bases[k], current.effects), frecs[k].test);
      std::vector<double> res(pred.size());
      for (std::size_t i = 0; i < res.size(); ++i) res[i] = pred[i] - frecs[k].test.force_kip[i];
      std::vector<std::uint8_t> held(res.size());
      for (std::size_t i = 0; i < res.size(); ++i) held[i] = frecs[k].seg.train[i] ? 0 : 1;
      cur_energy += localize(res, frecs[k].seg, frecs[k].test.dt_s, o.segmentation, &held);
    }
    log("");
    log("round " + std::to_string(round) + " (n_eff = " + fmt(n_eff, 4) + " effective held-out samples; current held-out RMSE " +
        fmt(cur.held_rmse()) + " kip):");
    for (const std::string& l : format_candidate_table(scores)) log(l);
    log(format_evidence(scores[best], cur_energy, cur.held_rmse(), o.min_improvement, o.bic_threshold));
    result.candidates.insert(result.candidates.end(), scores.begin(), scores.end());
    if (!accept) {
      result.stop_reason = "no candidate helps materially (best: " + scores[best].effect + ", held-out RMSE " +
                           fmt(100.0 * scores[best].heldout_gain, 3) + "% lower, dBIC " + fmt(scores[best].delta_bic, 4) +
                           "; needs >= " + fmt(100.0 * o.min_improvement, 3) + "% and dBIC <= " + fmt(o.bic_threshold, 3) + ")";
      break;
    }
    current = states[best];
    result.added.push_back(scores[best].effect);
    // Joint refit of all added effects (and the base on passive data).
    if (result.added.size() > 1 && o.polish_evals > 0) {
      FitSpace all;
      for (const std::string& name : result.added) all.specs.push_back(&effect_spec(name));
      FitOutcome fit = fit_space(frecs, current, all, {all.unit_of(current.effects)}, o.polish_evals, o);
      const Sse polished = evaluate(frecs, fit.state);
      const Sse unpolished = evaluate(frecs, current);
      if (polished.train < unpolished.train) current = fit.state;
    }
    cur = evaluate(frecs, current);
    log("added " + scores[best].effect + ": train RMSE " + fmt(cur.train_rmse()) + " kip, held-out RMSE " +
        fmt(cur.held_rmse()) + " kip; effects now: " + current.effects.names());
    if (round == o.max_effects) result.stop_reason = "reached --max-effects " + std::to_string(o.max_effects);
  }
  if (result.stop_reason.empty()) result.stop_reason = "--max-effects " + std::to_string(o.max_effects);
  log("");
  log("stop: " + result.stop_reason);
  result.effects = current.effects;

  // 5. Gap before/after per record.
  double sum_before = 0.0, sum_after = 0.0, max_after = 0.0;
  for (std::size_t k = 0; k < recs.size(); ++k) {
    RecordReport& rep = result.records[k];
    const Record& r = recs[k];
    rep.final_params = with_effects(current.bases[k], current.effects);
    const std::vector<double> after = simulate(rep.final_params, r.test);
    std::vector<std::uint8_t> held(after.size());
    for (std::size_t i = 0; i < held.size(); ++i) held[i] = r.seg.train[i] ? 0 : 1;
    rep.before = force_error(r.test.force_kip, pred_before[k], 0, r.test.size());
    rep.after = force_error(r.test.force_kip, after, 0, r.test.size());
    rep.before_heldout = masked_error(r.test.force_kip, pred_before[k], held, 1);
    rep.after_heldout = masked_error(r.test.force_kip, after, held, 1);
    std::vector<double> res(after.size());
    for (std::size_t i = 0; i < res.size(); ++i) res[i] = after[i] - r.test.force_kip[i];
    rep.energy_after = localize(res, r.seg, r.test.dt_s, o.segmentation);
    rep.time_s = r.test.time_s;
    rep.disp_in = r.test.drum_disp_in;
    rep.vel_in_per_s = r.test.drum_vel_in_per_s;
    rep.act1_in = r.test.has_actuator_positions ? r.test.actuator1_in : std::vector<double>(r.test.size(), 0.0);
    rep.act2_in = r.test.has_actuator_positions ? r.test.actuator2_in : std::vector<double>(r.test.size(), 0.0);
    rep.measured_kip = r.test.force_kip;
    rep.model_before_kip = pred_before[k];
    rep.model_after_kip = after;
    rep.segmentation = r.seg;
    sum_before += rep.before.nrmse_std;
    sum_after += rep.after.nrmse_std;
    max_after = std::max(max_after, rep.after.nrmse_std);
  }
  result.nrmse_before_mean = sum_before / static_cast<double>(recs.size());
  result.nrmse_after_mean = sum_after / static_cast<double>(recs.size());
  result.nrmse_after_max = max_after;

  // The updated config: the --model file with the effects; in identify mode its LuGre block is
  // re-identified on the passive windows of all records jointly (passive data only).
  result.updated_params = model;
  result.updated_params.effects = current.effects;
  if (o.base == BaseSource::identify && !result.added.empty())
    result.updated_params.lugre = joint_passive_lugre(frecs, model, current.effects, 400);
  for (std::size_t k = 0; k < recs.size(); ++k) {
    BrfdParams p = result.updated_params;
    if (recs[k].test.has_actuator_positions) {
      p.semiactive.actuator1_initial_in = recs[k].test.actuator1_in[0];
      p.semiactive.actuator2_initial_in = recs[k].test.actuator2_in[0];
    }
    result.records[k].updated_config = force_error(recs[k].test.force_kip, simulate(p, recs[k].test), 0, recs[k].test.size());
  }

  log("");
  log("== Gap before/after per record (NRMSE = RMSE / std of the measured force) ==");
  for (const std::string& l : format_gap_table(result.records, o.base == BaseSource::identify)) log(l);
  log("where the residual sits after:");
  RegimeEnergy energy_after_all;
  for (const RecordReport& rep : result.records) energy_after_all += rep.energy_after;
  for (const std::string& l : format_regime_shift(energy_all, energy_after_all)) log(l);

  if (!o.out_dir.empty()) {
    write_outputs(o, result, lines, log);
  }
  return result;
}

}  // namespace damper
