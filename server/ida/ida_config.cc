#include "server/ida/ida_config.h"

#include "common/strict_yaml.h"
#include "server/run/run_config.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>

namespace server::ida {

namespace fs = std::filesystem;

namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

IdaConfig load_ida_config(const std::string& path) {
  const common::YamlSection top = common::YamlSection::load_file(path);
  top.allow_only({"ida", "cases"});
  IdaConfig c;
  c.source_file = path;
  const common::YamlSection s = top.section("ida");
  s.allow_only({"name", "intensity_measure", "damping_ratio", "story_height_in", "drift_limits_pct",
                "collapse_drift_pct", "transport", "duration_s", "hunt"});
  c.name = s.get_string("name", c.name);
  c.intensity_measure = s.get_choice("intensity_measure", c.intensity_measure, {"sa_t1", "pga"});
  c.damping_ratio = s.get_double_in("damping_ratio", c.damping_ratio, 0.0, 0.5);
  c.story_height_in = s.get_double_in("story_height_in", 1e-3, 1e4);
  c.drift_limits_pct = s.get_double_list("drift_limits_pct");
  c.collapse_drift_pct = s.get_double_in("collapse_drift_pct", c.collapse_drift_pct, 1e-3, 100.0);
  if (c.drift_limits_pct.empty()) s.fail("drift_limits_pct", "give at least one drift limit (%)");
  for (double d : c.drift_limits_pct)
    if (!(d > 0.0 && d < c.collapse_drift_pct))
      s.fail("drift_limits_pct", "each limit must be > 0 and below collapse_drift_pct (" +
                                     number(c.collapse_drift_pct) + "), got " + number(d));
  c.transport = s.get_choice("transport", c.transport, {"in_process", "lcm"});
  c.duration_s = s.get_double("duration_s", c.duration_s);
  if (s.has("hunt")) {
    const common::YamlSection h = s.section("hunt");
    h.allow_only({"first_im_g", "step_g", "step_increment_g", "max_im_g", "bracket_resolution_g", "max_runs"});
    HuntFillSettings& f = c.hunt;
    f.first_im = h.get_double_in("first_im_g", f.first_im, 1e-6, 100.0);
    f.step = h.get_double_in("step_g", f.step, 1e-6, 100.0);
    f.step_increment = h.get_double_in("step_increment_g", f.step_increment, 0.0, 100.0);
    f.max_im = h.get_double_in("max_im_g", f.max_im, 1e-6, 100.0);
    f.bracket_resolution = h.get_double_in("bracket_resolution_g", f.bracket_resolution, 1e-6, 100.0);
    f.max_runs = h.get_int("max_runs", f.max_runs);
    if (f.max_runs < 2 || f.max_runs > 200) h.fail("max_runs", "must be in [2, 200], got " + std::to_string(f.max_runs));
    if (f.first_im > f.max_im) h.fail("first_im_g", "must not exceed max_im_g");
  }
  const fs::path base = fs::absolute(path).parent_path();
  std::set<std::string> labels;
  for (const common::YamlSection& k : top.section_list("cases")) {
    k.allow_only({"label", "config"});
    IdaCase one;
    one.label = k.get_string("label");
    bool good = !one.label.empty() && one.label.size() <= 40;
    for (char ch : one.label) good = good && (std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-');
    if (!good) k.fail("label", "must be 1-40 letters, digits, '_' or '-', got '" + one.label + "'");
    if (!labels.insert(one.label).second) k.fail("label", "'" + one.label + "' is used twice");
    const fs::path p(k.get_string("config"));
    one.config = (p.is_absolute() ? p : base / p).lexically_normal().string();
    load_run_config(one.config);  // a bad case config is an error now, naming its file
    c.cases.push_back(one);
  }
  if (c.cases.empty()) top.fail("cases", "give at least one case (label, config)");
  return c;
}

std::string ida_config_to_yaml(const IdaConfig& c) {
  std::ostringstream o;
  o << "# effective IDA config (hybridsim ida); units: IM in g, story height in in, drift limits in %\n"
    << "ida:\n"
    << "  name: \"" << c.name << "\"\n"
    << "  intensity_measure: " << c.intensity_measure << "\n"
    << "  damping_ratio: " << number(c.damping_ratio) << "\n"
    << "  story_height_in: " << number(c.story_height_in) << "\n"
    << "  drift_limits_pct: [";
  for (std::size_t i = 0; i < c.drift_limits_pct.size(); ++i) o << (i ? ", " : "") << number(c.drift_limits_pct[i]);
  o << "]\n"
    << "  collapse_drift_pct: " << number(c.collapse_drift_pct) << "\n"
    << "  transport: " << c.transport << "\n"
    << "  duration_s: " << number(c.duration_s) << "\n"
    << "  hunt:\n"
    << "    first_im_g: " << number(c.hunt.first_im) << "\n"
    << "    step_g: " << number(c.hunt.step) << "\n"
    << "    step_increment_g: " << number(c.hunt.step_increment) << "\n"
    << "    max_im_g: " << number(c.hunt.max_im) << "\n"
    << "    bracket_resolution_g: " << number(c.hunt.bracket_resolution) << "\n"
    << "    max_runs: " << c.hunt.max_runs << "\n"
    << "cases:\n";
  for (const IdaCase& k : c.cases) o << "  - {label: " << k.label << ", config: \"" << k.config << "\"}\n";
  return o.str();
}

}  // namespace server::ida
