#pragma once
/// @file staged_search.h
/// The bounded search of both identifications (LuGre: identification.h; band brake:
/// band_brake_fit.h): the start point (clamped to the box) counts as a candidate, then
/// `global_runs` NLopt GN_CRS2_LM runs of `global_max_evals` evaluations from it, seeded seed,
/// seed + 1, ... (the costs have several local minima, e.g. a Stribeck hump vs viscous friction
/// explaining the same force rise), then an LN_BOBYQA polish of `local_max_evals` evaluations
/// from the best point seen. Every stage keeps the best point seen (a round-off-limited or
/// forced stop of NLopt keeps it too); a non-finite cost counts as 1e9.

#include <functional>
#include <string>
#include <vector>

namespace damper {

struct StagedSearchOptions {
  int global_max_evals = 0;  ///< GN_CRS2_LM evaluations per run (0: no global stage)
  int global_runs = 0;       ///< independent GN_CRS2_LM runs
  int local_max_evals = 0;   ///< LN_BOBYQA evaluations
  unsigned seed = 1;         ///< NLopt's random seed of the first global run (reproducible fits)
  double ftol_abs = 1e-7;    ///< absolute cost tolerance of each stage (relative x tolerance 1e-6)
};

struct StagedSearchResult {
  std::vector<double> x;     ///< best point seen
  double cost = 0.0;         ///< its cost
  int evaluations = 0;       ///< cost evaluations, the start point included
  std::string algorithm;     ///< e.g. "3 x GN_CRS2_LM(6000) + LN_BOBYQA(3000)"
};

/// Minimises `cost` over the box [lo, hi] from `start` as described above.
StagedSearchResult staged_search(const std::function<double(const std::vector<double>&)>& cost,
                                 std::vector<double> start, const std::vector<double>& lo,
                                 const std::vector<double>& hi, const StagedSearchOptions& options);

}  // namespace damper
