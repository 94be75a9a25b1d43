#include "server/ida/fragility.h"

#include <nlopt.hpp>

#include <cmath>
#include <numeric>
#include <stdexcept>

namespace server::ida {

namespace {

constexpr double kZ975 = 1.959963984540054;  // standard normal 97.5 % quantile

struct Sample {
  std::vector<double> y;    // ln capacities
  std::vector<double> yc;   // ln censoring IMs
};

/// ln[1 − Φ(z)] without cancellation for large z.
double log_survival(double z) { return std::log(0.5 * std::erfc(z / std::sqrt(2.0))); }

/// ℓ(μ, s) with s = ln β.
double log_likelihood(const Sample& d, double mu, double s) {
  const double beta = std::exp(s);
  const double log_norm = -0.5 * std::log(2.0 * 3.14159265358979323846);
  double l = 0.0;
  for (double y : d.y) {
    const double z = (y - mu) / beta;
    l += log_norm - 0.5 * z * z - s - y;
  }
  for (double y : d.yc) l += log_survival((y - mu) / beta);
  return l;
}

double nlopt_negative_ll(const std::vector<double>& x, std::vector<double>& /*grad*/, void* data) {
  return -log_likelihood(*static_cast<const Sample*>(data), x[0], x[1]);
}

}  // namespace

double lognormal_cdf(double x, double median, double beta) {
  if (!(x > 0.0)) return 0.0;
  return 0.5 * std::erfc(-std::log(x / median) / (beta * std::sqrt(2.0)));
}

LognormalFit fit_lognormal_fragility(const std::vector<double>& capacities, const std::vector<double>& censored_at) {
  Sample d;
  for (double x : capacities) {
    if (!(std::isfinite(x) && x > 0.0)) throw std::invalid_argument("fragility: capacity IMs must be finite and > 0");
    d.y.push_back(std::log(x));
  }
  for (double x : censored_at) {
    if (!(std::isfinite(x) && x > 0.0)) throw std::invalid_argument("fragility: censoring IMs must be finite and > 0");
    d.yc.push_back(std::log(x));
  }
  LognormalFit fit;
  fit.exceeded = static_cast<int>(d.y.size());
  fit.censored = static_cast<int>(d.yc.size());
  if (d.y.size() < 2) {
    fit.note = "fewer than 2 records reached the limit";
    return fit;
  }
  const double n = static_cast<double>(d.y.size());
  double mu = std::accumulate(d.y.begin(), d.y.end(), 0.0) / n;
  double var = 0.0;
  for (double y : d.y) var += (y - mu) * (y - mu);
  var /= n;
  if (!(var > 0.0)) {
    fit.note = "all capacities are equal: beta is zero";
    return fit;
  }
  double s = 0.5 * std::log(var);
  if (!d.yc.empty()) {
    nlopt::opt opt(nlopt::LN_BOBYQA, 2);
    std::vector<double> x{mu, s};
    opt.set_lower_bounds({mu - 20.0, std::log(1e-3)});
    opt.set_upper_bounds({mu + 20.0, std::log(20.0)});
    opt.set_min_objective(nlopt_negative_ll, &d);
    opt.set_initial_step({0.1, 0.1});
    opt.set_xtol_abs(1e-10);
    opt.set_maxeval(20000);
    double f = 0.0;
    try {
      opt.optimize(x, f);
    } catch (const nlopt::roundoff_limited&) {
      // x holds the best point found
    }
    mu = x[0];
    s = x[1];
  }
  // Observed information: numerical Hessian of −ℓ in (μ, s), central differences.
  const double h = 1e-4;
  auto nl = [&](double a, double b) { return -log_likelihood(d, a, b); };
  const double f0 = nl(mu, s);
  const double hmm = (nl(mu + h, s) - 2.0 * f0 + nl(mu - h, s)) / (h * h);
  const double hss = (nl(mu, s + h) - 2.0 * f0 + nl(mu, s - h)) / (h * h);
  const double hms = (nl(mu + h, s + h) - nl(mu + h, s - h) - nl(mu - h, s + h) + nl(mu - h, s - h)) / (4.0 * h * h);
  const double det = hmm * hss - hms * hms;
  if (!(det > 0.0 && hmm > 0.0)) {
    fit.note = "likelihood is flat at the maximum (no confidence bounds)";
    return fit;
  }
  const double var_mu = hss / det, var_s = hmm / det;
  fit.ok = true;
  fit.median = std::exp(mu);
  fit.beta = std::exp(s);
  fit.median_lo = std::exp(mu - kZ975 * std::sqrt(var_mu));
  fit.median_hi = std::exp(mu + kZ975 * std::sqrt(var_mu));
  fit.beta_lo = std::exp(s - kZ975 * std::sqrt(var_s));
  fit.beta_hi = std::exp(s + kZ975 * std::sqrt(var_s));
  return fit;
}

}  // namespace server::ida
