// Lognormal fragility fit (server/ida/fragility.h) against samples drawn from a known
// lognormal: the fit gives back θ and β within its 95 % bounds, and over many independent
// samples those bounds cover the true values about 95 % of the time (complete and
// right-censored samples). Random numbers: std::mt19937_64 with fixed seeds.
#include "server/ida/fragility.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

namespace {

using server::ida::fit_lognormal_fragility;
using server::ida::LognormalFit;

constexpr double kMedian = 0.85, kBeta = 0.4;

/// n capacities from the lognormal; those above `censor` (if > 0) are censored there.
void draw(std::mt19937_64& rng, int n, double censor, std::vector<double>& cap, std::vector<double>& cens) {
  std::normal_distribution<double> z(0.0, 1.0);
  cap.clear();
  cens.clear();
  for (int i = 0; i < n; ++i) {
    const double x = kMedian * std::exp(kBeta * z(rng));
    if (censor > 0.0 && x > censor) cens.push_back(censor);
    else cap.push_back(x);
  }
}

TEST(Fragility, LargeSampleRecoversTheLognormal) {
  std::mt19937_64 rng(20260101);
  std::vector<double> cap, cens;
  draw(rng, 4000, 0.0, cap, cens);
  const LognormalFit f = fit_lognormal_fragility(cap, cens);
  ASSERT_TRUE(f.ok) << f.note;
  std::printf("n 4000: median %.4f [%.4f, %.4f], beta %.4f [%.4f, %.4f]\n", f.median, f.median_lo, f.median_hi,
              f.beta, f.beta_lo, f.beta_hi);
  // One sample: the truth within 3.29 standard errors (99.9 %; the 95 % coverage is the
  // next test's subject).
  EXPECT_LT(std::abs(std::log(f.median / kMedian)), 3.29 * kBeta / std::sqrt(4000.0));
  EXPECT_LT(std::abs(std::log(f.beta / kBeta)), 3.29 / std::sqrt(8000.0));
  // Bounds of the complete sample: the textbook ones, β̂/√n on ln θ and β̂/√(2n) on ln β.
  EXPECT_NEAR(std::log(f.median_hi / f.median), 1.96 * f.beta / std::sqrt(4000.0), 1e-3);
  EXPECT_NEAR(std::log(f.beta_hi / f.beta), 1.96 / std::sqrt(8000.0), 1e-3);
}

TEST(Fragility, BoundsCoverTheTruthAboutNinetyFivePercent) {
  for (double censor : {0.0, 1.1}) {  // complete; about 26 % censored
    std::mt19937_64 rng(7);
    int cover_median = 0, cover_beta = 0, fits = 0;
    const int trials = 400;
    std::vector<double> cap, cens;
    for (int t = 0; t < trials; ++t) {
      draw(rng, 60, censor, cap, cens);
      const LognormalFit f = fit_lognormal_fragility(cap, cens);
      if (!f.ok) continue;
      ++fits;
      cover_median += f.median_lo <= kMedian && kMedian <= f.median_hi;
      cover_beta += f.beta_lo <= kBeta && kBeta <= f.beta_hi;
    }
    std::printf("censor %.2f: %d fits of 60 records, coverage median %.1f %%, beta %.1f %%\n", censor, fits,
                100.0 * cover_median / fits, 100.0 * cover_beta / fits);
    ASSERT_EQ(fits, trials);
    // Binomial(400, 0.95): sd 1.1 %; allow the asymptotic bounds' small-sample deficit.
    EXPECT_GT(cover_median, 0.90 * fits);
    EXPECT_LT(cover_median, 0.985 * fits);
    EXPECT_GT(cover_beta, 0.90 * fits);
    EXPECT_LT(cover_beta, 0.985 * fits);
  }
}

TEST(Fragility, CensoringMatters) {
  // Ignoring censored records biases the median low; the censored likelihood does not.
  std::mt19937_64 rng(11);
  std::vector<double> cap, cens;
  draw(rng, 3000, 1.0, cap, cens);
  ASSERT_GT(cens.size(), 500u);
  const LognormalFit with = fit_lognormal_fragility(cap, cens);
  const LognormalFit without = fit_lognormal_fragility(cap, {});
  EXPECT_NEAR(with.median / kMedian, 1.0, 0.03);
  EXPECT_LT(without.median, 0.92 * kMedian);
}

TEST(Fragility, DegenerateInput) {
  EXPECT_FALSE(fit_lognormal_fragility({0.5}, {1.0, 1.0}).ok);
  EXPECT_FALSE(fit_lognormal_fragility({0.5, 0.5}).ok);
  EXPECT_THROW(fit_lognormal_fragility({0.5, -1.0}), std::invalid_argument);
  EXPECT_NEAR(server::ida::lognormal_cdf(kMedian, kMedian, kBeta), 0.5, 1e-15);
  EXPECT_NEAR(server::ida::lognormal_cdf(kMedian * std::exp(kBeta), kMedian, kBeta), 0.8413447460685429, 1e-12);
}

}  // namespace
