// The selection engine and the whole workflow on synthetic records (the benchmark's generator,
// damper/diagnose/diagnose_bench.h: two 0.5 Hz ramped drum sinusoids with actuator moves, 2 s at
// rest, white force noise):
//  - a candidate pinned at its null value never wins (every part's gain is exactly 0);
//  - data of the model itself plus noise: the verdict is none and the gap does not grow, from the
//    exact base (--base model) and from bases identified on the passive windows (--base identify,
//    the path where the old workflow credited the base refit to a candidate);
//  - a force offset the drum stops with (inherited from the last stroke) is not named a residual
//    static force, even when residual_static's formula fits it exactly;
//  - the gap never grows when an effect is added, and every added effect beat the model without it
//    (same refit) on held-out data;
//  - the CI subset of `hybridsim diagnose bench` (library effects, shapes that are not library
//    formulas, none): at most one miss, no false positive.
#include "damper/diagnose/diagnose.h"
#include "damper/diagnose/diagnose_bench.h"
#include "damper/diagnose/diagnose_select.h"
#include "damper/fit/identification.h"
#include "damper/model/brfd_config.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <map>
#include <set>

namespace damper {
namespace {

// Two noisy records of `truth` on the benchmark drives (256 Hz: CI-sized).
std::vector<BrfdTest> records_of(const BrfdParams& truth, double noise_kip, unsigned seed) {
  std::vector<BrfdTest> recs = bench_drives(bench_base_model(), 256.0);
  std::mt19937 rng(seed);
  std::normal_distribution<double> nd(0.0, noise_kip);
  for (BrfdTest& t : recs) {
    BrfdParams p = truth;
    p.semiactive.actuator1_initial_in = t.actuator1_in[0];
    p.semiactive.actuator2_initial_in = t.actuator2_in[0];
    BrfdModel m(p);
    for (std::size_t i = 0; i < t.size(); ++i) {
      const DamperInput in{t.drum_disp_in[i], t.drum_vel_in_per_s[i], t.actuator1_in[i], t.actuator2_in[i]};
      t.force_kip.push_back((i == 0 ? m.force_kip(0.0, in) : m.step(in, t.dt_s)) + nd(rng));
    }
  }
  return recs;
}

// The exact base of every record (the bench's base model, x'_k from the record), no effects.
ModelState exact_bases(const std::vector<DiagnoseRecord>& recs) {
  ModelState start;
  for (const DiagnoseRecord& r : recs) {
    BrfdParams b = bench_base_model();
    b.semiactive.actuator1_initial_in = r.test.actuator1_in[0];
    b.semiactive.actuator2_initial_in = r.test.actuator2_in[0];
    start.bases.push_back(b);
  }
  return start;
}

// RMS error of a model state over every sample of the records (kip).
double fit_rms_kip(const std::vector<DiagnoseRecord>& recs, const ModelState& m) {
  double se = 0.0, n = 0.0;
  for (std::size_t k = 0; k < recs.size(); ++k) {
    const std::vector<double> f = simulate(m.params(k), recs[k].test);
    for (std::size_t i = 0; i < f.size(); ++i, n += 1.0) se += std::pow(f[i] - recs[k].test.force_kip[i], 2);
  }
  return std::sqrt(se / n);
}

std::string model_file(const std::string& name) {
  const std::string path = (std::filesystem::temp_directory_path() / ("diagnose_synth_" + name + ".yaml")).string();
  std::ofstream(path) << brfd_params_to_yaml(bench_base_model());
  return path;
}

DiagnoseOptions options_for(const std::vector<BrfdTest>& recs, BaseSource base) {
  DiagnoseOptions o;
  o.model_path = model_file(base == BaseSource::model ? "model" : "identify");
  o.measured_tests = recs;
  o.base = base;
  o.figures = false;
  o.max_effects = 2;
  o.base_identification.global_runs = 1;
  o.base_identification.global_max_evals = 1000;
  o.base_identification.local_max_evals = 400;
  o.base_refit_evals = 50;
  return o;
}

void check_gap_never_grows(const DiagnoseResult& r) {
  EXPECT_LE(r.nrmse_after_mean, r.nrmse_before_mean + 1e-12) << diagnose_final_line(r);
  for (const CandidateScore& c : r.candidates)
    if (c.accepted) {
      EXPECT_LT(c.heldout_rmse_kip, c.heldout_rmse_null_kip) << c.effect;
    }
}

TEST(DiagnoseSelection, CandidatePinnedAtItsNullValueNeverWins) {
  // Hidden backlash and actuator lag: plenty to explain, but every candidate is pinned (bounds
  // lo = hi = null value), so whatever the optimizer does it reproduces the refitted null model.
  BrfdParams truth = bench_base_model();
  truth.effects.backlash = BacklashEffect{0.04, 0.0, 1.0};
  truth.effects.actuator_lag = ActuatorLagEffect{0.25, 0.0, 1.0};
  std::vector<DiagnoseRecord> recs;
  for (const BrfdTest& t : records_of(truth, 0.03, 5)) recs.push_back({t, segment_record(t)});
  std::vector<EffectSpec> pinned = effect_library();
  std::vector<const EffectSpec*> todo;
  for (EffectSpec& s : pinned) {
    for (EffectParameter& p : s.parameters) p.lo = p.hi = p.start = p.null_value;
    todo.push_back(&s);
  }
  const ModelState start = exact_bases(recs);
  for (BaseSource base : {BaseSource::model, BaseSource::identify}) {
    DiagnoseOptions o;
    o.base = base;
    o.effect_evals = 20;
    o.base_refit_evals = 30;
    const RoundOutcome out = run_round(1, recs, make_validation_plan(recs), start, {}, todo, o);
    EXPECT_TRUE(out.noise.structured);
    ASSERT_EQ(out.scores.size(), todo.size());
    EXPECT_EQ(out.winner, -1);
    for (const CandidateScore& c : out.scores) {
      EXPECT_FALSE(c.passes) << c.effect;
      EXPECT_EQ(c.confidence, 0.0) << c.effect;
      for (double g : c.part_gain_kip2) EXPECT_EQ(g, 0.0) << c.effect;
    }
  }
}

// The candidate x fold fits of a round run on several threads (DiagnoseOptions::threads); each
// writes only its own result, so one thread and two give the same scores, bit for bit, and the
// same winner.
TEST(DiagnoseSelection, TheVerdictDoesNotDependOnTheThreadCount) {
  BrfdParams truth = bench_base_model();
  truth.effects.backlash = BacklashEffect{0.04, 0.0, 1.0};
  std::vector<DiagnoseRecord> recs;
  for (const BrfdTest& t : records_of(truth, 0.03, 6)) recs.push_back({t, segment_record(t)});
  std::vector<const EffectSpec*> todo;
  for (const char* name : {"backlash", "actuator_lag", "residual_static", "transition_shape"})
    todo.push_back(&effect_spec(name));
  const ModelState start = exact_bases(recs);
  std::vector<RoundOutcome> outs;
  for (int threads : {1, 2}) {
    DiagnoseOptions o;
    o.base = BaseSource::model;
    o.effect_evals = 20;
    o.threads = threads;
    outs.push_back(run_round(1, recs, make_validation_plan(recs), start, {}, todo, o));
  }
  ASSERT_EQ(outs[0].scores.size(), todo.size());
  ASSERT_EQ(outs[1].scores.size(), todo.size());
  EXPECT_EQ(outs[0].winner, outs[1].winner);
  ASSERT_GE(outs[0].winner, 0);
  EXPECT_EQ(outs[0].scores[static_cast<std::size_t>(outs[0].winner)].effect, "backlash");
  for (std::size_t c = 0; c < todo.size(); ++c) {
    EXPECT_EQ(outs[0].scores[c].theta, outs[1].scores[c].theta) << todo[c]->name;
    EXPECT_EQ(outs[0].scores[c].part_gain_kip2, outs[1].scores[c].part_gain_kip2) << todo[c]->name;
    EXPECT_EQ(outs[0].scores[c].evaluations, outs[1].scores[c].evaluations) << todo[c]->name;
    EXPECT_EQ(outs[0].scores[c].confidence, outs[1].scores[c].confidence) << todo[c]->name;
  }
  EXPECT_EQ(outs[0].next.effects.names(), outs[1].next.effects.names());
}

// A candidate that passes every gate but explains only part of what is missing is not named: the
// truth has a backlash AND an actuator lag, the only candidate is the actuator lag. It passes (its
// gain is real, consistent and in its own regime) but leaves the backlash's share of the excess;
// with the default min_explained_share it is reported as "something is missing that no library
// effect explains", and named only when the requirement is dropped.
TEST(DiagnoseSelection, APartialSurrogateIsReportedNotNamed) {
  BrfdParams truth = bench_base_model();
  truth.effects.backlash = BacklashEffect{0.04, 0.0, 1.0};
  truth.effects.actuator_lag = ActuatorLagEffect{0.25, 0.0, 1.0};
  std::vector<DiagnoseRecord> recs;
  for (const BrfdTest& t : records_of(truth, 0.03, 11)) recs.push_back({t, segment_record(t)});
  const ModelState start = exact_bases(recs);
  const std::vector<const EffectSpec*> todo{&effect_spec("actuator_lag")};
  DiagnoseOptions o;
  o.base = BaseSource::model;
  o.effect_evals = 30;
  const RoundOutcome out = run_round(1, recs, make_validation_plan(recs), start, {}, todo, o);
  ASSERT_EQ(out.scores.size(), 1u);
  const CandidateScore& lag = out.scores[0];
  std::cout << "actuator_lag alone: gain " << lag.heldout_gain << ", excess share " << lag.excess_share << ", "
            << lag.verdict << "\n  " << out.stop_reason << "\n";
  EXPECT_TRUE(lag.passes) << lag.verdict;
  EXPECT_GT(lag.excess_share, 0.1);
  EXPECT_LT(lag.excess_share, o.min_explained_share);
  EXPECT_EQ(out.winner, -1);
  EXPECT_FALSE(lag.accepted);
  EXPECT_EQ(out.stop_reason.rfind("something is missing that no library effect explains: the best candidate, actuator_lag,", 0), 0u)
      << out.stop_reason;
  o.min_explained_share = 0.0;
  const RoundOutcome named = run_round(1, recs, make_validation_plan(recs), start, {}, todo, o);
  EXPECT_EQ(named.winner, 0) << named.stop_reason;
}

// Identifiability caveat: only bounds that are not the parameter's null value count. self_energizing
// with |d| growth at its upper bound 1.2 and the exponent at its lower bound 0.5 (null 1) is flagged
// on both; the drum terms at 0 (null) and a backlash with slack 0 (null side) are not.
TEST(DiagnoseSelection, ParametersAtOuterSearchBoundsAreFlaggedNotNullSideOnes) {
  CandidateScore c;
  c.effect = "self_energizing";
  c.theta = {0.0, 0.0, 1.2, 0.5, 0.1};
  const std::vector<std::string> flagged = parameters_at_outer_bounds(c);
  ASSERT_EQ(flagged.size(), 2u);
  EXPECT_EQ(flagged[0], "drum_abs_per_in=1.2 (upper bound)");
  EXPECT_EQ(flagged[1], "abs_exponent=0.5 (lower bound)");
  c.effect = "backlash";
  c.theta = {0.0, 0.02, 1.0, 1.0, 1.0};  // the whole viscous force in the slack: a share's physical end
  EXPECT_TRUE(parameters_at_outer_bounds(c).empty());
  c.theta = {0.25, 0.02, 10.0, 1.0, 0.0};  // slack and stiffness ratio at their upper bounds
  EXPECT_EQ(parameters_at_outer_bounds(c).size(), 2u);
  c.effect = "residual_static";
  c.theta = {0.5, 0.02, 1.0, 0.0, 1.0};  // relaxation at the fastest the library allows (null: 100 s)
  ASSERT_EQ(parameters_at_outer_bounds(c).size(), 1u);
  EXPECT_EQ(parameters_at_outer_bounds(c)[0], "time_constant_s=0.02 (lower bound)");
}

TEST(DiagnoseSelection, ModelPlusNoiseIsNoneAndTheGapDoesNotGrow) {
  for (BaseSource base : {BaseSource::model, BaseSource::identify}) {
    const DiagnoseResult r = run_diagnose(options_for(records_of(bench_base_model(), 0.05, 3), base));
    std::cout << (base == BaseSource::model ? "[base model] " : "[base identify] ") << diagnose_final_line(r) << "\n  "
              << r.stop_reason << "\n";
    EXPECT_TRUE(r.added.empty()) << diagnose_final_line(r);
    EXPECT_EQ(diagnose_final_line(r).rfind("effects=none ", 0), 0u);
    EXPECT_EQ(diagnose_confidence_line(r).rfind("confidence: none (", 0), 0u) << diagnose_confidence_line(r);
    check_gap_never_grows(r);
  }
}

TEST(DiagnoseSelection, AnOffsetTheDrumStopsWithIsNotAResidualStaticForce) {
  // From the stop on, the measured force is held at 0.5 Fc of the loaded direction: exactly what
  // residual_static (ratio 0.5, short time constant) produces, but already there when the drum
  // stops instead of developing at rest, as a stroke with another transition or speed law leaves
  // it. residual_static takes its whole gain in the rest, and must not be named for it.
  std::vector<BrfdTest> tests = records_of(bench_base_model(), 0.03, 11);
  std::vector<DiagnoseRecord> recs;
  ModelState start;
  for (BrfdTest& t : tests) {
    const Segmentation seg = segment_record(t);
    std::size_t stop = 0;
    while (stop < t.size() && seg.regime[stop] != Regime::after_stop) ++stop;
    ASSERT_LT(stop + 100, t.size());
    BrfdParams b = bench_base_model();
    b.semiactive.actuator1_initial_in = t.actuator1_in[0];
    b.semiactive.actuator2_initial_in = t.actuator2_in[0];
    start.bases.push_back(b);
    const BrfdModel m(b);
    const double held = t.force_kip[stop];
    DamperInput in{t.drum_disp_in[stop], held >= 0.0 ? 1e-9 : -1e-9, t.actuator1_in[stop], t.actuator2_in[stop]};
    const double target = std::copysign(0.5 * m.kinetic_friction_kip(in), held);
    const std::vector<double> clean = [&] {
      std::vector<double> f(t.size());
      BrfdModel mm(b);
      for (std::size_t i = 0; i < t.size(); ++i) {
        const DamperInput x{t.drum_disp_in[i], t.drum_vel_in_per_s[i], t.actuator1_in[i], t.actuator2_in[i]};
        f[i] = i == 0 ? mm.force_kip(0.0, x) : mm.step(x, t.dt_s);
      }
      return f;
    }();
    for (std::size_t i = stop; i < t.size(); ++i) t.force_kip[i] += target - clean[stop];
    recs.push_back({t, seg});
  }
  std::vector<const EffectSpec*> todo{&effect_spec("residual_static")};
  DiagnoseOptions o;
  o.base = BaseSource::model;
  o.effect_evals = 40;
  const RoundOutcome out = run_round(1, recs, make_validation_plan(recs), start, {}, todo, o);
  ASSERT_EQ(out.scores.size(), 1u);
  const CandidateScore& c = out.scores.front();
  std::cout << "residual_static on an offset held from the stop: gain " << c.heldout_rmse_null_kip << " -> "
            << c.heldout_rmse_kip << " kip, own-regime share " << c.signature_share << "\n";
  EXPECT_LT(c.heldout_rmse_kip, 0.8 * c.heldout_rmse_null_kip) << "it does fit the offset";
  EXPECT_LT(c.signature_share, o.signature_share);
  EXPECT_FALSE(c.passes);
  EXPECT_EQ(out.winner, -1);
}

TEST(DiagnoseSelection, ALawOfTheMovingDrumIsNotNamedForAForceCreepingAtRest) {
  // At the final rest the measured force creeps logarithmically from the force the drum stopped
  // with (Dieterich 1972: F_h (1 − 0.06 ln(1 + t/0.2 s))), and the drum speed is the noise of a
  // differentiated displacement there (±0.003 in/s, as in measured records). A rate-and-state law
  // whose capacity falls at that speed lets the held force creep too (blind set 17 t07, named
  // velocity); a law of the moving drum has no mechanism at rest and must not be named for it.
  std::vector<BrfdTest> tests = records_of(bench_base_model(), 0.03, 17);
  std::vector<DiagnoseRecord> recs;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.003, 0.003);
  for (BrfdTest& t : tests) {
    const Segmentation seg = segment_record(t);
    std::size_t stop = 0;
    while (stop < t.size() && seg.regime[stop] != Regime::after_stop) ++stop;
    ASSERT_LT(stop + 100, t.size());
    const double held = t.force_kip[stop];
    for (std::size_t i = stop; i < t.size(); ++i) {
      t.force_kip[i] -= held * 0.15 * std::log1p((i - stop) * t.dt_s / 0.2);
      t.drum_vel_in_per_s[i] = jitter(rng);
    }
    recs.push_back({t, segment_record(t)});
  }
  std::vector<const EffectSpec*> todo{&effect_spec("velocity"), &effect_spec("residual_static")};
  DiagnoseOptions o;
  o.base = BaseSource::model;
  o.effect_evals = 40;
  o.consistency = 0.0;  // here the speed law also harms the strokes; only the rest's gate is tested
  const RoundOutcome out = run_round(1, recs, make_validation_plan(recs), exact_bases(recs), {}, todo, o);
  ASSERT_EQ(out.scores.size(), 2u);
  for (const CandidateScore& c : out.scores)
    std::cout << c.effect << " on a creep at rest: held-out RMSE " << c.heldout_rmse_null_kip << " -> " << c.heldout_rmse_kip
              << " kip, share at the rest " << c.rest_share << ", " << c.verdict << "\n";
  const CandidateScore& velocity = out.scores[0];
  EXPECT_LT(velocity.heldout_rmse_kip, 0.9 * velocity.heldout_rmse_null_kip) << "it does mimic the creep";
  EXPECT_GT(velocity.rest_share, o.max_rest_share);
  EXPECT_FALSE(velocity.passes) << velocity.verdict;
  EXPECT_NE(velocity.verdict.find("final rest"), std::string::npos) << velocity.verdict;
  if (out.winner >= 0) {
    EXPECT_EQ(out.scores[static_cast<std::size_t>(out.winner)].effect, "residual_static");
  }
  EXPECT_EQ(out.scores[1].rest_share, 0.0);  // residual_static acts at rest: its gain there is its own
}

// Gate (3), the signature: a gain spread evenly over the samples (its share in the effect's regimes
// equal to their share of the samples) never holds, however large the regimes; a gain concentrated
// there holds even below half (the refitted model without the effect spreads part of it into
// sliding: a right backlash of the twelfth blind set, 47 % of its gain in 34 % of the samples); a
// sliver of gain in a rare regime does not.
TEST(DiagnoseSelection, SignatureHoldsForAConcentratedGainNotForAnEvenOne) {
  const DiagnoseOptions o;
  auto score = [](double share, double time) {
    CandidateScore c;
    c.signature_share = share;
    c.own_time_share = time;
    return c;
  };
  for (const double t : {0.1, 0.25, 0.34, 0.45}) {
    EXPECT_NEAR(signature_density(score(t, t)), 1.0, 1e-12);
    EXPECT_FALSE(signature_holds(score(t, t), o)) << "even gain, regimes " << t;
  }
  EXPECT_NEAR(signature_density(score(0.47, 0.34)), (0.47 / 0.34) / (0.53 / 0.66), 1e-12);
  EXPECT_TRUE(signature_holds(score(0.47, 0.34), o));   // density 1.72
  EXPECT_FALSE(signature_holds(score(0.21, 0.27), o));  // a wrong backlash of the same set: 0.72
  EXPECT_FALSE(signature_holds(score(0.2, 0.05), o));   // density 4.75, but 80 % of the gain elsewhere
  EXPECT_TRUE(signature_holds(score(0.6, 0.9), o));     // most of the gain in its regimes
  EXPECT_FALSE(signature_holds(score(0.4, 0.0), o));    // regimes that hold no sample
}

// The bootstrap measures how stable the choice is: a resample that draws a record as its one worse
// part does not drop a candidate better on every record (the per-record gate runs once, on all
// held-out parts; blind set 22 t10, a backlash with 94 % of the held-out mean square chosen in only
// 78 % of resamples). Record 1 has a part 1.0 kip² better and one 0.1 kip² worse; record 2 three
// parts 1.0 kip² better. Drawn five parts from five, record 1 appears only as its worse part in
// (4/5)^5 (1 − (4/5)^5) = 22 % of resamples; every resample with one better part gains at least
// 6 % of the held-out mean square (> 5 %), so only the draw of the worse part five times, 1/3125,
// leaves it unchosen.
// Gate (3)'s own regime of actuator_lag: the actuators displaced, and after they return the time its
// fitted chain takes to settle — three time constants of each lag (e^-3 = 5 %), after the delay; a
// second-order response's envelope decays as e^(-ζ ω t), ω = 2π/T.
TEST(DiagnoseSelection, ActuatorLagOwnsTheTimeItsClampingSettlesAfterTheActuatorsStop) {
  ModelEffects e;
  EXPECT_EQ(actuator_settle_s(e), 0.0);
  ActuatorLagEffect a;
  a.time_constant_s = 0.1;
  e.actuator_lag = a;
  EXPECT_NEAR(actuator_settle_s(e), 0.3, 1e-12);
  a.extend_time_ratio = 4.0;  // the slower direction sets it
  e.actuator_lag = a;
  EXPECT_NEAR(actuator_settle_s(e), 1.2, 1e-12);
  a = ActuatorLagEffect{};
  a.delay_s = 0.05;
  a.natural_period_s = 0.4;
  a.damping_ratio = 0.5;
  e.actuator_lag = a;
  const double omega = 2.0 * M_PI / 0.4;
  EXPECT_NEAR(actuator_settle_s(e), 0.05 + 3.0 / (0.5 * omega), 1e-12);
  EXPECT_NEAR(std::exp(-0.5 * omega * (actuator_settle_s(e) - 0.05)), std::exp(-3.0), 1e-12);
  a.natural_period_s = 1.1;  // 1.75 s: capped at the longest lag searched
  a.damping_ratio = 0.3;
  e.actuator_lag = a;
  EXPECT_EQ(actuator_settle_s(e), kMaxActuatorSettleS);

  // The mask: displaced over samples [100, 200) at 100 Hz, settling 0.305 s: own through sample
  // 229 (0.30 s after the last displaced one), then not.
  Segmentation seg;
  seg.actuators_moving.assign(400, 0);
  for (std::size_t i = 100; i < 200; ++i) seg.actuators_moving[i] = 1;
  const std::vector<std::uint8_t> m = moving_or_settling(seg, 0.01, 0.305);
  std::size_t own = 0;
  for (std::size_t i = 0; i < m.size(); ++i) own += m[i];
  EXPECT_EQ(own, 130u);
  EXPECT_EQ(m[99], 0);
  EXPECT_EQ(m[229], 1);
  EXPECT_EQ(m[230], 0);
  EXPECT_EQ(moving_or_settling(seg, 0.01, 0.0), seg.actuators_moving);
}

TEST(DiagnoseSelection, AResampleDrawingARecordAsItsWorsePartStillCountsTheChoice) {
  DiagnoseOptions o;
  CandidateScore c;
  c.effect = "backlash";
  c.part_gain_kip2 = {1.0, -0.1, 1.0, 1.0, 1.0};
  c.part_null_kip2 = std::vector<double>(5, 2.0);
  c.part_samples = std::vector<std::size_t>(5, 1000);
  c.part_noise_kip2 = std::vector<double>(5, 0.01);
  c.signature_share = 1.0;
  c.own_time_share = 0.5;
  c.passes = true;  // every gate on all held-out parts: better on both records, 4 of 5 parts
  const std::vector<std::size_t> part_record{0, 0, 1, 1, 1};
  const double sigma2 = 1e-6;  // kip²: the residual is nearly all excess
  const std::vector<double> confidence = choice_confidence({c}, part_record, 2, sigma2, o, 7u);
  ASSERT_EQ(confidence.size(), 1u);
  EXPECT_GE(confidence[0], 0.97) << "chosen unless the worse part is all that is drawn";
  // The other gates still hold inside a resample: the same candidate with its gain mostly off its
  // own regimes is never chosen.
  c.signature_share = 0.1;
  EXPECT_EQ(choice_confidence({c}, part_record, 2, sigma2, o, 7u)[0], 0.0);
}

// Gate (3) is waived for a candidate that leaves nothing but noise of a large discrepancy: held-out
// mean square within 1.2 σ² (or 3 σ² with 90 % of the excess removed) where the model without it is
// at least 4 σ² (blind set 30 t17: a slack
// that biased the passive window's base everywhere; its backlash left 0.0262 kip of a 0.345 kip
// residual, noise 0.0275, with 10 % of its gain in its regimes). Not for a candidate that leaves
// 10 σ², nor where the model without it is already near the noise (3 σ²: a 'none' record).
TEST(DiagnoseSelection, SignatureGateIsWaivedOnlyForAWholeExplanation) {
  const DiagnoseOptions o;
  const std::vector<std::size_t> part_record{0, 0, 1, 1};
  auto score = [](double null_ms, double after_ms) {
    CandidateScore c;
    c.effect = "backlash";
    c.part_samples = std::vector<std::size_t>(4, 1000);
    c.part_null_kip2 = std::vector<double>(4, 1000.0 * null_ms);
    c.part_gain_kip2 = std::vector<double>(4, 1000.0 * (null_ms - after_ms));
    c.part_noise_kip2 = std::vector<double>(4, 1e-9);
    c.signature_share = 0.1;  // its gain mostly off its own regimes
    c.own_time_share = 0.22;
    c.passes = true;
    return c;
  };
  const double sigma2 = 0.0275 * 0.0275;
  EXPECT_GE(choice_confidence({score(158.0 * sigma2, 0.91 * sigma2)}, part_record, 2, sigma2, o, 7u)[0], 0.99);
  EXPECT_EQ(choice_confidence({score(158.0 * sigma2, 10.0 * sigma2)}, part_record, 2, sigma2, o, 7u)[0], 0.0);
  EXPECT_EQ(choice_confidence({score(3.0 * sigma2, 1.0 * sigma2)}, part_record, 2, sigma2, o, 7u)[0], 0.0);
  // A close shape of the right family: at most 3 σ² left with at least 90 % of the excess removed
  // (set 38 t05: 244 σ² -> 2.5 σ²) is waived too; 2.9 σ² left of 5 σ² (52 % of the excess) is not.
  EXPECT_GE(choice_confidence({score(244.0 * sigma2, 2.5 * sigma2)}, part_record, 2, sigma2, o, 7u)[0], 0.99);
  EXPECT_GE(choice_confidence({score(20.0 * sigma2, 2.8 * sigma2)}, part_record, 2, sigma2, o, 7u)[0], 0.99);
  EXPECT_EQ(choice_confidence({score(5.0 * sigma2, 2.9 * sigma2)}, part_record, 2, sigma2, o, 7u)[0], 0.0);
  EXPECT_EQ(choice_confidence({score(244.0 * sigma2, 3.5 * sigma2)}, part_record, 2, sigma2, o, 7u)[0], 0.0);
  // The waiver is judged once on all parts (CandidateScore::whole_explanation) and kept in every
  // resample: with one part worse (6 σ² left there, 2.25 σ² on all four), resamples that draw it
  // twice leave more than 3 σ² and, judged per resample, drop the candidate.
  CandidateScore uneven = score(244.0 * sigma2, 1.0 * sigma2);
  uneven.part_gain_kip2[3] = 1000.0 * (244.0 - 6.0) * sigma2;
  EXPECT_LT(choice_confidence({uneven}, part_record, 2, sigma2, o, 7u)[0], 0.95) << "judged per resample";
  uneven.whole_explanation = true;
  EXPECT_GE(choice_confidence({uneven}, part_record, 2, sigma2, o, 7u)[0], 0.99) << "judged on all parts";
  // ... and its signature holding, every one is chosen.
  for (const double after : {0.91, 10.0}) {
    CandidateScore c = score(158.0 * sigma2, after * sigma2);
    c.signature_share = 0.9;
    EXPECT_GE(choice_confidence({c}, part_record, 2, sigma2, o, 7u)[0], 0.99) << after;
  }
}

// Identifiability of the rest level: the counting of distinct rests and the sub-families it frees.
TEST(DiagnoseSelection, RestLevelSubfamiliesFreeAsManyParametersAsDistinctRests) {
  EXPECT_EQ(distinct_rest_levels({}), 0);
  EXPECT_EQ(distinct_rest_levels({2.1, 2.2}), 1);    // one sign, 5 % apart: one level
  EXPECT_EQ(distinct_rest_levels({2.1, -2.1}), 2);   // opposite signs
  EXPECT_EQ(distinct_rest_levels({2.0, 1.0}), 2);    // 50 % apart
  EXPECT_EQ(distinct_rest_levels({0.01, 0.04}), 1);  // within 0.05 kip
  EXPECT_EQ(distinct_rest_levels({2.0, 1.0, -1.5}), 3);
  const EffectSpec& rs = effect_spec("residual_static");
  ASSERT_EQ(rs.parameters.size(), 10u);
  // No rest, or as many rests as rest-level parameters: the ring-down (its own mechanism), then the
  // whole family.
  EXPECT_EQ(candidate_subfamilies(rs, 0).size(), 2u);
  EXPECT_EQ(candidate_subfamilies(rs, 4).size(), 2u);
  EXPECT_EQ(candidate_subfamilies(rs, 4).front().parameters.size(), 3u);
  EXPECT_EQ(candidate_subfamilies(rs, 4).back().parameters.size(), 10u);
  // A family without a rest level: the rest count changes nothing.
  EXPECT_EQ(candidate_subfamilies(effect_spec("backlash"), 1).size(), candidate_subfamilies(effect_spec("backlash"), 0).size());
  EXPECT_EQ(candidate_subfamilies(effect_spec("backlash"), 1).back().parameters.size(),
            effect_spec("backlash").parameters.size());
  for (int levels : {1, 2, 3}) {
    std::vector<EffectSpec> subs = candidate_subfamilies(rs, levels);
    // 4 choose `levels` (ratio, relaxed_share, offset_kip, held_change_kip) with the rest law's
    // shape (relaxation exponent 1, tail 0) held, the same with it free, the ring-down alone, then
    // the whole family.
    const std::size_t choices = levels == 2 ? 6u : 4u;
    ASSERT_EQ(subs.size(), 2 * choices + 2) << levels;
    EXPECT_EQ(subs.front().subfamily.rfind("ratio", 0), 0u) << subs.front().subfamily;  // ratio first
    EXPECT_TRUE(subs.back().subfamily.empty());
    EXPECT_EQ(subs.back().parameters.size(), 10u);
    subs.pop_back();
    EXPECT_EQ(subs.back().subfamily.rfind("ring_kip ring_frequency_hz ring_decay_s free;", 0), 0u) << subs.back().subfamily;
    subs.pop_back();
    for (std::size_t s = 0; s < subs.size(); ++s) {
      const EffectSpec& sub = subs[s];
      const bool shape_free = s >= choices;
      ASSERT_EQ(sub.parameters.size(), static_cast<std::size_t>(1 + levels + (shape_free ? 2 : 0))) << sub.subfamily;
      // set() puts the free values in their places and the fixed ones (ratio 0, relaxed_share 1,
      // offset_kip 0, held_change_kip 0) in the others; get() reads the free ones back.
      std::vector<double> theta;
      for (std::size_t j = 0; j < sub.parameters.size(); ++j) theta.push_back(0.3 + 0.1 * static_cast<double>(j));
      ModelEffects e;
      sub.set(e, theta);
      ASSERT_TRUE(e.residual_static.has_value());
      EXPECT_EQ(sub.get(e), theta);
      const std::vector<double> all = rs.get(e);
      // -1: time_constant_s, always free; the ring-down at its null values (no ring)
      const double fixed[] = {0.0, -1.0, 1.0, 0.0, 1.0, 0.0, 0.0, 3.0, 0.5, 0.0};
      EXPECT_EQ(std::find_if(sub.parameters.begin(), sub.parameters.end(),
                             [](const EffectParameter& q) { return q.name == "relaxation_exponent"; }) != sub.parameters.end(),
                shape_free)
          << sub.subfamily;
      EXPECT_EQ(std::find_if(sub.parameters.begin(), sub.parameters.end(),
                             [](const EffectParameter& q) { return q.name == "relaxation_tail"; }) != sub.parameters.end(),
                shape_free)
          << sub.subfamily;
      for (std::size_t j = 0; j < 10; ++j) {
        const auto at = std::find_if(sub.parameters.begin(), sub.parameters.end(),
                                     [&](const EffectParameter& q) { return q.name == rs.parameters[j].name; });
        if (at != sub.parameters.end()) {
          EXPECT_DOUBLE_EQ(all[j], theta[static_cast<std::size_t>(at - sub.parameters.begin())]) << sub.subfamily << " " << rs.parameters[j].name;
        } else {
          EXPECT_DOUBLE_EQ(all[j], fixed[j]) << sub.subfamily << " " << rs.parameters[j].name;
        }
      }
    }
  }
}

// Each mechanism of a family alone, the other parameters at their null values, then the whole
// family: a mechanism at its null value is the whole family's null (the model without the effect).
TEST(DiagnoseSelection, MechanismSubfamiliesHoldTheOtherParametersAtTheirNullValues) {
  for (const EffectSpec& spec : effect_library()) {
    const std::vector<EffectSpec> subs = candidate_subfamilies(spec, 0);
    ASSERT_EQ(subs.size(), spec.mechanisms.size() + 1) << spec.name;
    EXPECT_EQ(subs.back().parameters.size(), spec.parameters.size()) << spec.name;
    std::set<std::string> covered;  // a parameter may serve two mechanisms (self_energizing's origin of d)
    for (std::size_t m = 0; m < spec.mechanisms.size(); ++m) {
      const EffectSpec& sub = subs[m];
      // Entries "name=value" hold a parameter at that value in this mechanism (the origin of d).
      std::map<std::string, double> held;
      std::size_t free_count = 0;
      for (const std::string& entry : spec.mechanisms[m]) {
        const std::size_t eq = entry.find('=');
        if (eq == std::string::npos) {
          ++free_count;
        } else {
          held[entry.substr(0, eq)] = std::stod(entry.substr(eq + 1));
          covered.insert(entry.substr(0, eq));
        }
      }
      ASSERT_EQ(sub.parameters.size(), free_count) << sub.subfamily;
      for (const EffectParameter& p : sub.parameters) covered.insert(p.name);
      std::vector<double> theta;
      for (const EffectParameter& p : sub.parameters) theta.push_back(0.5 * (p.lo + p.hi));
      ModelEffects e;
      sub.set(e, theta);
      const std::vector<double> all = spec.get(e);
      for (std::size_t j = 0; j < spec.parameters.size(); ++j) {
        const auto it = std::find_if(sub.parameters.begin(), sub.parameters.end(),
                                     [&](const EffectParameter& p) { return p.name == spec.parameters[j].name; });
        const auto h = held.find(spec.parameters[j].name);
        const double null_or_held = h == held.end() ? spec.parameters[j].null_value : h->second;
        const double want = it == sub.parameters.end() ? null_or_held
                                                       : theta[static_cast<std::size_t>(it - sub.parameters.begin())];
        EXPECT_DOUBLE_EQ(all[j], want) << sub.subfamily << " " << spec.parameters[j].name;
      }
    }
    if (!spec.mechanisms.empty() && spec.rest_level.empty()) {  // (residual_static: the rest levels besides)
      EXPECT_EQ(covered.size(), spec.parameters.size()) << spec.name << ": every parameter belongs to a mechanism";
    }
  }
  // self_energizing: the rotation (on both levels and on Fc only) and the band spring each from the
  // start and from the drum's zero, the stroke wrap (on g, on Fc only), the self-servo (on g, on Fc
  // only), the self-servo by direction (on g, on Fc only), the self-servo through its lag (per kip;
  // relative and per kip), the brake factor by the level (on g, on Fc only), the whole family. The band spring, a force in parallel with the friction, has its own regimes
  // (every state of the drum but the final rest); the self-servo and the brake factor act through
  // the loop after a reversal too; the others keep the family's.
  const std::vector<EffectSpec> se = candidate_subfamilies(effect_spec("self_energizing"), 0);
  EXPECT_EQ(se.size(), 17u);
  for (std::size_t k = 0; k + 1 < se.size(); ++k) {
    const EffectSpec& sub = se[k];
    auto has = [&sub](const char* name) {
      return std::find_if(sub.parameters.begin(), sub.parameters.end(),
                          [name](const EffectParameter& p) { return p.name == name; }) != sub.parameters.end();
    };
    const std::vector<std::string> want =
        has("band_spring_kip_per_in") ? std::vector<std::string>{"sliding", "actuators", "reversal", "sticking"}
        : has("band_force_per_kip") || has("brake_factor_per_kip") ? std::vector<std::string>{"sliding", "actuators", "reversal"}
                                      : effect_spec("self_energizing").regimes;
    EXPECT_EQ(sub.regimes, want) << sub.subfamily;
  }
  EXPECT_EQ(se.back().regimes, effect_spec("self_energizing").regimes) << "the whole family";
  // slack band, take-up, by stroke, re-engagement, impact, impact pair, play; the slack band, take-up
  // and impact pair with the play taken up by the first motion; whole
  EXPECT_EQ(candidate_subfamilies(effect_spec("backlash"), 0).size(), 12u);
}

// model-updated.yaml's LuGre block (identify mode) is fitted only on passive windows that identify
// the LuGre parameters (window_does_not_identify): records whose actuators move from their first
// 0.3 s keep the model file's block (fitted on such windows it gave an outside author's records NRMSE
// 0.54 where the model file's block gives 0.16, and the named effect was dropped).
TEST(DiagnoseSelection, JointLugreOfTheUpdatedModelUsesOnlyWindowsThatIdentify) {
  BrfdParams truth = bench_base_model();
  truth.lugre.sigma0_kip_per_in *= 1.5;  // a base the passive windows can see
  std::vector<DiagnoseRecord> recs;
  for (BrfdTest& t : records_of(truth, 0.02, 5)) recs.push_back({t, segment_record(t)});
  const BrfdParams model = bench_base_model();
  const LugreParams identified = joint_passive_lugre(recs, model, model.effects, 200);
  EXPECT_GT(identified.sigma0_kip_per_in, 1.2 * model.lugre.sigma0_kip_per_in) << "long passive windows: fitted";
  for (DiagnoseRecord& r : recs) r.seg.passive_end = static_cast<std::size_t>(0.3 / r.test.dt_s);
  const LugreParams kept = joint_passive_lugre(recs, model, model.effects, 200);
  EXPECT_EQ(kept.fc_fwd_kip, model.lugre.fc_fwd_kip);
  EXPECT_EQ(kept.sigma0_kip_per_in, model.lugre.sigma0_kip_per_in);
  EXPECT_EQ(kept.vs_in_per_s, model.lugre.vs_in_per_s);
}

// A residual static force (rest level 0.8 Fc) on the two benchmark drives, which stop holding
// different forces: each fold's fitting data hold one rest, which fixes only where that held force
// settles. Fitted with all of ρ, m and f_o free, fold 1's fit lands elsewhere on the valley of equal
// fits and predicts the other drive's rest worse than the model without it (measured: held-out
// gain −30 %, nothing named). With one rest-level parameter free per rest, chosen on the held-out
// rests, the effect is named and removes most of the held-out residual.
TEST(DiagnoseSelection, OneRestPerRecordIsFittedWithOneRestLevelParameter) {
  BrfdParams truth = bench_base_model();
  effect_spec("residual_static").set(truth.effects, {0.8, 0.1, 1.0, 0.0, 1.0, 0.0, 0.0, 3.0, 0.5, 0.0});
  std::vector<DiagnoseRecord> recs;
  for (BrfdTest& t : records_of(truth, 0.02, 21)) {
    const Segmentation seg = segment_record(t);
    recs.push_back({t, seg});
  }
  const std::vector<double> held = rest_held_forces(recs, make_validation_plan(recs).final_mask);
  ASSERT_EQ(held.size(), 2u);
  std::cout << "held forces at the stops: " << held[0] << ", " << held[1] << " kip\n";
  std::vector<const EffectSpec*> todo{&effect_spec("residual_static")};
  DiagnoseOptions o;
  o.base = BaseSource::model;
  o.effect_evals = 60;
  const RoundOutcome out = run_round(1, recs, make_validation_plan(recs), exact_bases(recs), {}, todo, o);
  ASSERT_EQ(out.scores.size(), 1u);
  const CandidateScore& c = out.scores.front();
  std::cout << "residual_static, " << c.subfamily << ": held-out RMSE " << c.heldout_rmse_null_kip << " -> "
            << c.heldout_rmse_kip << " kip (" << c.verdict << ")\n";
  for (const std::string& n : out.notes) std::cout << n << "\n";
  EXPECT_FALSE(c.subfamily.empty());
  // Three of the four rest-level parameters fixed (the relaxation exponent too unless freeing it
  // predicts the unseen rest better, and the ring-down, its own sub-family).
  EXPECT_EQ(std::count_if(c.fixed_parameters.begin(), c.fixed_parameters.end(),
                          [](const std::string& n) {
                            return n == "ratio" || n == "relaxed_share" || n == "offset_kip" || n == "held_change_kip";
                          }),
            3);
  EXPECT_GT(c.heldout_gain, 0.5);
  EXPECT_EQ(out.winner, 0) << out.stop_reason;
  ASSERT_EQ(out.winner_spec.size(), 1u);
  EXPECT_EQ(out.winner_spec.front().subfamily, c.subfamily);
}

// Identify mode's second start: a base identified on the passive window WITHOUT the hidden effect
// absorbs part of it. Hidden elasto-plastic pre-sliding (in transition_shape's family); the fit
// starts from bases identified without effects. With the model file's LuGre block as second start
// (ModelState::file_lugre) the family comes back near the truth and the fitting error to about the
// noise (0.0205 kip for σ 0.02; from the identified bases alone 0.28 kip, measured when written):
// the test fails if fit_model ignores the second start.
TEST(DiagnoseSelection, SecondStartFromTheModelFileRecoversAnEffectTheIdentifiedBaseAbsorbed) {
  BrfdParams truth = bench_base_model();
  truth.effects.transition_shape = TransitionShapeEffect{1.0, 1.0, 0.3};
  const double noise = 0.02;
  std::vector<DiagnoseRecord> recs;
  for (const BrfdTest& t : records_of(truth, noise, 17)) recs.push_back({t, segment_record(t)});
  ModelState identified = exact_bases(recs);
  IdentificationOptions io;
  io.global_runs = 1;
  io.global_max_evals = 1500;
  io.local_max_evals = 500;
  for (std::size_t k = 0; k < recs.size(); ++k) {
    io.t0_s = 0.0;
    io.t1_s = recs[k].test.time_s[recs[k].seg.passive_end];
    identified.bases[k] = identify_lugre(recs[k].test, identified.bases[k], io).params;
  }
  std::vector<std::vector<std::uint8_t>> mask;
  for (const DiagnoseRecord& r : recs) mask.push_back(std::vector<std::uint8_t>(r.test.size(), 1));
  FitSettings fs;
  fs.base = BaseSource::identify;
  const FitSpace space{{&effect_spec("transition_shape")}};
  auto rms = [&recs](const ModelState& m) { return fit_rms_kip(recs, m); };
  const ModelState alone = fit_model(recs, identified, space, mask, fs);
  ModelState with_file = identified;
  with_file.file_lugre = bench_base_model().lugre;
  const ModelState both = fit_model(recs, with_file, space, mask, fs);
  const TransitionShapeEffect& t = *both.effects.transition_shape;
  std::cout << "identified base only: RMS " << rms(alone) << " kip; with the second start: " << rms(both)
            << " kip (exponent " << t.exponent << ", elastic_unloading " << t.elastic_unloading << ", breakaway "
            << t.breakaway_ratio << "); noise " << noise << " kip\n";
  EXPECT_LT(rms(both), 1.5 * noise);
  EXPECT_LE(rms(both), rms(alone));
  EXPECT_NEAR(t.elastic_unloading, 1.0, 0.15);
  EXPECT_NEAR(t.breakaway_ratio, 0.3, 0.1);
}

// refine_from_starts (diagnose_fit.h): a fit that ended short of its objective's floor continues
// from another fold's optimum when that fits the same samples better, and keeps its own result when
// the start fits worse. Hidden drum rotation counted from the start (κ_fwd 0.1, κ_bwd -0.1 /in); the
// short fit is LN_BOBYQA from the null with 5 evaluations and no scan; the refinement has diagnose's
// default budget. Fails if the better start is ignored, or if a worse start is taken.
TEST(DiagnoseSelection, AFitContinuesFromAnotherFoldsOptimumOnlyWhereItFitsTheSameSamplesBetter) {
  const EffectSpec& whole = effect_spec("self_energizing");
  const EffectSpec rotation = candidate_subfamilies(whole, 0).front();  // the rotation, from the start
  ASSERT_NE(rotation.subfamily.find("drum_start_share=1"), std::string::npos) << rotation.subfamily;
  BrfdParams truth = bench_base_model();
  rotation.set(truth.effects, {0.1, -0.1, 0.0, 1.0});
  const double noise = 0.02;
  std::vector<DiagnoseRecord> recs;
  for (const BrfdTest& t : records_of(truth, noise, 29)) recs.push_back({t, segment_record(t)});
  std::vector<std::vector<std::uint8_t>> mask;
  for (const DiagnoseRecord& r : recs) mask.push_back(std::vector<std::uint8_t>(r.test.size(), 1));
  FitSettings fs;  // the refinement: diagnose's default budget
  fs.base = BaseSource::model;
  FitSettings short_settings = fs;
  short_settings.effect_evals = 5;
  short_settings.iterations = 1;
  short_settings.scan = false;
  const FitSpace space{{&rotation}};
  auto rms = [&recs](const ModelState& m) { return fit_rms_kip(recs, m); };
  const ModelState short_fit = fit_model(recs, exact_bases(recs), space, mask, short_settings);
  ASSERT_GT(rms(short_fit), 1.5 * noise) << "the short fit must end short for this test to mean anything";

  ModelEffects near_truth;
  rotation.set(near_truth, {0.09, -0.11, 0.0, 1.0});  // another fold's optimum: near, not exact
  const ModelState refined = refine_from_starts(recs, short_fit, space, mask, fs, {near_truth});
  const std::vector<double> theta = rotation.get(refined.effects);
  std::cout << "short fit RMS " << rms(short_fit) << " kip; continued from the other optimum " << rms(refined)
            << " kip (kappa_fwd " << theta[0] << ", kappa_bwd " << theta[1] << "); noise " << noise << " kip\n";
  EXPECT_LT(rms(refined), 1.1 * noise);
  EXPECT_NEAR(theta[0], 0.1, 0.01);
  EXPECT_NEAR(theta[1], -0.1, 0.01);

  ModelEffects worse;
  rotation.set(worse, {-0.5, 0.5, 0.0, 1.0});
  const ModelState kept = refine_from_starts(recs, short_fit, space, mask, fs, {worse});
  EXPECT_EQ(rotation.get(kept.effects), rotation.get(short_fit.effects));
  EXPECT_EQ(rms(kept), rms(short_fit));
}

TEST(DiagnoseSelection, GapNeverGrowsWhenAnEffectIsAdded) {
  BrfdParams truth = bench_base_model();
  truth.effects.residual_static = ResidualStaticEffect{};
  truth.effects.residual_static->ratio = 0.5;
  truth.effects.residual_static->time_constant_s = 0.2;
  for (BaseSource base : {BaseSource::model, BaseSource::identify}) {
    DiagnoseOptions o = options_for(records_of(truth, 0.03, 9), base);
    // The confusable group of residual_static (CI time: the full library runs in the benchmark).
    o.candidates = {"residual_static", "backlash", "transition_shape"};
    o.max_effects = 1;
    const DiagnoseResult r = run_diagnose(o);
    std::cout << diagnose_confidence_line(r) << "\n" << diagnose_final_line(r) << "\n";
    ASSERT_FALSE(r.added.empty());
    EXPECT_EQ(r.added.front(), "residual_static");
    EXPECT_GE(r.added_confidence.front(), 0.8);
    check_gap_never_grows(r);
    EXPECT_LT(r.nrmse_after_mean, 0.5 * r.nrmse_before_mean);
  }
}

// Every case of the full matrix builds its truth on a bench drive (a library case whose parameter
// vector no longer matches its family throws here, not an hour into the benchmark), and every
// effect case differs from the base model by more than the benchmark's lower noise level.
TEST(DiagnoseBench, EveryCaseOfTheFullMatrixGeneratesItsHiddenEffect) {
  const BrfdParams base = bench_base_model();
  const std::vector<BrfdTest> drives = bench_drives(base, 512.0);
  ASSERT_FALSE(drives.empty());
  const BrfdTest& drive = drives.front();
  for (const BenchCase& c : bench_cases(false)) {
    if (c.records) continue;  // damper/synthetic shapes bring their own records
    std::vector<double> truth;
    ASSERT_NO_THROW(truth = c.truth(drive, base)) << c.name;
    ASSERT_EQ(truth.size(), drive.size()) << c.name;
    if (c.family == "none") continue;
    double rms = 0.0;
    std::vector<double> without;
    for (const BenchCase& n : bench_cases(false))
      if (n.family == "none" && !n.records) without = n.truth(drive, base);
    ASSERT_EQ(without.size(), truth.size());
    for (std::size_t i = 0; i < truth.size(); ++i) rms += (truth[i] - without[i]) * (truth[i] - without[i]);
    rms = std::sqrt(rms / truth.size());
    EXPECT_GT(rms, 0.02) << c.name << ": the hidden effect changes the force by " << rms << " kip RMS";
  }
}

TEST(DiagnoseBench, CiSubsetIsCorrectWithoutFalsePositives) {
  BenchOptions bo;
  bo.quick = true;
  bo.log = [](const std::string& s) { std::cout << s << "\n"; };
  const BenchResult r = run_diagnose_bench(bo);
  EXPECT_EQ(r.trials.size(), 5u);
  EXPECT_EQ(r.false_positive, 0);
  // Library backlash and actuator lag, the weight-law backlash and friction growing with d² (not
  // library formulas), none: the full matrix (docs/diagnose.md) gets these right in most trials;
  // at most one miss here.
  EXPECT_GE(r.correct, static_cast<int>(r.trials.size()) - 1) << bench_final_line(r);
}

}  // namespace
}  // namespace damper
