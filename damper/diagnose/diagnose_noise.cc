#include "damper/diagnose/diagnose_noise.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace damper {

namespace {

int half_width(double window_s, double dt_s) { return std::max(1, static_cast<int>(std::lround(0.5 * window_s / dt_s))); }

double median_of(std::vector<double> x) {
  if (x.empty()) return 0.0;
  const std::size_t m = x.size() / 2;
  std::nth_element(x.begin(), x.begin() + static_cast<long>(m), x.end());
  return x[m];
}

}  // namespace

double noise_floor_kip(const std::vector<double>& r, double dt_s, const SegmentationOptions& o) {
  const int hw = half_width(o.chatter_window_s, dt_s);
  const double w = 2.0 * hw + 1.0;
  const std::vector<double> low = centered_moving_average(r, hw);
  std::vector<double> h;
  for (std::size_t i = static_cast<std::size_t>(hw); i + static_cast<std::size_t>(hw) < r.size(); ++i)
    h.push_back(r[i] - low[i]);
  if (h.size() < 16) return 0.0;
  const double med = median_of(h);
  for (double& x : h) x = std::abs(x - med);
  return 1.4826 * median_of(h) / std::sqrt(1.0 - 1.0 / w);
}

NoiseReport residual_structure(const std::vector<ResidualSample>& recs, const SegmentationOptions& o) {
  NoiseReport rep;
  double sigma2_sum = 0.0;
  int sigma_n = 0;
  for (const ResidualSample& s : recs) {
    const double sg = noise_floor_kip(*s.residual, s.dt_s, o);
    sigma2_sum += sg * sg;
    ++sigma_n;
  }
  const double sigma2 = sigma_n ? sigma2_sum / sigma_n : 0.0;
  rep.sigma_kip = std::sqrt(sigma2);
  // Low-frequency power per regime and overall, in units of the white-noise expectation σ²/W.
  double lf_sum[kRegimeCount] = {0, 0, 0, 0, 0, 0};
  double lf_n[kRegimeCount] = {0, 0, 0, 0, 0, 0};
  double lf_w[kRegimeCount] = {0, 0, 0, 0, 0, 0};  // Σ W over samples (for the mean window)
  double se = 0.0, n = 0.0, acf_num = 0.0, acf_den = 0.0, acf_n = 0.0;
  for (const ResidualSample& s : recs) {
    const std::vector<double>& r = *s.residual;
    const int hw = half_width(o.chatter_window_s, s.dt_s);
    const double w = 2.0 * hw + 1.0;
    const std::vector<double> low = centered_moving_average(r, hw);
    const std::size_t lag = static_cast<std::size_t>(2 * hw + 1);
    for (std::size_t i = 0; i < r.size(); ++i) {
      if (s.mask && !(*s.mask)[i]) continue;
      se += r[i] * r[i];
      n += 1.0;
      acf_den += r[i] * r[i];
      if (i + lag < r.size() && (!s.mask || (*s.mask)[i + lag])) {
        acf_num += r[i] * r[i + lag];
        acf_n += 1.0;
      }
      if (i < static_cast<std::size_t>(hw) || i + static_cast<std::size_t>(hw) >= r.size()) continue;
      const int g = static_cast<int>(s.seg->regime[i]);
      lf_sum[g] += low[i] * low[i] * w;  // in units of σ² after division
      lf_n[g] += 1.0;
      lf_w[g] += w;
    }
  }
  rep.mse_kip2 = n > 0 ? se / n : 0.0;
  rep.excess_ratio = sigma2 > 0 ? rep.mse_kip2 / sigma2 : INFINITY;
  rep.lag_autocorrelation = acf_den > 0 ? acf_num / acf_den * (n / std::max(1.0, acf_n)) : 0.0;
  rep.autocorrelation_limit = n > 0 ? 3.0 / std::sqrt(n) : 1.0;
  double all_sum = 0.0, all_n = 0.0, all_w = 0.0;
  for (int g = 0; g < kRegimeCount - 1; ++g) {
    all_sum += lf_sum[g];
    all_n += lf_n[g];
    all_w += lf_w[g];
    if (lf_n[g] < 8.0 || sigma2 <= 0.0) continue;
    const double wbar = lf_w[g] / lf_n[g];
    const double ratio = lf_sum[g] / lf_n[g] / sigma2;
    const double limit = 1.0 + 3.0 * std::sqrt(2.0 * wbar / lf_n[g]);
    if (ratio > limit) rep.significant_regimes.push_back(to_string(static_cast<Regime>(g)));
  }
  if (all_n > 0 && sigma2 > 0.0) {
    const double wbar = all_w / all_n;
    rep.lowfreq_ratio = all_sum / all_n / sigma2;
    rep.lowfreq_limit = 1.0 + 3.0 * std::sqrt(2.0 * wbar / all_n);
  } else {
    rep.lowfreq_ratio = INFINITY;
    rep.lowfreq_limit = 1.0;
  }
  rep.structured = rep.lowfreq_ratio > rep.lowfreq_limit || !rep.significant_regimes.empty();
  std::ostringstream line;
  line << std::setprecision(3) << "noise floor sigma " << rep.sigma_kip << " kip; residual RMS " << std::sqrt(rep.mse_kip2)
       << " kip (mean square " << rep.excess_ratio << " x sigma^2); low-frequency residual power " << rep.lowfreq_ratio
       << " x white noise (3-sigma limit " << rep.lowfreq_limit << "); autocorrelation at the window lag "
       << rep.lag_autocorrelation << " (limit " << rep.autocorrelation_limit << ")";
  if (!rep.significant_regimes.empty()) {
    line << "; structure concentrated in:";
    for (const std::string& g : rep.significant_regimes) line << " " << g;
  }
  line << (rep.structured ? " -> structured: something is missing" : " -> indistinguishable from noise");
  rep.summary = line.str();
  return rep;
}

}  // namespace damper
