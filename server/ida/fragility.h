#pragma once
/// @file fragility.h
/// Lognormal fragility curves from IDA capacities (FEMA P-695 §7; Ibarra & Krawinkler; Baker
/// 2015, "Efficient analytical fragility function fitting using dynamic structural analysis",
/// Earthquake Spectra 31(1)):
///   P(limit exceeded | IM = x) = Φ( ln(x / θ) / β ),
/// θ the median capacity (IM units, g), β the logarithmic standard deviation.
///
/// Method: maximum likelihood on the capacities of the records. Each record's capacity is the
/// IM at which its IDA curve first reaches the limit; a record that never reaches it within
/// the traced range is right-censored at the highest IM run (it is known only to exceed it).
/// Log-likelihood (y = ln x, μ = ln θ):
///   ℓ(μ, β) = Σ_exceeded [ ln φ((y_i − μ)/β) − ln β − y_i ] + Σ_censored ln[1 − Φ((y_c − μ)/β)].
/// Without censored records the maximum is closed form (μ̂ = mean y, β̂² = (1/n)Σ(y − μ̂)²);
/// with them it is found with NLopt (BOBYQA on μ, ln β). Confidence bounds (95 %) are Wald
/// bounds from the observed information (the numerical Hessian of ℓ at the maximum) on μ and
/// ln β, so they hold for censored samples too; they are asymptotic (few records: wide and
/// approximate).

#include <string>
#include <vector>

namespace server::ida {

/// Name of the fitting method, written next to every fit.
inline constexpr const char* kFragilityMethod =
    "maximum likelihood, lognormal IDA capacities, right-censored at the highest IM traced; "
    "95 % Wald bounds from the observed information";

struct LognormalFit {
  bool ok = false;             ///< false: fewer than 2 exceeded capacities (no fit)
  std::string note;            ///< why not ok
  int exceeded = 0;            ///< records with a capacity (reached the limit)
  int censored = 0;            ///< records that never reached it
  double median = 0.0;         ///< θ, IM units
  double beta = 0.0;           ///< β
  double median_lo = 0.0, median_hi = 0.0;  ///< 95 % bounds of θ
  double beta_lo = 0.0, beta_hi = 0.0;      ///< 95 % bounds of β
};

/// Fits the lognormal by maximum likelihood. `capacities` > 0 (IM at which the limit was
/// reached), `censored_at` > 0 (highest IM reached by records that never exceeded the limit).
/// @throws std::invalid_argument on non-positive or non-finite values.
LognormalFit fit_lognormal_fragility(const std::vector<double>& capacities,
                                     const std::vector<double>& censored_at = {});

/// Φ(ln(x/θ)/β): probability of exceedance at IM x.
double lognormal_cdf(double x, double median, double beta);

}  // namespace server::ida
