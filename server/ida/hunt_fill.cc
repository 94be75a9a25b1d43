#include "server/ida/hunt_fill.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace server::ida {

namespace {

bool same_im(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b)); }

bool is_done(const std::vector<TracePoint>& done, double im) {
  for (const TracePoint& p : done)
    if (same_im(p.im, im)) return true;
  return false;
}

}  // namespace

void validate(const HuntFillSettings& s) {
  auto positive = [](double v, const char* name) {
    if (!(std::isfinite(v) && v > 0.0)) throw std::invalid_argument(std::string(name) + " must be > 0");
  };
  positive(s.first_im, "hunt.first_im");
  positive(s.step, "hunt.step");
  positive(s.max_im, "hunt.max_im");
  positive(s.bracket_resolution, "hunt.bracket_resolution");
  if (!(std::isfinite(s.step_increment) && s.step_increment >= 0.0))
    throw std::invalid_argument("hunt.step_increment must be >= 0");
  if (s.first_im > s.max_im) throw std::invalid_argument("hunt.first_im must not exceed hunt.max_im");
  if (s.max_runs < 2 || s.max_runs > 200) throw std::invalid_argument("hunt.max_runs must be in [2, 200]");
}

std::vector<double> hunt_sequence(const HuntFillSettings& s) {
  validate(s);
  std::vector<double> seq;
  for (int k = 0; static_cast<int>(seq.size()) < s.max_runs; ++k) {
    const double im = s.first_im + k * s.step + 0.5 * k * (k - 1) * s.step_increment;
    if (im >= s.max_im) {
      seq.push_back(s.max_im);
      break;
    }
    seq.push_back(im);
  }
  return seq;
}

std::vector<double> next_runs(const HuntFillSettings& s, const std::vector<TracePoint>& done) {
  const int used = static_cast<int>(done.size());
  if (used >= s.max_runs) return {};
  double lowest_collapse = std::numeric_limits<double>::infinity();
  for (const TracePoint& p : done)
    if (p.collapse) lowest_collapse = std::min(lowest_collapse, p.im);

  // 1. hunt up.
  for (double im : hunt_sequence(s)) {
    if (im >= lowest_collapse) break;
    if (!is_done(done, im)) return {im};
  }
  // 2. bracket the first collapse.
  double lo = 0.0;
  std::vector<double> ok;
  for (const TracePoint& p : done) {
    if (!p.collapse && p.im < lowest_collapse) {
      lo = std::max(lo, p.im);
      ok.push_back(p.im);
    }
  }
  if (std::isfinite(lowest_collapse) && lowest_collapse - lo > s.bracket_resolution) return {0.5 * (lo + lowest_collapse)};
  // 3. fill the largest gaps below it (from IM = 0), all remaining runs at once.
  ok.push_back(0.0);
  std::sort(ok.begin(), ok.end());
  std::vector<double> fill;
  for (int r = used; r < s.max_runs; ++r) {
    std::size_t best = 0;
    double gap = 0.0;
    for (std::size_t i = 0; i + 1 < ok.size(); ++i) {
      if (ok[i + 1] - ok[i] > gap * (1.0 + 1e-12)) {
        gap = ok[i + 1] - ok[i];
        best = i;
      }
    }
    if (gap <= 1e-6) break;
    const double mid = 0.5 * (ok[best] + ok[best + 1]);
    fill.push_back(mid);
    ok.insert(ok.begin() + static_cast<std::ptrdiff_t>(best) + 1, mid);
  }
  return fill;
}

}  // namespace server::ida
