#include "damper/diagnose/diagnose_report.h"

#include "common/gnuplot.h"
#include "common/number_format.h"
#include "damper/model/brfd_config.h"
#include "damper/diagnose/diagnose_select.h"
#include "damper/model/effects.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace damper {

namespace {

using common::format_significant;
using common::format_fixed;
using common::gnuplot_quote;

std::string pad(const std::string& s, std::size_t w) { return s.size() >= w ? s : s + std::string(w - s.size(), ' '); }
std::string lpad(const std::string& s, std::size_t w) { return s.size() >= w ? s : std::string(w - s.size(), ' ') + s; }

std::string pct(double share) { return format_fixed(100.0 * share, 1) + "%"; }

int color_int(Regime r) { return std::stoi(regime_color(r).substr(1), nullptr, 16); }

std::ofstream open_out(const std::string& path) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  return f;
}

// Per-record figure: force history and residual with the regimes shaded and the held-out spans
// marked, and the force-displacement loops with the large residuals coloured by regime.
std::string plot_record(const RecordReport& r, const std::string& csv, const std::string& png, const std::string& added) {
  const std::string gp_path = png.substr(0, png.size() - 4) + ".gp";
  {
    std::ofstream gp(gp_path);
    if (!gp) return "cannot write " + gp_path;
    gp << "set terminal pngcairo noenhanced size 1300,1150 font ',10'\n"
       << "set output " << gnuplot_quote(png) << "\n"
       << "set datafile separator ','\nset grid\nset key top right opaque\n"
       << "set multiplot title " << gnuplot_quote(r.name + ": effects added: " + added + "   NRMSE before " +
                                             format_significant(r.before.nrmse_std, 3) + ", after " + format_significant(r.after.nrmse_std, 3))
       << "\n";
    // Regime shading (time panels).
    const Segmentation& s = r.segmentation;
    int obj = 1;
    std::ostringstream shade;
    std::size_t b = 0;
    const std::size_t n = r.time_s.size();
    for (std::size_t i = 1; i <= n; ++i) {
      if (i < n && s.regime[i] == s.regime[b]) continue;
      if (s.regime[b] != Regime::sliding) {
        shade << "set object " << obj++ << " rect from " << r.time_s[b] << ", graph 0 to " << r.time_s[i - 1] + r.dt_s
              << ", graph 1 fc rgb '" << regime_color(s.regime[b]) << "' fs transparent solid 0.22 noborder behind\n";
      }
      b = i;
    }
    for (const Segmentation::Span& sp : s.spans) {
      if (sp.train || sp.end <= sp.begin) continue;
      shade << "set object " << obj++ << " rect from " << r.time_s[sp.begin] << ", graph 0 to "
            << r.time_s[sp.end - 1] + r.dt_s << ", graph 0.035 fc rgb '#333333' fs solid 1.0 noborder front\n";
    }
    std::ostringstream legend;
    double x = 0.01;
    for (Regime g : {Regime::reversal, Regime::sticking, Regime::actuators, Regime::after_stop}) {
      legend << "set label " << (100 + static_cast<int>(g)) << " " << gnuplot_quote(to_string(g)) << " at graph " << x
             << ", graph 0.93 textcolor rgb '" << regime_color(g) << "' font ',10'\n";
      x += 0.09;
    }
    legend << "set label 110 'black bars: held-out' at graph " << x << ", graph 0.93 textcolor rgb '#333333'\n";
    gp << "set size 1,0.36\nset origin 0,0.62\n"
       << shade.str() << legend.str()
       << "set xlabel 'time (s)'\nset ylabel 'damper force (kip)'\n"
       << "plot " << gnuplot_quote(csv) << " u 1:6 w l lw 1.4 lc rgb '#000000' t 'measured', "
       << "'' u 1:7 w l lw 1.2 lc rgb '#d62728' t 'model before', "
       << "'' u 1:8 w l lw 1.2 lc rgb '#1f77b4' t 'model after'\n"
       << "unset label\n"
       << "set size 1,0.26\nset origin 0,0.36\n"
       << "set ylabel 'residual, model - measured (kip)'\n"
       << "plot " << gnuplot_quote(csv) << " u 1:9 w l lw 1 lc rgb '#d62728' t 'before', "
       << "'' u 1:10 w l lw 1 lc rgb '#1f77b4' t 'after'\n";
    for (int k = 1; k < obj; ++k) gp << "unset object " << k << "\n";
    gp << "set size 0.5,0.36\nset origin 0,0\n"
       << "set xlabel 'drum displacement (in)'\nset ylabel 'damper force (kip)'\n"
       << "set title 'loops: large residuals (before) coloured by regime' font ',10'\n"
       << "plot " << gnuplot_quote(csv) << " u 2:6 w l lw 1 lc rgb '#999999' t 'measured', "
       << "'' u 2:7 w l lw 0.8 lc rgb '#d62728' t 'model before', "
       << "'' u 2:($13 > 0 ? $6 : 1/0):14 w p pt 7 ps 0.35 lc rgb variable t 'large residual'\n"
       << "set size 0.5,0.36\nset origin 0.5,0\n"
       << "set title 'loops after' font ',10'\n"
       << "plot " << gnuplot_quote(csv) << " u 2:6 w l lw 1 lc rgb '#999999' t 'measured', "
       << "'' u 2:8 w l lw 0.8 lc rgb '#1f77b4' t 'model after'\n"
       << "unset multiplot\n";
  }
  return common::run_gnuplot(gp_path);
}

std::string plot_gap(const std::string& csv, const std::string& png) {
  const std::string gp_path = png.substr(0, png.size() - 4) + ".gp";
  {
    std::ofstream gp(gp_path);
    if (!gp) return "cannot write " + gp_path;
    gp << "set terminal pngcairo noenhanced size 900,500 font ',10'\n"
       << "set output " << gnuplot_quote(png) << "\n"
       << "set datafile separator ','\nset grid ytics\nset key top right autotitle columnhead\n"
       << "set style data histograms\nset style histogram clustered gap 1\nset style fill solid 0.85 border -1\n"
       << "set boxwidth 0.9\nset yrange [0:*]\nset xtics rotate by -25 noenhanced\n"
       << "set ylabel 'NRMSE (RMSE / std of measured force)'\n"
       << "set title 'model vs measured, whole records: before and after the added effects'\n"
       << "plot " << gnuplot_quote(csv) << " u 2:xtic(1) lc rgb '#d62728' t 'before', '' u 3 lc rgb '#1f77b4' t 'after'\n";
  }
  return common::run_gnuplot(gp_path);
}

}  // namespace

std::string regime_color(Regime r) {
  switch (r) {
    case Regime::sliding: return "#1f77b4";
    case Regime::reversal: return "#ff7f0e";
    case Regime::sticking: return "#8c8c00";
    case Regime::actuators: return "#2ca02c";
    case Regime::after_stop: return "#7f7f7f";
    case Regime::chatter: return "#9467bd";
  }
  return "#000000";
}

std::vector<std::string> format_regime_table(const std::vector<RecordReport>& records, const RegimeEnergy& all) {
  std::vector<std::string> out;
  std::string head = pad("regime", 11) + pad("meaning", 34) + lpad("time", 7) + lpad("energy", 8) + lpad("rms kip", 9);
  for (std::size_t k = 0; k < records.size(); ++k) head += lpad("#" + std::to_string(k + 1), 7);
  out.push_back(head);
  const double total = all.total();
  std::size_t time_samples = 0;
  for (int g = 0; g < kRegimeCount - 1; ++g) time_samples += all.samples[g];
  for (int g = 0; g < kRegimeCount; ++g) {
    const Regime rg = static_cast<Regime>(g);
    const double time_share =
        rg == Regime::chatter ? 1.0 : (time_samples ? static_cast<double>(all.samples[g]) / static_cast<double>(time_samples) : 0.0);
    const double rms = all.samples[g] ? std::sqrt(all.energy[g] / static_cast<double>(all.samples[g])) : 0.0;
    std::string l = pad(to_string(rg), 11) + pad(describe(rg), 34) + lpad(rg == Regime::chatter ? "all" : pct(time_share), 7) +
                    lpad(total > 0 ? pct(all.energy[g] / total) : "-", 8) + lpad(format_fixed(rms, 3), 9);
    for (const RecordReport& r : records) {
      const double t = r.energy_before.total();
      l += lpad(t > 0 ? format_fixed(100.0 * r.energy_before.energy[g] / t, 0) + "%" : "-", 7);
    }
    out.push_back(l);
  }
  out.push_back("(energy = share of the sum of squared residual; chatter = residual minus its moving average; "
                "rms = RMS of the regime's part; #k: share in record k)");
  for (std::size_t k = 0; k < records.size(); ++k)
    out.push_back("  #" + std::to_string(k + 1) + " " + records[k].name);
  return out;
}

std::vector<std::string> format_windows(const std::vector<ResidualWindow>& w, double total) {
  std::vector<std::string> out;
  for (const ResidualWindow& x : w) {
    out.push_back("  " + pad(x.test, 28) + lpad(format_fixed(x.t0_s, 2), 7) + " - " + pad(format_fixed(x.t1_s, 2) + " s", 9) +
                  pad(to_string(x.regime), 11) + lpad(total > 0 ? pct(x.energy / total) : "-", 7) + " of the residual energy");
  }
  return out;
}

std::string diagnose_final_line(const DiagnoseResult& r) {
  std::ostringstream o;
  std::string names;
  for (const std::string& a : r.added) names += (names.empty() ? "" : ",") + a;
  o << std::setprecision(4) << "effects=" << (names.empty() ? "none" : names)
    << " nrmse_before=" << r.nrmse_before_mean << " nrmse_after=" << r.nrmse_after_mean
    << " nrmse_after_max=" << r.nrmse_after_max;
  return o.str();
}

std::string diagnose_confidence_line(const DiagnoseResult& r) {
  std::ostringstream o;
  o << std::setprecision(3) << "confidence:";
  if (r.added.empty()) return o.str() + " none (" + r.stop_reason + ")";
  for (std::size_t k = 0; k < r.added.size(); ++k)
    o << " " << r.added[k] << "=" << (k < r.added_confidence.size() ? r.added_confidence[k] : 0.0);
  o << " (share of bootstrap resamples of the held-out parts choosing it)";
  return o.str();
}

std::vector<std::string> format_candidate_table(const std::vector<CandidateScore>& scores) {
  std::vector<std::string> out;
  out.push_back("  " + pad("effect", 17) + pad("params (fold 1; ADDED: all fitting data)", 62) + lpad("held-out RMSE", 16) + lpad("gain", 7) +
                lpad("excess", 8) + lpad("parts", 7) + lpad("own", 6) + lpad("conf", 6) + "  verdict");
  for (const CandidateScore& c : scores) {
    std::string params;
    for (std::size_t j = 0; j < c.theta.size(); ++j) params += (j ? " " : "") + c.parameter_names[j] + "=" + format_significant(c.theta[j], 3);
    if (c.theta.empty()) params = "(null)";
    out.push_back("  " + pad(c.effect, 17) + pad(params, 62) +
                  lpad(format_fixed(c.heldout_rmse_null_kip, 4) + "->" + format_fixed(c.heldout_rmse_kip, 4), 16) +
                  lpad(format_fixed(100.0 * c.heldout_gain, 1) + "%", 7) + lpad(format_fixed(100.0 * c.excess_share, 0) + "%", 8) +
                  lpad(std::to_string(c.parts_improved) + "/" + std::to_string(c.parts_changed), 7) +
                  lpad(format_fixed(100.0 * c.signature_share, 0) + "%", 6) + lpad(format_fixed(100.0 * c.confidence, 0) + "%", 6) + "  " +
                  (c.accepted ? "ADDED" : c.verdict));
  }
  out.push_back("  (held-out RMSE: refitted model without -> with the candidate, same procedure and budget; gain: share of "
                "the held-out mean square removed; excess: share of the residual above the noise floor removed; parts: "
                "held-out parts improved / changed; own: share of the gain in its own regimes; conf: bootstrap)");
  return out;
}

std::string format_evidence(const CandidateScore& c) {
  std::ostringstream o;
  std::string params;
  for (std::size_t j = 0; j < c.theta.size(); ++j) params += (j ? ", " : "") + c.parameter_names[j] + "=" + format_significant(c.theta[j], 4);
  o << "added " << c.effect << " (" << params << (c.subfamily.empty() ? "" : "; sub-family: " + c.subfamily)
    << "): held-out RMSE " << format_fixed(c.heldout_rmse_null_kip, 4) << " -> "
    << format_fixed(c.heldout_rmse_kip, 4) << " kip (" << format_fixed(100.0 * c.heldout_gain, 1) << "% of the mean square, "
    << format_fixed(100.0 * c.excess_share, 0) << "% of the excess over noise), better on " << c.parts_improved << " of the "
    << c.parts_changed << " held-out parts it changes, " << format_fixed(100.0 * c.signature_share, 0)
    << "% of the gain in its own regimes (" ;
  const EffectSpec& spec = effect_spec(c.effect);
  for (std::size_t k = 0; k < spec.regimes.size(); ++k) o << (k ? "/" : "") << spec.regimes[k];
  o << "), chosen in " << format_fixed(100.0 * c.confidence, 0) << "% of bootstrap resamples";
  return o.str();
}

std::vector<std::string> format_gap_table(const std::vector<RecordReport>& records, bool identify) {
  std::vector<std::string> out;
  out.push_back("  " + pad("record", 28) + lpad("NRMSE before", 13) + lpad("after", 8) + lpad("RMSE before", 12) +
                lpad("after", 8) + lpad("held-out NRMSE", 15) + lpad("after", 8) + lpad("updated.yaml", 13));
  double sb = 0, sa = 0, rb = 0, ra = 0, hb = 0, ha = 0, u = 0;
  for (const RecordReport& r : records) {
    out.push_back("  " + pad(r.name, 28) + lpad(format_fixed(r.before.nrmse_std, 4), 13) + lpad(format_fixed(r.after.nrmse_std, 4), 8) +
                  lpad(format_fixed(r.before.rmse_kip, 4), 12) + lpad(format_fixed(r.after.rmse_kip, 4), 8) +
                  lpad(format_fixed(r.before_heldout.nrmse_std, 4), 15) + lpad(format_fixed(r.after_heldout.nrmse_std, 4), 8) +
                  lpad(format_fixed(r.updated_config.nrmse_std, 4), 13));
    sb += r.before.nrmse_std;
    sa += r.after.nrmse_std;
    rb += r.before.rmse_kip;
    ra += r.after.rmse_kip;
    hb += r.before_heldout.nrmse_std;
    ha += r.after_heldout.nrmse_std;
    u += r.updated_config.nrmse_std;
  }
  const double n = static_cast<double>(records.size());
  out.push_back("  " + pad("mean", 28) + lpad(format_fixed(sb / n, 4), 13) + lpad(format_fixed(sa / n, 4), 8) + lpad(format_fixed(rb / n, 4), 12) +
                lpad(format_fixed(ra / n, 4), 8) + lpad(format_fixed(hb / n, 4), 15) + lpad(format_fixed(ha / n, 4), 8) + lpad(format_fixed(u / n, 4), 13));
  out.push_back(std::string("  (RMSE in kip; before/after: each record's base") +
                (identify ? " identified on its own passive window" : " = the --model file") +
                "; updated.yaml: model-updated.yaml as written, one parameter set for all records)");
  return out;
}

std::vector<std::string> format_regime_shift(const RegimeEnergy& before, const RegimeEnergy& after) {
  std::vector<std::string> out;
  for (int g = 0; g < kRegimeCount; ++g) {
    const double b = before.energy[g], a = after.energy[g];
    out.push_back("  " + pad(to_string(static_cast<Regime>(g)), 11) + lpad(format_fixed(b, 1), 9) + " -> " + lpad(format_fixed(a, 1), 9) +
                  " kip^2" + (b > 0 ? "  (" + format_fixed(100.0 * (a - b) / b, 0) + "%)" : ""));
  }
  out.push_back("  " + pad("total", 11) + lpad(format_fixed(before.total(), 1), 9) + " -> " + lpad(format_fixed(after.total(), 1), 9) + " kip^2");
  return out;
}

void write_outputs(const DiagnoseOptions& o, DiagnoseResult& result, std::vector<std::string>& lines,
                   const std::function<void(const std::string&)>& log) {
  const fs::path out(o.out_dir);
  fs::create_directories(out / "records");
  std::string added;
  for (const std::string& a : result.added) added += (added.empty() ? "" : ",") + a;
  if (added.empty()) added = "none";

  // model-updated.yaml
  result.updated_config_path = (out / "model-updated.yaml").string();
  {
    std::ofstream y = open_out(result.updated_config_path);
    y << "# Updated BRFD model written by `hybridsim diagnose` (docs/diagnose.md).\n"
      << "# Started from: " << (o.model_path.empty() ? std::string("built-in defaults") : fs::absolute(o.model_path).string()) << "\n"
      << "# Effects added: " << added << "; effects in the model: "
      << (result.effects.empty() ? std::string("none") : result.effects.names()) << "\n";
    y << "# Effect parameters: fitted on the measured records (" << result.validation << ").\n";
    if (o.base == BaseSource::identify) {
      y << "# Base parameters per record: the LuGre block is NOT what the 'after' column used. Each record's\n"
        << "# LuGre parameters are re-identified on its passive window"
        << (result.effects.empty() ? "" : " with these effects on") << ", exactly as\n"
        << "# `hybridsim damper predict` does by default (x'_1, x'_2 from the record's first row); this\n"
        << "# reproduces the 'after' NRMSE printed by diagnose:\n";
      for (const RecordReport& r : result.records) {
        std::ostringstream w;
        w << std::setprecision(10) << r.passive_end_s;
        const bool passive = !r.segmentation.actuated;
        y << "#   hybridsim damper predict --config model-updated.yaml --test " << r.path
          << (passive ? " --fit-window 0:" + w.str() : std::string()) << "   # nrmse=" << format_fixed(r.after.nrmse_std, 4) << "\n";
      }
      if (result.added.empty()) {
        y << "# No effect added: the LuGre block below is the --model file's (for hybrid runs / --no-fit).\n";
      } else {
        y << "# The LuGre block below is one set for all records, identified on their passive windows jointly\n"
          << "# with the effects on (for hybrid runs / --no-fit: NRMSE " ;
        double u = 0.0;
        for (const RecordReport& r : result.records) u += r.updated_config.nrmse_std;
        y << format_fixed(u / static_cast<double>(std::max<std::size_t>(1, result.records.size())), 4) << " mean on these records).\n";
      }
    } else {
      y << "# Base: the starting model's LuGre block as is (diagnose --base model); x'_1, x'_2 from each record's\n"
        << "# first row. Reproduce 'after' with: hybridsim damper predict --no-fit --config model-updated.yaml --test <record>\n";
    }
    y << brfd_params_to_yaml(result.updated_params);
  }

  // records/<name>.csv, _model.yaml, .png
  for (RecordReport& r : result.records) {
    const std::string base = (out / "records" / r.name).string();
    r.csv_path = base + ".csv";
    {
      std::ofstream c = open_out(r.csv_path);
      c << "time_s,drum_disp_in,drum_vel_in_per_s,actuator1_in,actuator2_in,measured_kip,model_before_kip,"
           "model_after_kip,residual_before_kip,residual_after_kip,regime,train,large_residual,regime_color\n";
      c << std::setprecision(7);
      std::vector<double> res(r.time_s.size());
      for (std::size_t i = 0; i < res.size(); ++i) res[i] = r.model_before_kip[i] - r.measured_kip[i];
      const std::vector<double> low = low_frequency_part(res, r.dt_s, o.segmentation);
      double ms = 0.0;
      for (double x : low) ms += x * x;
      const double rms = std::sqrt(ms / static_cast<double>(std::max<std::size_t>(1, low.size())));
      for (std::size_t i = 0; i < r.time_s.size(); ++i) {
        const Regime g = r.segmentation.regime[i];
        const bool large = std::abs(low[i]) > 1.5 * rms && i % 3 == 0;
        c << r.time_s[i] << ',' << r.disp_in[i] << ',' << r.vel_in_per_s[i] << ',' << r.act1_in[i] << ',' << r.act2_in[i]
          << ',' << r.measured_kip[i] << ',' << r.model_before_kip[i] << ',' << r.model_after_kip[i] << ',' << res[i] << ','
          << r.model_after_kip[i] - r.measured_kip[i] << ',' << static_cast<int>(g) << ','
          << static_cast<int>(r.segmentation.train[i]) << ',' << (large ? 1 : 0) << ',' << color_int(g) << '\n';
      }
    }
    {
      std::ofstream y = open_out(base + "_model.yaml");
      y << "# " << r.name << ": base (LuGre from passive data) + effects, as used for 'after' by `hybridsim diagnose`\n"
        << brfd_params_to_yaml(r.final_params);
    }
    if (o.figures) {
      r.png_path = base + ".png";
      const std::string warn = plot_record(r, r.csv_path, r.png_path, added);
      if (!warn.empty()) {
        log("warning: " + warn);
        r.png_path.clear();
      }
    }
  }

  // Tables as CSV.
  {
    std::ofstream c = open_out((out / "candidates.csv").string());
    c << "round,effect,params,heldout_rmse_null_kip,heldout_rmse_kip,heldout_gain,excess_share,parts_improved,"
         "parts_changed,signature_share,confidence,verdict,accepted,params_at_outer_bound,own_time_share,own_residual_share\n";
    for (const CandidateScore& s : result.candidates) {
      std::string params;
      for (std::size_t j = 0; j < s.theta.size(); ++j) params += (j ? " " : "") + s.parameter_names[j] + "=" + format_significant(s.theta[j], 6);
      std::string verdict = s.verdict;
      std::replace(verdict.begin(), verdict.end(), ',', ';');
      c << s.round << ',' << s.effect << ',' << params << ',' << s.heldout_rmse_null_kip << ',' << s.heldout_rmse_kip << ','
        << s.heldout_gain << ',' << s.excess_share << ',' << s.parts_improved << ',' << s.parts_changed << ','
        << s.signature_share << ',' << s.confidence << ',' << verdict << ',' << (s.accepted ? 1 : 0) << ',';
      const std::vector<std::string> at_bounds = parameters_at_outer_bounds(s);
      for (std::size_t j = 0; j < at_bounds.size(); ++j) c << (j ? "; " : "") << at_bounds[j];
      c << ',' << s.own_time_share << ',' << s.own_residual_share << '\n';
    }
  }
  {
    std::ofstream c = open_out((out / "regimes.csv").string());
    c << "record,regime,samples,energy_before_kip2,energy_after_kip2\n";
    for (const RecordReport& r : result.records)
      for (int g = 0; g < kRegimeCount; ++g)
        c << r.name << ',' << to_string(static_cast<Regime>(g)) << ',' << r.energy_before.samples[g] << ','
          << r.energy_before.energy[g] << ',' << r.energy_after.energy[g] << '\n';
  }
  {
    std::ofstream c = open_out((out / "windows.csv").string());
    c << "record,t0_s,t1_s,regime,energy_kip2\n";
    for (const ResidualWindow& w : result.top_windows)
      c << w.test << ',' << w.t0_s << ',' << w.t1_s << ',' << to_string(w.regime) << ',' << w.energy << '\n';
  }
  const std::string gap_csv = (out / "gap.csv").string();
  {
    std::ofstream c = open_out(gap_csv);
    c << "record,nrmse_before,nrmse_after,rmse_before_kip,rmse_after_kip,heldout_nrmse_before,heldout_nrmse_after,"
         "updated_config_nrmse\n";
    for (const RecordReport& r : result.records)
      c << r.name << ',' << r.before.nrmse_std << ',' << r.after.nrmse_std << ',' << r.before.rmse_kip << ','
        << r.after.rmse_kip << ',' << r.before_heldout.nrmse_std << ',' << r.after_heldout.nrmse_std << ','
        << r.updated_config.nrmse_std << '\n';
  }
  if (o.figures) {
    result.gap_png_path = (out / "gap.png").string();
    const std::string warn = plot_gap(gap_csv, result.gap_png_path);
    if (!warn.empty()) {
      log("warning: " + warn);
      result.gap_png_path.clear();
    }
  }
  log("wrote " + result.updated_config_path);
  log("wrote " + (out / "records").string() + "/<record>.csv, _model.yaml" + (o.figures ? ", .png" : "") +
      "; candidates.csv, regimes.csv, windows.csv, gap.csv" + (result.gap_png_path.empty() ? "" : ", gap.png") + " in " +
      o.out_dir);
  result.report_path = (out / "report.txt").string();
  std::ofstream rep = open_out(result.report_path);
  for (const std::string& l : lines) rep << l << "\n";
  rep << diagnose_confidence_line(result) << "\n" << diagnose_final_line(result) << "\n";
}

}  // namespace damper
