#pragma once
/// @file diagnose_select.h
/// Selection engine of `hybridsim diagnose` (docs/diagnose.md): decides on unseen data whether a
/// candidate effect of the library (effects.h) is missing from the model.
///
/// Validation plan: with two or more records, leave-one-record-out (fold f fits on every other
/// record and scores record f after its passive window); with one record, the held-out drum
/// cycles of its split. The scored samples are cut into held-out PARTS (one per drum cycle /
/// rest half), the units of the consistency test and of the bootstrap.
///
/// One round, per fold: stage A refits the effects already added (and the bases) on the fold's
/// fitting samples; then the model without a candidate ("null") and each candidate get the same
/// fit procedure from A (diagnose_fit.h), the candidate with its parameters free. Per held-out
/// part p, g_p = SSE_null,p − SSE_cand,p. A candidate passes when
///   (1) Σg / Σ SSE_null >= min_improvement and Σg >= min_excess_share · (Σ SSE_null − n σ²),
///       σ the noise floor (diagnose_noise.h);
///   (2) it improves >= consistency of the parts it changes (|g_p| > 2 % of SSE_null,p), and with
///       several records no record gets materially worse;
///   (3) >= signature_share of its held-out low-frequency gain sits in its own regimes
///       (EffectSpec::regimes), or its gain per sample there is >= signature_density times that
///       elsewhere (signature_holds) — waived when the candidate leaves nothing but noise of a
///       discrepancy of at least signature_waiver_excess σ² (DiagnoseOptions);
/// the winner is the passing candidate with the largest Σg; it is named only when it removes at
/// least min_explained_share of the excess (most of what is missing, not a part). Its confidence is the share of
/// bootstrap resamples of the parts (with replacement) in which it is still the winner among the
/// candidates passing (1), the per-record part of (2) and (3) on the resample (the consistency
/// share of (2) is a requirement on all held-out parts, applied once, not re-drawn);
/// it is added only with confidence >= options.confidence. Confusable effects (EffectSpec::
/// confusable) that also pass are compared part by part and reported as told apart or not.
/// Before any candidate, the residual of the refitted model is tested against the noise floor;
/// when it is indistinguishable from noise the verdict is "nothing significant is missing".

#include "damper/diagnose/diagnose_fit.h"

#include <string>
#include <vector>

namespace damper {

/// A scored unit of held-out samples [begin, end) of a record (fit-rate indices).
struct HeldOutPart {
  std::size_t record = 0, begin = 0, end = 0;
};

/// One fold of the validation plan.
struct Fold {
  std::vector<std::vector<std::uint8_t>> fit_mask;  ///< per record: samples the fits may use
  std::vector<HeldOutPart> parts;                   ///< scored samples
};

/// Folds, the mask of the final fit after an effect is accepted, and a description.
struct ValidationPlan {
  std::vector<Fold> folds;
  std::vector<std::vector<std::uint8_t>> final_mask;
  std::string description;
};

/// Leave-one-record-out with >= 2 records, else held-out cycles (file comment).
ValidationPlan make_validation_plan(const std::vector<DiagnoseRecord>& recs);

/// What one round found.
struct RoundOutcome {
  NoiseReport noise;                    ///< residual of the refitted current model, held-out parts
  std::vector<CandidateScore> scores;   ///< one per candidate tried (empty if nothing is missing)
  int winner = -1;                      ///< index in scores of the accepted effect, -1: none
  ModelState next;                      ///< the model with the winner, refitted on the final mask
  std::vector<std::string> notes;       ///< evidence lines (confusable pairs, signatures)
  std::string stop_reason;              ///< set when the round adds nothing
  /// The accepted effect as fitted: its spec, or the sub-family of it that the data identify
  /// (candidate_subfamilies); later rounds refit it within the same sub-family.
  std::vector<EffectSpec> winner_spec;  ///< empty or one
};

/// Identifiability of a fitted candidate: its parameters that end at an OUTER search bound (a bound
/// that is not the parameter's null value), as "name=value (upper bound)". A null-side bound
/// (slack 0, a share 0) means that part of the family is unused; an outer bound means the data ask
/// for more than the family allows: the shape may be another effect's or stronger than the library
/// reaches, and the fitted values are not identified. Reported with the evidence, not a gate.
std::vector<std::string> parameters_at_outer_bounds(const CandidateScore& c);

/// How concentrated a candidate's held-out gain is in its own regimes: the gain per sample there
/// over the gain per sample elsewhere, (s/t)/((1 − s)/(1 − t)) with s its signature_share and t its
/// own_time_share (1: spread evenly, as a change everywhere gives; 0 when its regimes hold no sample
/// or none of its gain; infinite when all of it).
double signature_density(const CandidateScore& c);

/// The longest settling actuator_settle_s gives: the longest lag the actuator_lag family searches, s.
constexpr double kMaxActuatorSettleS = 1.5;

/// How long after the actuators stop the clamping of a fitted actuator_lag still moves, s: the
/// delay plus three time constants of each lag in its chain (95 % settled: 3 τ_a, ρ_e τ_a for the
/// slower direction; the second-order response's envelope decays at ζω, 3/(ζω) = 3T/(2πζ)), at most
/// kMaxActuatorSettleS; 0 without the effect. Gate (3) counts these samples as the effect's own
/// regime as well as those where the actuators are displaced: its physics acts there as much
/// (blind set 25 t07: a clamping ringing at 1.17 s, ζ 0.31, fitted exactly, removed 97 % of the
/// excess with 33 % of its gain while they were displaced, and was not named).
double actuator_settle_s(const ModelEffects& e);

/// Per sample: the actuators are displaced (Segmentation::actuators_moving) or were, at most
/// settle_s ago.
std::vector<std::uint8_t> moving_or_settling(const Segmentation& seg, double dt_s, double settle_s);

/// Gate (3): the signature holds when at least options.signature_share of the gain sits in the
/// effect's own regimes, or at least options.signature_share_floor of it with a density there of at
/// least options.signature_density.
bool signature_holds(const CandidateScore& c, const DiagnoseOptions& o);

/// The rests in the fitting samples of `mask`: for each rest (Segmentation::rests: the stops
/// between strokes and the final rest) that the mask covers, the measured force held when the drum
/// stopped (mean over the first 10 ms of the rest), kip.
std::vector<double> rest_held_forces(const std::vector<DiagnoseRecord>& recs,
                                     const std::vector<std::vector<std::uint8_t>>& mask);

/// How many distinct rest levels `held_kip` holds: two rests count apart when their held forces have
/// opposite signs or magnitudes more than 15 % (and 0.05 kip) apart.
int distinct_rest_levels(const std::vector<double>& held_kip);

/// The sub-families of `spec` that a round fits and scores; run_round keeps, per candidate, the
/// one with the smallest held-out error (an earlier one unless a later one is better by more than
/// 1 % of the held-out squared error), on every fold: which holds is decided on unseen data.
///  - Identifiability of the rest level (EffectSpec::rest_level): every choice of
///    min(rest_levels, n) of its n rest-level parameters free and the others at their fixed values,
///    ratio first (the classical residual static force), when 0 < rest_levels < n. One rest fixes
///    only where its held force settles: a fit of all of ρ, m and f_o lands anywhere along a valley
///    of equal fits and predicts a rest at another held force at random (bench
///    residual_static/strong: 6 of 6 before m and f_o were added, 1 of 6 after, 6 of 6 with this).
///    The whole family comes last: a settling shape outside the sub-families (a fixed shift of the
///    held force needs m -> 0 with m f_o fixed) is still reached where its fit predicts the unseen
///    rests better (measured: an outside author's fixed shift was named only with it).
///  - Otherwise each mechanism (EffectSpec::mechanisms) alone, the other parameters at their null
///    values or, for an entry "name=value" of the mechanism, at that value (self_energizing's origin
///    of the rotation, drum_start_share=1), with the mechanism's own regimes where it has them
///    (EffectSpec::mechanism_regimes), then the whole family; {spec} when it has no mechanisms.
std::vector<EffectSpec> candidate_subfamilies(const EffectSpec& spec, int rest_levels);

/// Length of the rest over which levels_at_stops takes the level the drum stopped with, s.
constexpr double kStopLevelS = 0.05;

/// The level each rest starts from, for the physics signature at rest: per sample of each rest
/// (Segmentation::rests: the stops between strokes and the final rest), the mean of the
/// low-frequency residual `l` (low_frequency_part, a centred moving average over
/// so.chatter_window_s) over kStopLevelS once that average has left the stroke, i.e. from half its
/// width after the stop; NaN over that first half-width, where `l` still averages the stroke before
/// the stop (counted as the drum's state); 0 outside the rests. Only the change of `l` from this
/// level is the work of an effect acting at rest: an offset carried into the rest from the stroke
/// is nobody's signature. (Twenty-third session: with the level taken from the stop itself, the end
/// of the stroke showed as a change at rest, and set 33 t15's Iwan bank, recovered to the noise
/// floor, had 58 % of its gain counted as a change at rest; docs/diagnose.md.)
std::vector<double> levels_at_stops(const std::vector<double>& l, const Segmentation& seg, double dt_s,
                                    const SegmentationOptions& so);

/// Bootstrap confidence of the choice: for each candidate, the share of o.resamples resamples (with
/// replacement, seeded by `seed`) of the held-out parts in which it is the winner — the passing
/// candidate with the largest gain on the drawn parts. part_record[p] is part p's record, sigma2 the
/// noise variance, kip². Inside a resample every gate of the file comment is re-applied except the
/// consistency gate (2) and the per-record gate, which run_round applies once, on all held-out parts
/// (scores[c].passes): in a resample they would measure how far a candidate sits above their
/// thresholds, or whether the one or two drawn parts of a record are worse, not how stable the choice
/// is (a backlash improving 10 of 12 parts, 87 % of the held-out mean square, was chosen in 68 % of
/// resamples, bench 144 -> 149 of 156; a backlash removing 94 % and better on both records failed
/// the per-record gate in 22 % of resamples, blind set 22 t10; docs/diagnose.md).
std::vector<double> choice_confidence(const std::vector<CandidateScore>& scores, const std::vector<std::size_t>& part_record,
                                      std::size_t records, double sigma2, const DiagnoseOptions& o, unsigned seed);

/// Runs one round of the selection from `current` (effects `added` already added by this run)
/// over the candidates `todo`.
RoundOutcome run_round(int round, const std::vector<DiagnoseRecord>& recs, const ValidationPlan& plan,
                       const ModelState& current, const std::vector<const EffectSpec*>& added,
                       const std::vector<const EffectSpec*>& todo, const DiagnoseOptions& options);

}  // namespace damper
