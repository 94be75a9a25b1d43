#include "server/ida/ida_curves.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace server::ida {

namespace {

/// Non-collapsed runs below the first collapse, sorted by IM, after (0, 0); and that collapse.
std::vector<TracePoint> curve(const std::vector<TracePoint>& runs, double* first_collapse) {
  double lowest = std::numeric_limits<double>::infinity();
  for (const TracePoint& p : runs)
    if (p.collapse) lowest = std::min(lowest, p.im);
  std::vector<TracePoint> c{{0.0, 0.0, false}};
  for (const TracePoint& p : runs)
    if (!p.collapse && p.im < lowest) c.push_back(p);
  std::sort(c.begin(), c.end(), [](const TracePoint& a, const TracePoint& b) { return a.im < b.im; });
  *first_collapse = lowest;
  return c;
}

}  // namespace

double drift_at(const std::vector<TracePoint>& runs, double im) {
  double collapse = 0.0;
  const std::vector<TracePoint> c = curve(runs, &collapse);
  if (im >= collapse) return std::numeric_limits<double>::infinity();
  if (im > c.back().im) {
    // Between the last non-collapsed run and the collapse: the flatline has begun somewhere
    // in there; without a collapse the curve is not traced that far.
    return std::isfinite(collapse) ? std::numeric_limits<double>::infinity() : std::nan("");
  }
  for (std::size_t i = 0; i + 1 < c.size(); ++i) {
    if (im <= c[i + 1].im) {
      const double f = (im - c[i].im) / (c[i + 1].im - c[i].im);
      return c[i].drift_ratio + f * (c[i + 1].drift_ratio - c[i].drift_ratio);
    }
  }
  return c.back().drift_ratio;
}

Capacity capacity_at(const std::vector<TracePoint>& runs, double drift_limit) {
  if (runs.empty()) throw std::invalid_argument("capacity_at: no runs");
  double collapse = 0.0;
  const std::vector<TracePoint> c = curve(runs, &collapse);
  for (std::size_t i = 0; i + 1 < c.size(); ++i) {
    if (c[i + 1].drift_ratio >= drift_limit) {
      const double f = (drift_limit - c[i].drift_ratio) / (c[i + 1].drift_ratio - c[i].drift_ratio);
      return {true, c[i].im + f * (c[i + 1].im - c[i].im)};
    }
  }
  if (std::isfinite(collapse)) return {true, c.back().im > 0.0 ? c.back().im : collapse};
  double top = 0.0;
  for (const TracePoint& p : runs) top = std::max(top, p.im);
  return {false, top};
}

double quantile(std::vector<double> values, double p) {
  values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return std::isnan(v); }), values.end());
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  const double h = p * static_cast<double>(values.size() - 1);
  const std::size_t lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(values.size() - 1, lo + 1);
  if (std::isinf(values[lo]) || std::isinf(values[hi])) return h == static_cast<double>(lo) ? values[lo] : values[hi];
  return values[lo] + (h - static_cast<double>(lo)) * (values[hi] - values[lo]);
}

}  // namespace server::ida
