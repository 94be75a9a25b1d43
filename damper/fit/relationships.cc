#include "damper/fit/relationships.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace damper {

namespace {

double peak_abs(const std::vector<double>& v) {
  double p = 0.0;
  for (double x : v) p = std::max(p, std::abs(x));
  return p;
}

// Kinetic friction sample: fast enough and the force in the direction of motion.
bool kinetic(const BrfdTest& t, std::size_t i, double v_min) {
  const double v = t.drum_vel_in_per_s[i];
  return std::abs(v) >= v_min && v * t.force_kip[i] > 0.0;
}

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

std::vector<std::string> json_files(const std::filesystem::path& dir) {
  std::vector<std::string> files;
  if (!std::filesystem::is_directory(dir)) return files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".json") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y_signed) {
  LineFit f;
  const std::size_t n = x.size();
  f.samples = n;
  if (n < 2) return f;
  double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double y = std::abs(y_signed[i]);
    sx += x[i];
    sy += y;
    sxx += x[i] * x[i];
    sxy += x[i] * y;
    syy += y * y;
  }
  const double dn = static_cast<double>(n);
  const double cxx = sxx - sx * sx / dn, cxy = sxy - sx * sy / dn, cyy = syy - sy * sy / dn;
  f.slope = cxx > 0 ? cxy / cxx : 0.0;
  f.intercept_kip = (sy - f.slope * sx) / dn;
  f.slope_origin = sxx > 0 ? sxy / sxx : 0.0;
  f.r2 = (cxx > 0 && cyy > 0) ? cxy * cxy / (cxx * cyy) : 0.0;
  return f;
}

CharacterizationRelations characterization_relations(const BrfdTest& t,
                                                     const RelationshipsOptions& opt) {
  CharacterizationRelations r;
  r.name = t.name();
  const double v_min = opt.kinetic_speed_fraction * peak_abs(t.drum_vel_in_per_s);
  // [0] fwd act1, [1] fwd act2, [2] bwd act1, [3] bwd act2 (C1..C4 ordering).
  std::array<std::vector<double>, 4> xa;
  std::array<std::vector<double>, 2> fy;  // |F| fwd, bwd
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!kinetic(t, i, v_min)) continue;
    if (t.has_actuator_positions &&
        (std::abs(t.actuator1_in[i] - t.actuator1_in[0]) > opt.actuator_motion_threshold_in ||
         std::abs(t.actuator2_in[i] - t.actuator2_in[0]) > opt.actuator_motion_threshold_in))
      continue;
    const bool fwd = t.drum_vel_in_per_s[i] > 0.0;
    const double a1 = t.actuator1_force_lb[i] / 1000.0, a2 = t.actuator2_force_lb[i] / 1000.0;
    xa[fwd ? 0 : 2].push_back(a1);
    xa[fwd ? 1 : 3].push_back(a2);
    fy[fwd ? 0 : 1].push_back(std::abs(t.force_kip[i]));
  }
  for (int k = 0; k < 4; ++k) r.scaling[k] = fit_line(xa[k], fy[k < 2 ? 0 : 1]);
  r.slack_force_fwd_lb = 1000.0 * mean(xa[0]);
  r.taut_force_fwd_lb = 1000.0 * mean(xa[1]);
  r.taut_force_bwd_lb = 1000.0 * mean(xa[2]);
  r.slack_force_bwd_lb = 1000.0 * mean(xa[3]);
  // A slack load cell reading <= 0 lb is an offset, not a force: no amplification factor then.
  r.amplification_fwd = r.slack_force_fwd_lb > 0 ? mean(fy[0]) / mean(xa[0]) : NAN;
  r.amplification_bwd = r.slack_force_bwd_lb > 0 ? mean(fy[1]) / mean(xa[3]) : NAN;
  for (const std::string& pat : opt.exclude_from_mean)
    if (r.name.find(pat) != std::string::npos) r.in_mean = false;
  return r;
}

namespace {

Increase increase_of(const std::vector<StrokeAmplification>& strokes, bool forward,
                     double StrokeAmplification::*field) {
  std::vector<double> act, unact;
  for (const auto& st : strokes)
    if (st.forward == forward) (st.actuated ? act : unact).push_back(st.*field);
  Increase inc;
  inc.actuated = mean(act);
  inc.unactuated = mean(unact);
  inc.increase = (!act.empty() && !unact.empty()) ? inc.actuated / inc.unactuated - 1.0 : NAN;
  return inc;
}

}  // namespace

SemiactiveAmplification semiactive_amplification(const BrfdTest& t, const RelationshipsOptions& opt) {
  if (!t.has_actuator_positions)
    throw std::invalid_argument(t.path + ": not a semi-active test (no actuator position columns)");
  SemiactiveAmplification s;
  s.name = t.name();
  s.passive = characterization_relations(t, opt);
  const double peak = peak_abs(t.drum_vel_in_per_s);
  const double v_min = opt.kinetic_speed_fraction * peak;
  const double x1 = t.actuator1_in[0], x2 = t.actuator2_in[0];
  std::vector<double> abs_f(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) abs_f[i] = std::abs(t.force_kip[i]);
  const std::vector<double> abs_f_smooth = centered_moving_average(abs_f, 7);
  std::size_t i = 0;
  const std::size_t n = t.size();
  while (i < n) {
    const bool fwd = t.drum_vel_in_per_s[i] > 0.0;
    std::size_t j = i;
    double stroke_peak = 0.0, f_sum = 0.0, f_peak = 0.0, slack_sum = 0.0;
    std::size_t m = 0;
    bool moved = false;
    while (j < n && (t.drum_vel_in_per_s[j] > 0.0) == fwd) {
      stroke_peak = std::max(stroke_peak, std::abs(t.drum_vel_in_per_s[j]));
      if (kinetic(t, j, v_min)) {
        moved = moved || std::abs(t.actuator1_in[j] - x1) > opt.actuator_motion_threshold_in ||
                std::abs(t.actuator2_in[j] - x2) > opt.actuator_motion_threshold_in;
        f_sum += abs_f[j];
        f_peak = std::max(f_peak, abs_f_smooth[j]);
        slack_sum += (fwd ? t.actuator1_force_lb[j] : t.actuator2_force_lb[j]) / 1000.0;
        ++m;
      }
      ++j;
    }
    // Full strokes only (the ramp-up/down strokes are smaller); noise near rest gives short runs.
    if (stroke_peak >= opt.full_stroke_fraction * peak && m > 50 && slack_sum > 0.0) {
      StrokeAmplification st;
      st.t_start_s = t.time_s[i];
      st.t_end_s = t.time_s[j - 1];
      st.forward = fwd;
      st.actuated = moved;
      st.mean_force_kip = f_sum / static_cast<double>(m);
      st.peak_force_kip = f_peak;
      st.mean_slack_lb = 1000.0 * slack_sum / static_cast<double>(m);
      st.af_mean = f_sum / slack_sum;
      st.af_peak = f_peak / (slack_sum / static_cast<double>(m));
      s.strokes.push_back(st);
    }
    i = j;
  }
  int act_fwd = 0, act_bwd = 0;
  for (const auto& st : s.strokes)
    if (st.actuated) ++(st.forward ? act_fwd : act_bwd);
  s.forward_actuated = act_fwd >= act_bwd;
  s.af_mean = increase_of(s.strokes, s.forward_actuated, &StrokeAmplification::af_mean);
  s.af_peak = increase_of(s.strokes, s.forward_actuated, &StrokeAmplification::af_peak);
  s.peak_force = increase_of(s.strokes, s.forward_actuated, &StrokeAmplification::peak_force_kip);
  return s;
}

RelationshipsReport derive_relationships(const std::string& dir, const RelationshipsOptions& opt) {
  RelationshipsReport rep;
  const auto chars = json_files(std::filesystem::path(dir) / "characterization");
  const auto semis = json_files(std::filesystem::path(dir) / "semiactive");
  if (chars.empty() && semis.empty())
    throw std::invalid_argument(dir + ": no characterization/*.json nor semiactive/*.json found");
  std::array<std::vector<double>, 4> slopes, slopes0;
  for (const std::string& f : chars) {
    const BrfdTest t = read_brfd_test(f);
    if (t.has_actuator_positions) {
      rep.notes.push_back(f + ": 8-column layout in characterization/, skipped");
      continue;
    }
    CharacterizationRelations c = characterization_relations(t, opt);
    if (c.in_mean) {
      for (int k = 0; k < 4; ++k) {
        slopes[k].push_back(c.scaling[k].slope);
        slopes0[k].push_back(c.scaling[k].slope_origin);
      }
    }
    rep.characterization.push_back(std::move(c));
  }
  for (int k = 0; k < 4; ++k) {
    rep.mean_slope[k] = mean(slopes[k]);
    rep.mean_slope_origin[k] = mean(slopes0[k]);
  }
  std::array<std::vector<double>, 4> s_slopes, s_slopes0;
  std::vector<double> inc_mean, inc_peak, inc_force;
  for (const std::string& f : semis) {
    const BrfdTest t = read_brfd_test(f);
    if (!t.has_actuator_positions) continue;
    SemiactiveAmplification s = semiactive_amplification(t, opt);
    for (int k = 0; k < 4; ++k) {
      s_slopes[k].push_back(s.passive.scaling[k].slope);
      s_slopes0[k].push_back(s.passive.scaling[k].slope_origin);
    }
    if (std::isfinite(s.af_mean.increase)) inc_mean.push_back(s.af_mean.increase);
    if (std::isfinite(s.af_peak.increase)) inc_peak.push_back(s.af_peak.increase);
    if (std::isfinite(s.peak_force.increase)) inc_force.push_back(s.peak_force.increase);
    rep.semiactive.push_back(std::move(s));
  }
  for (int k = 0; k < 4; ++k) {
    rep.semiactive_mean_slope[k] = s_slopes[k].empty() ? NAN : mean(s_slopes[k]);
    rep.semiactive_mean_slope_origin[k] = s_slopes0[k].empty() ? NAN : mean(s_slopes0[k]);
  }
  rep.mean_increase_af_mean = inc_mean.empty() ? NAN : mean(inc_mean);
  rep.mean_increase_af_peak = inc_peak.empty() ? NAN : mean(inc_peak);
  rep.mean_increase_peak_force = inc_force.empty() ? NAN : mean(inc_force);
  return rep;
}

namespace {

void scaling_row(std::ostringstream& o, const CharacterizationRelations& c, const std::string& label) {
  o << std::left << std::setw(34) << label << std::right;
  for (const auto& f : c.scaling) {
    std::ostringstream cell;
    cell << std::fixed << std::setprecision(2) << f.slope << " (" << f.slope_origin << ") ["
         << f.r2 << "]";
    o << std::setw(26) << cell.str();
  }
  o << std::setprecision(1) << std::setw(9) << c.amplification_fwd << std::setw(9)
    << c.amplification_bwd << std::setw(8) << c.slack_force_fwd_lb << "/" << std::setw(6)
    << c.slack_force_bwd_lb << "\n";
}

void scaling_header(std::ostringstream& o) {
  o << std::left << std::setw(34) << "test" << std::right;
  for (const char* h : {"C1 fwd/act1 slack", "C2 fwd/act2 taut", "C3 bwd/act1 taut", "C4 bwd/act2 slack"})
    o << std::setw(26) << h;
  o << std::setw(9) << "AF fwd" << std::setw(9) << "AF bwd" << std::setw(15) << "slack lb f/b" << "\n";
}

}  // namespace

std::string format_relationships(const RelationshipsReport& r) {
  std::ostringstream o;
  o << std::fixed;
  if (!r.characterization.empty()) {
    o << "Scaling factors (paper Figs. 6-7): slope of |friction force| (kip) vs actuator force (kip)\n"
         "during kinetic friction (|v| >= half the peak, force along v). Forward: actuator 2 taut,\n"
         "actuator 1 slack. Cells: OLS slope (slope through the origin) [R^2].\n"
         "AF: force amplification factor (Figs. 9-10) = mean |F| / mean slack-actuator force.\n\n"
         "Characterization tests (actuators hold):\n";
    scaling_header(o);
    for (const auto& c : r.characterization) scaling_row(o, c, c.name + (c.in_mean ? "" : " (*)"));
    o << "(*) left out of the means (0 lb tests: band tension measured incorrectly per the data's authors)\n\n";
  }
  if (!r.semiactive.empty()) {
    o << "Semi-active tests, samples with the actuators at x' (passive drum cycles):\n";
    scaling_header(o);
    for (const auto& s : r.semiactive) scaling_row(o, s.passive, s.name);
    o << "\n";
  }
  o << "Scaling factors beside the paper's Table 2 (means over tests):\n";
  o << std::left << std::setw(6) << "" << std::right << std::setw(18) << "charact. OLS"
    << std::setw(18) << "charact. origin" << std::setw(18) << "semi-act. OLS" << std::setw(18)
    << "semi-act. origin" << std::setw(10) << "Table 2" << "\n";
  for (int k = 0; k < 4; ++k)
    o << std::left << std::setw(6) << ("C" + std::to_string(k + 1)) << std::right
      << std::setprecision(2) << std::setw(18) << r.mean_slope[k] << std::setw(18)
      << r.mean_slope_origin[k] << std::setw(18) << r.semiactive_mean_slope[k] << std::setw(18)
      << r.semiactive_mean_slope_origin[k] << std::setw(10) << r.table2[k] << "\n";
  o << "\n";
  if (!r.semiactive.empty()) {
    o << "Amplification factor on actuated vs unactuated full drum strokes (same direction),\n"
         "semi-active tests. AF_mean = mean|F|/mean slack force; AF_peak = peak|F|/mean slack force.\n";
    o << std::left << std::setw(26) << "test" << std::right << std::setw(5) << "dir"
      << std::setw(24) << "AF_mean unact/act" << std::setw(9) << "incr." << std::setw(24)
      << "AF_peak unact/act" << std::setw(9) << "incr." << std::setw(24) << "peak F kip unact/act"
      << std::setw(9) << "incr." << "\n";
    auto cell = [&o](const Increase& inc, int prec) {
      std::ostringstream c;
      c << std::fixed << std::setprecision(prec) << inc.unactuated << " / " << inc.actuated;
      o << std::setw(24) << c.str() << std::setprecision(1) << std::setw(8) << 100.0 * inc.increase << "%";
    };
    for (const auto& s : r.semiactive) {
      o << std::left << std::setw(26) << s.name << std::right << std::setw(5)
        << (s.forward_actuated ? "fwd" : "bwd");
      cell(s.af_mean, 1);
      cell(s.af_peak, 1);
      cell(s.peak_force, 2);
      o << "\n";
    }
    o << std::setprecision(1)
      << "average increase on actuated cycles: AF_peak " << 100.0 * r.mean_increase_af_peak
      << "%, AF_mean " << 100.0 * r.mean_increase_af_mean << "%, peak damping force "
      << 100.0 * r.mean_increase_peak_force << "% (paper: about 33%)\n";
  }
  for (const auto& n : r.notes) o << "note: " << n << "\n";
  return o.str();
}

}  // namespace damper
