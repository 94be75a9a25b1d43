#pragma once
/// @file ida_curves.h
/// From traced runs to IDA results (Vamvatsikos & Cornell 2002, §5 and §7): the IDA curve of a
/// record is the piecewise-linear line through (0, 0) and its non-collapsed runs (IM vs peak
/// interstory drift ratio), flat (infinite drift) from its first collapse on. Summaries:
///  - drift fractiles (16/50/84 %) across records at given IMs, collapsed records counted as
///    infinite drift (empirical quantiles, linear between order statistics as numpy's
///    default);
///  - the capacity of a record for a drift limit: the IM at which its curve first reaches the
///    limit (linear interpolation), or the last non-collapsed IM if it flatlines first; a
///    record that never reaches the limit within its traced range is right-censored at its
///    highest IM (fragility.h).

#include "server/ida/hunt_fill.h"

#include <vector>

namespace server::ida {

/// Drift ratio of the curve at `im` (runs in any order): linear between runs, +inf at or above
/// the first collapse, NaN above the highest run of a curve without collapse (not traced).
double drift_at(const std::vector<TracePoint>& runs, double im);

struct Capacity {
  bool reached = false;   ///< false: censored at `im`
  double im = 0.0;        ///< capacity IM (g), or the censoring IM
};

/// Capacity of one record for `drift_limit` (ratio). Needs at least one run.
Capacity capacity_at(const std::vector<TracePoint>& runs, double drift_limit);

/// Empirical p-quantile (0 ≤ p ≤ 1) of `values` (may hold +inf; NaN entries are ignored);
/// NaN if there are none.
double quantile(std::vector<double> values, double p);

}  // namespace server::ida
