#include "damper/fit/identification.h"

#include "damper/fit/staged_search.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace damper {

LugreParams lugre_from_search_vector(const std::vector<double>& x) {
  LugreParams g;
  g.sigma0_kip_per_in = std::pow(10.0, x[0]);
  g.sigma1_kip_s_per_in = x[1];
  g.sigma2_kip_s_per_in = x[2];
  g.fc_fwd_kip = x[3];
  g.fc_bwd_kip = x[4];
  g.fs_fwd_kip = x[3] * x[5];
  g.fs_bwd_kip = x[4] * x[6];
  g.vs_in_per_s = std::pow(10.0, x[7]);
  return g;
}

namespace {

// Search vector: log10 σ0, σ1, σ2, Fc_fwd, Fc_bwd, Fs_fwd/Fc_fwd, Fs_bwd/Fc_bwd, log10 v_s.
std::vector<double> pack(const LugreParams& g) {
  return {std::log10(g.sigma0_kip_per_in), g.sigma1_kip_s_per_in, g.sigma2_kip_s_per_in,
          g.fc_fwd_kip, g.fc_bwd_kip, g.fs_fwd_kip / g.fc_fwd_kip, g.fs_bwd_kip / g.fc_bwd_kip,
          std::log10(g.vs_in_per_s)};
}

// `params` with its residual over [begin, end) and the window's times (evaluations, algorithm unset).
IdentificationResult result_on_window(const BrfdParams& params, const BrfdTest& test, std::size_t begin,
                                      std::size_t end, const ReplayOptions& replay) {
  IdentificationResult r;
  r.params = params;
  const std::vector<double> f = replay_force_kip(r.params, test, begin, end, replay);
  std::vector<double> full(test.size(), 0.0);
  std::copy(f.begin(), f.end(), full.begin() + static_cast<long>(begin));
  r.residual = force_error(test.force_kip, full, begin, end);
  r.t0_s = test.time_s[begin];
  r.t1_s = end < test.size() ? test.time_s[end] : test.time_s.back() + test.dt_s;
  return r;
}

}  // namespace

DrumExcursion drum_excursion(const BrfdTest& test, std::size_t begin, std::size_t end) {
  DrumExcursion e;
  if (end <= begin) return e;
  double lo = test.drum_disp_in[begin], hi = lo;
  for (std::size_t i = begin; i < end; ++i) {
    const double d = test.drum_disp_in[i];
    lo = std::min(lo, d);
    hi = std::max(hi, d);
    e.forward_in = std::max(e.forward_in, d - lo);
    e.backward_in = std::max(e.backward_in, hi - d);
  }
  return e;
}

std::string window_does_not_identify(const BrfdTest& test, const BrfdParams& start, const IdentificationOptions& opt) {
  const std::size_t begin = index_at_time(test, opt.t0_s);
  const std::size_t end = std::isfinite(opt.t1_s) ? index_at_time(test, opt.t1_s) : test.size();
  std::ostringstream o;
  o << std::setprecision(3);
  if (end <= begin || end - begin < 100) {
    o << test.path << ": the identification window [" << opt.t0_s << ", " << opt.t1_s << ") s holds "
      << (end > begin ? end - begin : 0) << " samples (need at least 100)";
    return o.str();
  }
  const double t0 = test.time_s[begin];
  const double t1 = end < test.size() ? test.time_s[end] : test.time_s.back() + test.dt_s;
  double peak_v = 0.0;
  for (std::size_t i = begin; i < end; ++i) peak_v = std::max(peak_v, std::abs(test.drum_vel_in_per_s[i]));
  if (peak_v < 0.05) {
    o << test.path << ": the drum barely moves in the window " << t0 << "-" << t1 << " s (peak |v| " << peak_v
      << " in/s < 0.05): it does not identify the LuGre parameters";
    return o.str();
  }
  // Does the window identify anything? Both directions must slide past the pre-sliding range.
  const DrumExcursion ex = drum_excursion(test, begin, end);
  const LugreParams& g0 = start.lugre;
  const double need_fwd = opt.min_excursion_presliding * g0.fc_fwd_kip / g0.sigma0_kip_per_in;
  const double need_bwd = opt.min_excursion_presliding * g0.fc_bwd_kip / g0.sigma0_kip_per_in;
  if (ex.forward_in < need_fwd || ex.backward_in < need_bwd) {
    o << test.path << ": the window " << t0 << "-" << t1
      << " s does not identify the LuGre parameters: the drum's largest excursion there is " << ex.forward_in
      << " in forward and " << ex.backward_in << " in backward, and sliding past the pre-sliding range needs "
      << need_fwd << " and " << need_bwd << " in (" << opt.min_excursion_presliding << " Fc/sigma0)";
    return o.str();
  }
  return "";
}

StribeckShown stribeck_shown(const BrfdTest& test, std::size_t begin, std::size_t end, const BrfdParams& start,
                             const IdentificationOptions& opt) {
  StribeckShown s;
  for (std::size_t i = 0; i < test.size(); ++i) {
    const double v = test.drum_vel_in_per_s[i];
    const bool inside = i >= begin && i < end;
    double& fwd = inside ? s.window_fwd_in_per_s : s.test_fwd_in_per_s;
    double& bwd = inside ? s.window_bwd_in_per_s : s.test_bwd_in_per_s;
    fwd = std::max(fwd, v);
    bwd = std::max(bwd, -v);
  }
  s.min_speeds = opt.min_stribeck_speeds;
  s.shows_in_per_s = opt.min_stribeck_speeds * start.lugre.vs_in_per_s;
  const double faster = opt.stribeck_extrapolation_ratio;
  s.keep_fwd = s.window_fwd_in_per_s < s.shows_in_per_s && s.test_fwd_in_per_s > faster * s.window_fwd_in_per_s;
  s.keep_bwd = s.window_bwd_in_per_s < s.shows_in_per_s && s.test_bwd_in_per_s > faster * s.window_bwd_in_per_s;
  s.keep_vs = s.keep_fwd && s.keep_bwd;
  return s;
}

std::string StribeckShown::note() const {
  if (!keep_fwd && !keep_bwd) return "";
  std::ostringstream o;
  o << std::setprecision(3) << "the window's peak speed";
  if (keep_fwd) o << " forward " << window_fwd_in_per_s << " in/s (the test reaches " << test_fwd_in_per_s << ")";
  if (keep_bwd) o << (keep_fwd ? " and" : "") << " backward " << window_bwd_in_per_s << " in/s (the test reaches " << test_bwd_in_per_s << ")";
  o << " stays below " << min_speeds << " v_s = " << shows_in_per_s << " in/s, where the Stribeck curve reaches the kinetic level: Fs/Fc" << (keep_fwd && keep_bwd ? " both ways" : keep_fwd ? " forward" : " backward")
    << (keep_vs ? " and v_s" : "") << " kept at the start's, the level fitted";
  return o.str();
}

IdentificationResult identify_lugre(const BrfdTest& test, const BrfdParams& start,
                                    const IdentificationOptions& opt) {
  const std::size_t begin = index_at_time(test, opt.t0_s);
  const std::size_t end = std::isfinite(opt.t1_s) ? index_at_time(test, opt.t1_s) : test.size();
  if (end <= begin || end - begin < 100) {
    std::ostringstream o;
    o << test.path << ": identification window [" << opt.t0_s << ", " << opt.t1_s
      << ") s holds " << (end > begin ? end - begin : 0) << " samples (need at least 100)";
    throw std::invalid_argument(o.str());
  }
  const std::string obstacle = window_does_not_identify(test, start, opt);
  if (!obstacle.empty()) {
    IdentificationResult r = result_on_window(start, test, begin, end, opt.replay);
    r.algorithm = "none";
    r.identified = false;
    r.note = obstacle + ": the start parameters are kept";
    return r;
  }

  // Which of the search vector's entries the window's speeds identify (min_stribeck_speeds):
  // entries 5 and 6 are Fs/Fc forward and backward, 7 is log10 v_s.
  const StribeckShown shown = stribeck_shown(test, begin, end, start, opt);
  const bool keep_fwd = shown.keep_fwd, keep_bwd = shown.keep_bwd, keep_vs = shown.keep_vs;

  const LugreBounds& b = opt.bounds;
  const std::vector<double> lo = {std::log10(b.sigma0_min), b.sigma1_min, b.sigma2_min, b.fc_min,
                                  b.fc_min, b.fs_ratio_min, b.fs_ratio_min, std::log10(b.vs_min)};
  const std::vector<double> hi = {std::log10(b.sigma0_max), b.sigma1_max, b.sigma2_max, b.fc_max,
                                  b.fc_max, b.fs_ratio_max, b.fs_ratio_max, std::log10(b.vs_max)};

  // Cost: RMSE between measured force and the force replayed with the candidate's LuGre block.
  BrfdParams params = start;
  const auto rmse = [&](const std::vector<double>& x) {
    params.lugre = lugre_from_search_vector(x);
    const std::vector<double> f = replay_force_kip(params, test, begin, end, opt.replay);
    double se = 0.0;
    for (std::size_t i = begin; i < end; ++i) {
      const double e = f[i - begin] - test.force_kip[i];
      se += e * e;
    }
    return std::sqrt(se / static_cast<double>(end - begin));
  };
  // The search runs over the free entries; the kept ones stay at the start's values.
  const std::vector<double> full_start = pack(start.lugre);
  std::vector<std::size_t> free_entries;
  for (std::size_t k = 0; k < full_start.size(); ++k)
    if (!(k == 5 && keep_fwd) && !(k == 6 && keep_bwd) && !(k == 7 && keep_vs)) free_entries.push_back(k);
  const auto full_of = [&](const std::vector<double>& y) {
    std::vector<double> x = full_start;
    for (std::size_t j = 0; j < free_entries.size(); ++j) x[free_entries[j]] = y[j];
    return x;
  };
  std::vector<double> y_start, y_lo, y_hi;
  for (std::size_t k : free_entries) {
    y_start.push_back(full_start[k]);
    y_lo.push_back(lo[k]);
    y_hi.push_back(hi[k]);
  }
  const StagedSearchResult found =
      staged_search([&](const std::vector<double>& y) { return rmse(full_of(y)); }, y_start, y_lo, y_hi,
                    {opt.global_max_evals, opt.global_runs, opt.local_max_evals, opt.seed, 1e-7});

  BrfdParams fitted = start;
  fitted.lugre = lugre_from_search_vector(full_of(found.x));
  IdentificationResult r = result_on_window(fitted, test, begin, end, opt.replay);
  r.evaluations = found.evaluations;
  r.algorithm = found.algorithm;
  r.stribeck_kept_fwd = keep_fwd;
  r.stribeck_kept_bwd = keep_bwd;
  r.vs_kept = keep_vs;
  r.note = shown.note();
  return r;
}

std::string describe(const IdentificationResult& r) {
  const LugreParams& g = r.params.lugre;
  std::ostringstream o;
  o << std::setprecision(5);
  if (!r.identified)
    o << "NOT identified: " << r.note << "\n";
  else
    o << "identified on [" << r.t0_s << ", " << r.t1_s << ") s with " << r.algorithm << ", " << r.evaluations
      << " evaluations\n" << (r.note.empty() ? "" : "  " + r.note + "\n");
  o
    << "  sigma0 = " << g.sigma0_kip_per_in << " kip/in\n"
    << "  sigma1 = " << g.sigma1_kip_s_per_in << " kip s/in\n"
    << "  sigma2 = " << g.sigma2_kip_s_per_in << " kip s/in\n"
    << "  Fc (b) fwd = " << g.fc_fwd_kip << " kip, bwd = " << g.fc_bwd_kip << " kip\n"
    << "  Fs fwd = " << g.fs_fwd_kip << " kip, bwd = " << g.fs_bwd_kip << " kip\n"
    << "  v_s = " << g.vs_in_per_s << " in/s\n"
    << "  residual on the window: rmse = " << r.residual.rmse_kip
    << " kip, nrmse(std) = " << r.residual.nrmse_std << ", nrmse(range) = " << r.residual.nrmse_range;
  return o.str();
}

}  // namespace damper
