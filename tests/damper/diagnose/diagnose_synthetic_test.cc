// The whole diagnose workflow on synthetic records with a hidden effect: "measured" data made by
// the model itself plus one effect of the library (0.5 Hz, 1 in ramped drum sinusoid, actuator
// motions, rest at the end, white noise 0.05 kip); starting from the model without the effect
// (base = the model file as is), the workflow must name that effect first and at least halve the
// gap (NRMSE). With no hidden effect it must report effects=none.
#include "damper/model/brfd_config.h"
#include "damper/diagnose/diagnose.h"
#include "synthetic.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>

namespace damper {
namespace {

using diagnose_test::make_record;
using diagnose_test::synthetic_base;
using diagnose_test::write_json;

struct Hidden {
  std::string effect;
  std::vector<double> theta;
};
void PrintTo(const Hidden& h, std::ostream* os) { *os << (h.effect.empty() ? "none" : h.effect); }

DiagnoseResult diagnose_hidden(const Hidden& h, bool figures = false) {
  const std::string dir = (std::filesystem::temp_directory_path() / ("diagnose_hidden_" + (h.effect.empty() ? std::string("none") : h.effect))).string();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const BrfdParams base = synthetic_base();
  BrfdParams truth = base;
  if (!h.effect.empty()) effect_spec(h.effect).set(truth.effects, h.theta);
  write_json(make_record(truth), dir + "/synthetic.json");
  std::ofstream(dir + "/model.yaml") << brfd_params_to_yaml(base);
  DiagnoseOptions o;
  o.model_path = dir + "/model.yaml";
  o.measured = {dir + "/synthetic.json"};
  o.out_dir = dir + "/out";
  o.base = BaseSource::model;
  o.figures = figures;
  const DiagnoseResult r = run_diagnose(o);
  std::cout << "[hidden " << (h.effect.empty() ? "none" : h.effect) << "] " << diagnose_final_line(r) << "\n";
  for (const CandidateScore& c : r.candidates) {
    if (!c.accepted) continue;
    std::cout << "  added " << c.effect << ":";
    for (std::size_t k = 0; k < c.theta.size(); ++k) std::cout << " " << c.parameter_names[k] << "=" << c.theta[k];
    std::cout << " (held-out RMSE -" << 100 * c.heldout_gain << "%, dBIC " << c.delta_bic << ")\n";
  }
  return r;
}

class HiddenEffect : public ::testing::TestWithParam<Hidden> {};

TEST_P(HiddenEffect, IsNamedAndTheGapAtLeastHalves) {
  const Hidden h = GetParam();
  const DiagnoseResult r = diagnose_hidden(h, h.effect == "backlash");
  ASSERT_FALSE(r.added.empty()) << "nothing named for hidden " << h.effect;
  EXPECT_EQ(r.added.front(), h.effect);
  EXPECT_LE(r.added.size(), 2u) << "spurious extra effects";
  EXPECT_LE(r.nrmse_after_mean, 0.5 * r.nrmse_before_mean);
  // The fitted parameters of the named effect are close to the hidden ones.
  const std::vector<double> fitted = effect_spec(h.effect).get(r.effects);
  const std::vector<EffectParameter>& params = effect_spec(h.effect).parameters;
  for (std::size_t k = 0; k < fitted.size(); ++k) {
    const double range = params[k].hi - params[k].lo;
    if (params[k].log_scale) continue;  // a settling time: checked through the gap
    EXPECT_NEAR(fitted[k], h.theta[k], 0.2 * std::abs(h.theta[k]) + 0.05 * range) << params[k].name;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Library, HiddenEffect,
    ::testing::Values(Hidden{"backlash", {0.05}}, Hidden{"residual_static", {0.4, 0.15}},
                      Hidden{"actuator_lag", {0.15}}, Hidden{"asymmetry", {0.15, 0.3}},
                      Hidden{"velocity", {1.0, 0.25}}, Hidden{"pretension", {1.0, 0.8}},
                      Hidden{"self_energizing", {-0.2, 0.15}}, Hidden{"transition_shape", {4.0}}),
    [](const ::testing::TestParamInfo<Hidden>& info) { return info.param.effect; });

TEST(NoHiddenEffect, ReportsThatNothingSignificantIsMissing) {
  const DiagnoseResult r = diagnose_hidden(Hidden{"", {}});
  EXPECT_TRUE(r.added.empty());
  EXPECT_EQ(diagnose_final_line(r).rfind("effects=none ", 0), 0u) << diagnose_final_line(r);
  EXPECT_NEAR(r.nrmse_after_mean, r.nrmse_before_mean, 1e-12);
}

}  // namespace
}  // namespace damper
