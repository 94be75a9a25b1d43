#include "damper/diagnose/diagnose.h"

#include "common/number_format.h"
#include "common/parallel_for.h"
#include "damper/model/brfd_config.h"
#include "damper/diagnose/diagnose_fit.h"
#include "damper/diagnose/diagnose_report.h"
#include "damper/diagnose/diagnose_select.h"
#include "damper/fit/predict.h"

#include <algorithm>
#include <deque>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

namespace fs = std::filesystem;

namespace damper {

namespace {

using common::format_significant;

using Log = std::function<void(const std::string&)>;

// The passive window of a record as `damper predict` takes it: [t0, first actuator motion); records
// whose actuators never move: the split's passive window (predict: --fit-window 0:T1).
double passive_window_end_s(const DiagnoseRecord& r, const DiagnoseOptions& o) {
  const std::optional<double> t = first_actuator_motion_s(r.test, o.segmentation.actuator_motion_threshold_in);
  if (t) return *t;
  return r.seg.passive_end < r.test.size() ? r.test.time_s[r.seg.passive_end] : r.test.time_s.back() + r.test.dt_s;
}

// The base of a record for "before"/"after": identified on its passive window exactly as
// `damper predict` does (identify), or `p` as is (model).
BrfdParams record_base(const DiagnoseRecord& r, const BrfdParams& p, const DiagnoseOptions& o, double* window_rmse,
                       std::string* not_identified = nullptr, std::string* identification_note = nullptr) {
  BrfdParams b = for_record(p, r.test);
  if (o.base != BaseSource::identify) return b;
  IdentificationOptions io = o.base_identification;
  io.t0_s = r.test.time_s.front();
  io.t1_s = passive_window_end_s(r, o);
  const std::string obstacle = window_does_not_identify(r.test, b, io);
  if (!obstacle.empty()) {  // e.g. the actuators move from the start: the model file's LuGre
    if (window_rmse) *window_rmse = 0.0;
    if (not_identified) *not_identified = obstacle;
    return b;
  }
  const IdentificationResult id = identify_lugre(r.test, b, io);
  if (window_rmse) *window_rmse = id.residual.rmse_kip;
  if (not_identified && !id.identified) *not_identified = id.note;
  if (identification_note && id.identified) *identification_note = id.note;  // e.g. Fs/Fc kept (min_stribeck_speeds)
  return id.params;
}

// 1. Records (read, split, regimes) and their "before" bases.
std::vector<DiagnoseRecord> load_records(const DiagnoseOptions& o, const BrfdParams& model, DiagnoseResult& result,
                                         ModelState& before, const Log& log) {
  std::vector<DiagnoseRecord> recs;
  before.effects = model.effects;
  if (o.base == BaseSource::identify) before.file_lugre = model.lugre;  // the fits' second start
  std::vector<std::string> paths;
  if (!o.measured.empty() || o.measured_tests.empty()) paths = expand_measured_paths(o.measured);
  // Read and split every record, then identify their bases in parallel (independent fits), then
  // report in record order.
  const std::size_t n_records = paths.size() + o.measured_tests.size();
  for (std::size_t m = 0; m < n_records; ++m) {
    DiagnoseRecord r;
    r.test = m < paths.size() ? read_measured_record(paths[m], o.read) : o.measured_tests[m - paths.size()];
    if (r.test.has_actuator_positions && o.actuator_smoothing_s > 0.0) {
      const int hw = static_cast<int>(std::lround(0.5 * o.actuator_smoothing_s / r.test.dt_s));
      if (hw > 0) {
        r.test.actuator1_in = centered_moving_average(r.test.actuator1_in, hw);
        r.test.actuator2_in = centered_moving_average(r.test.actuator2_in, hw);
      }
    }
    r.seg = segment_record(r.test, o.segmentation);
    recs.push_back(std::move(r));
  }
  std::vector<BrfdParams> bases(n_records);
  std::vector<double> window_rmses(n_records, 0.0);
  std::vector<std::string> not_identifieds(n_records), identification_notes(n_records);
  common::parallel_for(n_records, o.threads, [&](std::size_t m) {
    bases[m] = record_base(recs[m], model, o, &window_rmses[m], &not_identifieds[m], &identification_notes[m]);
  });
  for (std::size_t m = 0; m < n_records; ++m) {
    const DiagnoseRecord& r = recs[m];
    for (const std::string& n : r.test.notes) log(n);
    const double t_passive = passive_window_end_s(r, o);
    const double window_rmse = window_rmses[m];
    const std::string& not_identified = not_identifieds[m];
    const BrfdParams& base = bases[m];
    if (o.base == BaseSource::identify && !not_identified.empty())
      log(r.test.name() + ": base LuGre from the model file (" + not_identified + ")");
    else if (o.base == BaseSource::identify)
      log(r.test.name() + ": base LuGre identified on the passive window 0-" + format_significant(t_passive, 4) + " s (residual there " +
          format_significant(window_rmse, 4) + " kip RMSE)" +
          (identification_notes[m].empty() ? std::string() : "; " + identification_notes[m]));
    double train_s = 0.0, held_s = 0.0;
    for (std::uint8_t t : r.seg.train) (t ? train_s : held_s) += r.test.dt_s;
    std::ostringstream sp;
    sp << r.test.name() << ": " << r.test.size() << " samples at " << format_significant(1.0 / r.test.dt_s, 4) << " Hz, passive window 0-"
       << format_significant(t_passive, 4) << " s" << (r.seg.actuated ? " (before the first actuator motion)" : " (actuators never move)")
       << ", " << r.seg.reversals.size() << " reversals, rest from "
       << (r.seg.rest_begin < r.test.size() ? format_significant(r.test.time_s[r.seg.rest_begin], 4) + " s" : std::string("- (none)"));
    log(sp.str());
    BrfdParams b = base;
    b.effects = ModelEffects{};
    before.bases.push_back(b);
    RecordReport rep;
    rep.name = r.test.name();
    rep.path = r.test.path;
    rep.dt_s = r.test.dt_s;
    rep.passive_end_s = t_passive;
    rep.train_s = train_s;
    rep.heldout_s = held_s;
    rep.base_params = base;
    result.records.push_back(rep);
  }
  log(std::string("base parameters: ") +
      (o.base == BaseSource::identify
           ? "LuGre identified on each record's passive window, as `hybridsim damper predict` does (re-identified "
             "there with the effects in every fit, for the model with and without a candidate alike)"
           : "the --model file as is (x'_1, x'_2 from each record's first row)"));
  if (!model.effects.empty()) log("the --model file already holds effects: " + model.effects.names());
  return recs;
}

// 2. Residual of the model as it is, localized in regimes and windows.
std::vector<std::vector<double>> localize_before(const std::vector<DiagnoseRecord>& recs, const ModelState& before,
                                                 const DiagnoseOptions& o, DiagnoseResult& result, const Log& log) {
  std::vector<std::vector<double>> pred(recs.size());
  RegimeEnergy all;
  for (std::size_t k = 0; k < recs.size(); ++k) {
    pred[k] = simulate(before.params(k), recs[k].test);
    std::vector<double> res(pred[k].size());
    for (std::size_t i = 0; i < res.size(); ++i) res[i] = pred[k][i] - recs[k].test.force_kip[i];
    result.records[k].energy_before = localize(res, recs[k].seg, recs[k].test.dt_s, o.segmentation);
    all += result.records[k].energy_before;
    const std::vector<ResidualWindow> w =
        residual_windows(recs[k].test.name(), recs[k].test.time_s, res, recs[k].seg, recs[k].test.dt_s, o.segmentation);
    result.top_windows.insert(result.top_windows.end(), w.begin(), w.end());
  }
  std::sort(result.top_windows.begin(), result.top_windows.end(),
            [](const ResidualWindow& a, const ResidualWindow& b) { return a.energy > b.energy; });
  if (result.top_windows.size() > 10) result.top_windows.resize(10);
  log("");
  log("== Where the model disagrees (residual = model - measured, before) ==");
  for (const std::string& l : format_regime_table(result.records, all)) log(l);
  log("time windows holding the most residual energy:");
  for (const std::string& l : format_windows(result.top_windows, all.total())) log(l);
  return pred;
}

// The records decimated to about o.fit_rate_hz (every k-th sample, k >= 1; k = 1 for fit_rate_hz 0,
// the records' own rate), as the fits see them.
std::vector<DiagnoseRecord> decimated_for_fits(const std::vector<DiagnoseRecord>& recs, const DiagnoseOptions& o) {
  std::vector<DiagnoseRecord> frecs;
  for (const DiagnoseRecord& r : recs) {
    const std::size_t k =
        o.fit_rate_hz <= 0.0
            ? 1
            : std::max<std::size_t>(
                  1, static_cast<std::size_t>(std::floor(1.0 / (r.test.dt_s * std::max(1.0, o.fit_rate_hz)) + 1e-9)));
    frecs.push_back(decimate(r, k));
  }
  return frecs;
}

// 3. Rounds of the selection on records decimated to about fit_rate_hz. Returns the final state.
ModelState select_effects(const std::vector<DiagnoseRecord>& recs, const ModelState& before,
                          const std::vector<const EffectSpec*>& library, const DiagnoseOptions& o, DiagnoseResult& result,
                          const Log& log) {
  const std::vector<DiagnoseRecord> frecs = decimated_for_fits(recs, o);
  const ValidationPlan plan = make_validation_plan(frecs);
  result.validation = plan.description;
  log("");
  log("== Is anything missing? (candidates fitted and scored on unseen data) ==");
  log("validation: " + plan.description);
  ModelState current = before;
  std::vector<const EffectSpec*> added;
  std::deque<EffectSpec> added_specs;  // the accepted effects as fitted (a sub-family where the data identify only one)
  for (int round = 1; round <= o.max_effects; ++round) {
    std::vector<const EffectSpec*> todo;
    for (const EffectSpec* s : library)
      if (!s->present(current.effects)) todo.push_back(s);
    if (todo.empty()) {
      result.stop_reason = "every candidate effect is in the model";
      break;
    }
    RoundOutcome r = run_round(round, frecs, plan, current, added, todo, o);
    log("");
    log("round " + std::to_string(round) + ": " + r.noise.summary);
    result.noise.push_back(r.noise);
    if (!r.scores.empty()) {
      for (const std::string& l : format_candidate_table(r.scores)) log(l);
      for (const std::string& n : r.notes) {
        log("  " + n);
        result.notes.push_back("round " + std::to_string(round) + ": " + n);
      }
    }
    result.candidates.insert(result.candidates.end(), r.scores.begin(), r.scores.end());
    if (r.winner < 0) {
      result.stop_reason = r.stop_reason;
      break;
    }
    const CandidateScore& w = r.scores[static_cast<std::size_t>(r.winner)];
    log(format_evidence(w));
    const std::vector<std::string> at_bounds = parameters_at_outer_bounds(w);
    if (!at_bounds.empty()) {
      std::string list;
      for (const std::string& b : at_bounds) list += (list.empty() ? "" : ", ") + b;
      const std::string note = "round " + std::to_string(round) + ": " + w.effect +
                               " ends with parameters at an outer search bound (" + list +
                               "): the data ask for more than the family allows, so the shape may be another "
                               "effect's and these values are not identified; the name is the library's best "
                               "explanation, not a measured mechanism";
      log("  caution: " + note.substr(note.find(": ") + 2));
      result.notes.push_back(note);
    }
    current = r.next;
    added_specs.push_back(r.winner_spec.empty() ? effect_spec(w.effect) : r.winner_spec.front());
    added.push_back(&added_specs.back());
    result.added.push_back(w.effect);
    result.added_confidence.push_back(w.confidence);
    if (round == o.max_effects) result.stop_reason = "reached --max-effects " + std::to_string(o.max_effects);
  }
  if (result.stop_reason.empty()) result.stop_reason = "--max-effects " + std::to_string(o.max_effects);
  log("");
  log("stop: " + result.stop_reason);
  return current;
}

// Parameters as model-updated.yaml gives them back (written and read through the loader, so that
// "after" is computed from exactly what the file holds).
BrfdParams through_yaml(const BrfdParams& p, const std::string& dir) {
  const fs::path tmp = fs::path(dir.empty() ? fs::temp_directory_path().string() : dir) /
                       (".diagnose-roundtrip-" + std::to_string(::getpid()) + ".yaml");
  fs::create_directories(tmp.parent_path());
  {
    std::ofstream f(tmp);
    if (!f) throw std::runtime_error("cannot write " + tmp.string());
    f << brfd_params_to_yaml(p);
  }
  BrfdParams q = load_brfd_params(tmp.string());
  fs::remove(tmp);
  return q;
}

// 4. The updated model and the gap per record, "after" computed exactly as `damper predict` does
// with model-updated.yaml. The gap never grows: effects are dropped from the last while the mean
// NRMSE after exceeds the mean before.
void final_gap(const std::vector<DiagnoseRecord>& recs, const BrfdParams& model, ModelEffects effects,
               const std::vector<std::vector<double>>& pred_before, const DiagnoseOptions& o, DiagnoseResult& result,
               const Log& log) {
  const std::vector<DiagnoseRecord> frecs = decimated_for_fits(recs, o);
  double sum_before = 0.0;
  for (std::size_t k = 0; k < recs.size(); ++k) {
    result.records[k].before = force_error(recs[k].test.force_kip, pred_before[k], 0, recs[k].test.size());
    sum_before += result.records[k].before.nrmse_std;
  }
  result.nrmse_before_mean = sum_before / static_cast<double>(recs.size());
  std::vector<std::vector<double>> after(recs.size());
  for (;;) {
    result.updated_params = model;
    result.updated_params.effects = effects;
    if (o.base == BaseSource::identify && !result.added.empty())
      result.updated_params.lugre = joint_passive_lugre(frecs, model, effects, 400);
    const BrfdParams file = through_yaml(result.updated_params, o.out_dir);
    double sum_after = 0.0, max_after = 0.0;
    common::parallel_for(recs.size(), o.threads, [&](std::size_t k) {  // independent per record
      RecordReport& rep = result.records[k];
      if (result.added.empty()) {
        rep.final_params = rep.base_params;
        after[k] = pred_before[k];
      } else {
        rep.final_params = record_base(recs[k], file, o, nullptr);
        after[k] = simulate(rep.final_params, recs[k].test);
      }
      rep.after = force_error(recs[k].test.force_kip, after[k], 0, recs[k].test.size());
      rep.updated_config = force_error(recs[k].test.force_kip, simulate(for_record(file, recs[k].test), recs[k].test), 0,
                                       recs[k].test.size());
    });
    for (std::size_t k = 0; k < recs.size(); ++k) {
      const RecordReport& rep = result.records[k];
      sum_after += rep.after.nrmse_std;
      max_after = std::max(max_after, rep.after.nrmse_std);
    }
    result.nrmse_after_mean = sum_after / static_cast<double>(recs.size());
    result.nrmse_after_max = max_after;
    if (result.added.empty() || result.nrmse_after_mean <= result.nrmse_before_mean) break;
    const std::string dropped = result.added.back();
    const std::string note = "dropped " + dropped + ": with it the mean NRMSE (" + format_significant(result.nrmse_after_mean, 4) +
                             ") exceeds the model's before (" + format_significant(result.nrmse_before_mean, 4) + "); the gap never grows";
    log(note);
    result.notes.push_back(note);
    effect_spec(dropped).remove(effects);
    result.added.pop_back();
    result.added_confidence.pop_back();
  }
  result.effects = effects;
  for (std::size_t k = 0; k < recs.size(); ++k) {
    RecordReport& rep = result.records[k];
    const DiagnoseRecord& r = recs[k];
    std::vector<std::uint8_t> held(r.test.size());
    for (std::size_t i = 0; i < held.size(); ++i) held[i] = r.seg.train[i] ? 0 : 1;
    rep.before_heldout = masked_error(r.test.force_kip, pred_before[k], held, 1);
    rep.after_heldout = masked_error(r.test.force_kip, after[k], held, 1);
    std::vector<double> res(after[k].size());
    for (std::size_t i = 0; i < res.size(); ++i) res[i] = after[k][i] - r.test.force_kip[i];
    rep.energy_after = localize(res, r.seg, r.test.dt_s, o.segmentation);
    rep.time_s = r.test.time_s;
    rep.disp_in = r.test.drum_disp_in;
    rep.vel_in_per_s = r.test.drum_vel_in_per_s;
    rep.act1_in = r.test.has_actuator_positions ? r.test.actuator1_in : std::vector<double>(r.test.size(), 0.0);
    rep.act2_in = r.test.has_actuator_positions ? r.test.actuator2_in : std::vector<double>(r.test.size(), 0.0);
    rep.measured_kip = r.test.force_kip;
    rep.model_before_kip = pred_before[k];
    rep.model_after_kip = after[k];
    rep.segmentation = r.seg;
  }
}

}  // namespace

DiagnoseResult run_diagnose(const DiagnoseOptions& o) {
  std::vector<std::string> lines;
  const Log log = [&](const std::string& s) {
    lines.push_back(s);
    if (o.log) o.log(s);
  };
  DiagnoseResult result;
  const BrfdParams model = o.model_path.empty() ? BrfdParams{} : load_brfd_params(o.model_path);
  result.initial_effects = model.effects;
  std::vector<const EffectSpec*> library;
  if (o.candidates.empty()) {
    for (const EffectSpec& s : effect_library()) library.push_back(&s);
  } else {
    for (const std::string& name : o.candidates) library.push_back(&effect_spec(name));
  }

  ModelState before;
  const std::vector<DiagnoseRecord> recs = load_records(o, model, result, before, log);
  const std::vector<std::vector<double>> pred_before = localize_before(recs, before, o, result, log);
  const ModelState selected = select_effects(recs, before, library, o, result, log);
  final_gap(recs, model, selected.effects, pred_before, o, result, log);

  log("");
  log("== Gap before/after per record (NRMSE = RMSE / std of the measured force) ==");
  for (const std::string& l : format_gap_table(result.records, o.base == BaseSource::identify)) log(l);
  log("where the residual sits after:");
  RegimeEnergy before_all, after_all;
  for (const RecordReport& rep : result.records) {
    before_all += rep.energy_before;
    after_all += rep.energy_after;
  }
  for (const std::string& l : format_regime_shift(before_all, after_all)) log(l);
  if (!o.out_dir.empty()) write_outputs(o, result, lines, log);
  return result;
}

}  // namespace damper
