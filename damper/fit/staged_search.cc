#include "damper/fit/staged_search.h"

#include <nlopt.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace damper {

namespace {

struct Search {
  const std::function<double(const std::vector<double>&)>* cost = nullptr;
  int evaluations = 0;
  double best = INFINITY;
  std::vector<double> best_x;

  double evaluate(const std::vector<double>& x) {
    double c = (*cost)(x);
    ++evaluations;
    if (!std::isfinite(c)) c = 1e9;
    if (c < best) {
      best = c;
      best_x = x;
    }
    return c;
  }
};

double objective(const std::vector<double>& x, std::vector<double>& /*grad*/, void* data) {
  return static_cast<Search*>(data)->evaluate(x);
}

// One NLopt stage from x; x becomes the best point seen so far (over all stages).
void run_stage(nlopt::algorithm algo, int max_evals, const std::vector<double>& lo, const std::vector<double>& hi,
               double ftol_abs, Search& search, std::vector<double>& x) {
  nlopt::opt o(algo, static_cast<unsigned>(x.size()));
  o.set_lower_bounds(lo);
  o.set_upper_bounds(hi);
  o.set_min_objective(objective, &search);
  o.set_maxeval(max_evals);
  o.set_xtol_rel(1e-6);
  o.set_ftol_abs(ftol_abs);
  double f = 0.0;
  try {
    o.optimize(x, f);
  } catch (const nlopt::roundoff_limited&) {
    // Converged as far as floating point allows: keep the best point seen.
  } catch (const nlopt::forced_stop&) {
  }
  x = search.best_x;
}

}  // namespace

StagedSearchResult staged_search(const std::function<double(const std::vector<double>&)>& cost,
                                 std::vector<double> x, const std::vector<double>& lo,
                                 const std::vector<double>& hi, const StagedSearchOptions& opt) {
  Search search;
  search.cost = &cost;
  for (std::size_t k = 0; k < x.size(); ++k) x[k] = std::clamp(x[k], lo[k], hi[k]);
  search.evaluate(x);  // the start point counts as a candidate
  std::ostringstream algo;
  if (opt.global_max_evals > 0 && opt.global_runs > 0) {
    for (int run = 0; run < opt.global_runs; ++run) {
      nlopt::srand(opt.seed + static_cast<unsigned>(run));
      std::vector<double> xr = x;
      run_stage(nlopt::GN_CRS2_LM, opt.global_max_evals, lo, hi, opt.ftol_abs, search, xr);
    }
    algo << opt.global_runs << " x GN_CRS2_LM(" << opt.global_max_evals << ") + ";
  }
  x = search.best_x;
  run_stage(nlopt::LN_BOBYQA, opt.local_max_evals, lo, hi, opt.ftol_abs, search, x);
  algo << "LN_BOBYQA(" << opt.local_max_evals << ")";
  return {search.best_x, search.best, search.evaluations, algo.str()};
}

}  // namespace damper
