#include "server/ida/ida.h"

#include "common/gnuplot.h"
#include "common/number_format.h"
#include "server/batch/batch.h"
#include "server/batch/batch_files.h"
#include "server/batch/batch_report.h"
#include "server/batch/batch_set.h"
#include "server/batch/driver.h"
#include "server/batch/progress.h"
#include "server/ida/fragility.h"
#include "server/ida/hunt_fill.h"
#include "server/ida/ida_config.h"
#include "server/ida/ida_curves.h"
#include "server/run/run_config.h"
#include "structure/ground_motion.h"
#include "structure/response_spectrum.h"
#include "structure/shear_building.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

namespace server::ida {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using nlohmann::json;
using common::format_fixed;
using common::format_shortest;
using common::gnuplot_quote;
namespace bi = server::batch_internal;

namespace {

struct CaseInfo {
  IdaCase def;
  double t1_s = 0.0;
  int stories = 0;
};

struct RecordInfo {
  BatchRecord rec;
  std::vector<double> im_unit;  // IM of the record at scale 1, per case (g)
  std::string error;            // record unreadable: not traced
};

/// One finished (or failed) run of the trace, read back from disk.
struct RunInfo {
  std::string label;
  double im = 0.0, scale = 0.0;
  TracePoint point;
  std::string status, error;
};

std::string run_label(const CaseInfo& c, const RecordInfo& r, double im) {
  return c.def.label + "." + r.rec.label + ".im" + format_fixed(im, 6);
}

/// The set of the IDA: config, cases with their first period, records with their IM.
struct IdaSet {
  IdaConfig config;
  std::vector<CaseInfo> cases;
  std::vector<RecordInfo> records;
};

IdaSet prepare(const IdaOptions& o) {
  if (o.config.empty()) throw BatchInputError("--config is required (an IDA config, e.g. configs/ida-three-story.yaml)");
  if (o.records.empty()) throw BatchInputError("--records is required: a record list file or a folder");
  if (o.out.empty()) throw BatchInputError("--out is required (the IDA folder)");
  if (o.jobs < 1) throw BatchInputError("--jobs must be at least 1");
  IdaSet s;
  s.config = load_ida_config(o.config);
  for (const IdaCase& k : s.config.cases) {
    const RunConfig rc = load_run_config(k.config);
    if (rc.damper.mode != "virtual" || rc.damper.launch != "spawn")
      throw BatchInputError("case " + k.label + ": config " + k.config +
                            " must use a virtual damper it spawns (damper.mode: virtual, damper.launch: spawn)");
    const structure::ShearBuilding building(rc.building);
    CaseInfo c;
    c.def = k;
    c.t1_s = building.modal().period_s[0];
    c.stories = building.num_stories();
    s.cases.push_back(c);
  }
  for (const BatchRecord& r : load_record_set(o.records)) {
    if (r.scale != 1.0)
      throw BatchInputError(o.records + (r.line ? ":" + std::to_string(r.line) : std::string()) + ": scale " +
                            format_shortest(r.scale) + ": an IDA scales every record itself; give scale 1 "
                            "(or a folder of records)");
    RecordInfo info;
    info.rec = r;
    try {
      const structure::GroundMotion g = structure::read_ground_motion(r.path, 1.0);
      for (const CaseInfo& c : s.cases) {
        const double im = s.config.intensity_measure == "pga"
                              ? g.pga_g()
                              : structure::spectral_accel_g(g, c.t1_s, s.config.damping_ratio);
        if (!(im > 0.0)) throw structure::RecordError(r.path + ": intensity measure is zero (a silent record)");
        info.im_unit.push_back(im);
      }
    } catch (const std::exception& e) {
      info.error = e.what();
    }
    s.records.push_back(info);
  }
  return s;
}

json manifest(const IdaSet& s) {
  json j;
  j["config"] = fs::absolute(s.config.source_file).lexically_normal().string();
  j["intensity_measure"] = s.config.intensity_measure;
  j["damping_ratio"] = s.config.damping_ratio;
  json cases = json::array();
  for (const CaseInfo& c : s.cases) cases.push_back({{"label", c.def.label}, {"config", c.def.config}, {"t1_s", c.t1_s}});
  j["cases"] = cases;
  json recs = json::array();
  for (const RecordInfo& r : s.records)
    recs.push_back({{"label", r.rec.label}, {"path", r.rec.path}, {"im_at_scale_1_g", r.im_unit}, {"error", r.error}});
  j["records"] = recs;
  return j;
}

/// The finished runs of every (case, record), read from OUT/runs.
std::map<std::pair<int, int>, std::vector<RunInfo>> finished_runs(const std::string& out, const IdaSet& s) {
  std::map<std::string, std::pair<int, int>> prefixes;
  for (std::size_t c = 0; c < s.cases.size(); ++c)
    for (std::size_t r = 0; r < s.records.size(); ++r)
      prefixes[s.cases[c].def.label + "." + s.records[r].rec.label + ".im"] = {static_cast<int>(c), static_cast<int>(r)};
  std::map<std::pair<int, int>, std::vector<RunInfo>> runs;
  std::error_code ec;
  if (!fs::exists(bi::runs_dir(out), ec)) return runs;
  for (const fs::directory_entry& e : fs::directory_iterator(bi::runs_dir(out))) {
    const std::string name = e.path().filename().string();
    if (!e.is_directory() || name.find(".partial") != std::string::npos || name.find(".failed-") != std::string::npos ||
        name.find(".stale-") != std::string::npos)
      continue;
    const std::size_t at = name.rfind(".im");
    if (at == std::string::npos) continue;
    const auto it = prefixes.find(name.substr(0, at + 3));
    if (it == prefixes.end()) continue;
    const bi::RunResult res = bi::read_result(out, name);
    if (!res.finished) continue;
    const json info = json::parse(bi::read_file(e.path() / "batch-run.json"), nullptr, false);
    if (info.is_discarded() || !info.contains("scale")) continue;
    const auto [c, r] = it->second;
    RunInfo run;
    run.label = name;
    run.scale = info["scale"].get<double>();
    run.im = run.scale * s.records[r].im_unit[c];
    run.status = res.state;
    run.error = res.summary.is_object() ? res.summary.value("error", "") : "";
    double ratio = std::numeric_limits<double>::infinity();
    if (res.state == "ok" && res.summary.contains("peak_drift_in")) {
      ratio = 0.0;
      for (const json& d : res.summary["peak_drift_in"]) ratio = std::max(ratio, d.get<double>() / s.config.story_height_in);
    }
    run.point = {run.im, ratio, res.state != "ok" || ratio >= s.config.collapse_drift_pct / 100.0};
    runs[it->second].push_back(run);
  }
  for (auto& [key, v] : runs) std::sort(v.begin(), v.end(), [](const RunInfo& a, const RunInfo& b) { return a.im < b.im; });
  return runs;
}

std::vector<TracePoint> points(const std::vector<RunInfo>& runs) {
  std::vector<TracePoint> p;
  for (const RunInfo& r : runs) p.push_back(r.point);
  return p;
}

std::string num(double v) { return std::isfinite(v) ? format_shortest(v) : (std::isnan(v) ? "" : "inf"); }

struct Outputs {
  int runs = 0, failed = 0;
  std::vector<std::string> fragility_lines;
};

/// Writes the CSV files and the plots; returns counts and one line per fragility fit.
Outputs write_results(const std::string& out, const IdaSet& s,
                      std::map<std::pair<int, int>, std::vector<RunInfo>>& runs, bool quiet) {
  Outputs o;
  const IdaConfig& cfg = s.config;
  std::ostringstream rows, fr, caps, fits;
  rows << "case,record,im_g,scale,peak_drift_ratio,collapse,status,label,error\n";
  fr << "case,im_g,drift_ratio_p16,drift_ratio_p50,drift_ratio_p84,records\n";
  caps << "case,drift_limit_pct,record,capacity_im_g,reached\n";
  fits << "case,drift_limit_pct,intensity_measure,median_g,beta,median_lo95_g,median_hi95_g,beta_lo95,beta_hi95,"
          "records_reached,records_censored,method,note\n";
  const fs::path plots = fs::path(out) / "plots";
  fs::create_directories(plots);
  std::ofstream frag_dat(plots / "fragility.dat");
  frag_dat << "# im_g then P(exceed) per case and drift limit, in the order of fragility.csv\n";
  std::vector<LognormalFit> all_fits;
  for (std::size_t c = 0; c < s.cases.size(); ++c) {
    const CaseInfo& k = s.cases[c];
    std::ofstream curves(plots / ("ida_" + k.def.label + ".dat"));
    curves << "# drift_ratio_pct im_g; one block per record (gnuplot index), from (0, 0); collapse marked by the"
              " last point at the collapse limit\n";
    std::vector<std::vector<TracePoint>> traced;
    double upper = std::numeric_limits<double>::infinity(), max_collapse = 0.0;
    for (std::size_t r = 0; r < s.records.size(); ++r) {
      if (!s.records[r].error.empty()) continue;
      const std::vector<RunInfo>& v = runs[{static_cast<int>(c), static_cast<int>(r)}];
      if (v.empty()) continue;
      for (const RunInfo& run : v) {
        ++o.runs;
        if (run.status != "ok") ++o.failed;
        rows << k.def.label << "," << bi::csv_field(s.records[r].rec.label) << "," << num(run.im) << ","
             << num(run.scale) << "," << num(run.point.drift_ratio) << "," << (run.point.collapse ? 1 : 0) << ","
             << run.status << "," << run.label << "," << bi::csv_field(run.error) << "\n";
      }
      const std::vector<TracePoint> p = points(v);
      traced.push_back(p);
      curves << "# " << s.records[r].rec.label << "\n0 0\n";
      double collapse = std::numeric_limits<double>::infinity(), top = 0.0;
      for (const TracePoint& t : p) {
        top = std::max(top, t.im);
        if (t.collapse) collapse = std::min(collapse, t.im);
      }
      for (const TracePoint& t : p) {
        if (t.collapse || t.im > collapse) continue;
        curves << num(100.0 * t.drift_ratio) << " " << num(t.im) << "\n";
      }
      if (std::isfinite(collapse)) {
        curves << num(cfg.collapse_drift_pct) << " " << num(collapse) << "\n";
        max_collapse = std::max(max_collapse, collapse);
      } else {
        upper = std::min(upper, top);
      }
      curves << "\n\n";
    }
    if (traced.empty()) continue;
    if (!std::isfinite(upper)) upper = max_collapse;
    std::ofstream fdat(plots / ("ida_" + k.def.label + "_fractiles.dat"));
    fdat << "# im_g drift_ratio_pct p16 p50 p84 (empty: infinite, collapsed)\n";
    const int grid = 60;
    for (int g = 1; g <= grid; ++g) {
      const double im = upper * g / grid;
      std::vector<double> d;
      for (const auto& p : traced) d.push_back(drift_at(p, im));
      const double q16 = quantile(d, 0.16), q50 = quantile(d, 0.50), q84 = quantile(d, 0.84);
      int n = 0;
      for (double x : d) n += !std::isnan(x);
      fr << k.def.label << "," << num(im) << "," << num(q16) << "," << num(q50) << "," << num(q84) << "," << n << "\n";
      auto pct = [](double x) { return std::isfinite(x) ? format_shortest(100.0 * x) : std::string("NaN"); };
      fdat << num(im) << " " << pct(q16) << " " << pct(q50) << " " << pct(q84) << "\n";
    }
    for (double limit_pct : cfg.drift_limits_pct) {
      std::vector<double> reached, censored;
      std::size_t ti = 0;
      for (std::size_t r = 0; r < s.records.size(); ++r) {
        if (!s.records[r].error.empty() || runs[{static_cast<int>(c), static_cast<int>(r)}].empty()) continue;
        const Capacity cap = capacity_at(traced[ti++], limit_pct / 100.0);
        (cap.reached ? reached : censored).push_back(cap.im);
        caps << k.def.label << "," << num(limit_pct) << "," << bi::csv_field(s.records[r].rec.label) << "," << num(cap.im)
             << "," << (cap.reached ? 1 : 0) << "\n";
      }
      const LognormalFit f = fit_lognormal_fragility(reached, censored);
      all_fits.push_back(f);
      fits << k.def.label << "," << num(limit_pct) << "," << cfg.intensity_measure << "," << (f.ok ? num(f.median) : "")
           << "," << (f.ok ? num(f.beta) : "") << "," << (f.ok ? num(f.median_lo) : "") << ","
           << (f.ok ? num(f.median_hi) : "") << "," << (f.ok ? num(f.beta_lo) : "") << ","
           << (f.ok ? num(f.beta_hi) : "") << "," << f.exceeded << "," << f.censored << ",\"" << kFragilityMethod
           << "\"," << bi::csv_field(f.note) << "\n";
      std::ostringstream line;
      line << k.def.label << ": drift " << format_shortest(limit_pct) << " %: ";
      if (f.ok)
        line << "median " << format_fixed(f.median, 3) << " g [" << format_fixed(f.median_lo, 3) << ", "
             << format_fixed(f.median_hi, 3) << "], beta " << format_fixed(f.beta, 3) << " [" << format_fixed(f.beta_lo, 3)
             << ", " << format_fixed(f.beta_hi, 3) << "], " << f.exceeded << " reached, " << f.censored << " censored";
      else
        line << "no fit (" << f.note << "; " << f.exceeded << " reached, " << f.censored << " censored)";
      o.fragility_lines.push_back(line.str());
    }
  }
  double im_max = 0.0;
  for (const auto& [key, v] : runs)
    for (const RunInfo& r : v) im_max = std::max(im_max, r.im);
  for (int g = 0; g <= 100; ++g) {
    const double im = im_max * g / 100.0;
    frag_dat << num(im);
    for (const LognormalFit& f : all_fits) frag_dat << " " << (f.ok ? num(lognormal_cdf(im, f.median, f.beta)) : "NaN");
    frag_dat << "\n";
  }
  frag_dat.close();
  bi::write_file_atomic(fs::path(out) / "ida_runs.csv", rows.str());
  bi::write_file_atomic(fs::path(out) / "ida_fractiles.csv", fr.str());
  bi::write_file_atomic(fs::path(out) / "capacities.csv", caps.str());
  bi::write_file_atomic(fs::path(out) / "fragility.csv", fits.str());

  // Figures.
  const std::string im_name = cfg.intensity_measure == "pga" ? "PGA (g)" : "Sa(T1, " + format_shortest(100.0 * cfg.damping_ratio) + " %) (g)";
  std::ofstream gp(plots / "plots.gp");
  gp << "# gnuplot script written by hybridsim ida; run from " << plots.string() << "\n"
     << "set terminal pngcairo size " << 520 * s.cases.size() + 120 << ",620 noenhanced\n"
     << "set output '../ida-curves.png'\n"
     << "set multiplot layout 1," << s.cases.size() << " title " << gnuplot_quote("IDA curves: " + cfg.name) << "\n"
     << "set grid\nset key top left\n"
     << "set xlabel 'peak interstory drift ratio (%)'\nset ylabel " << gnuplot_quote(im_name) << "\n"
     << "set xrange [0:" << format_shortest(cfg.collapse_drift_pct * 1.05) << "]\nset yrange [0:*]\n";
  for (const CaseInfo& k : s.cases) {
    gp << "set title " << gnuplot_quote(k.def.label + " (T1 " + format_fixed(k.t1_s, 3) + " s)") << "\n"
       << "plot for [i=0:" << std::max<std::size_t>(1, s.records.size()) - 1 << "] "
       << gnuplot_quote("ida_" + k.def.label + ".dat")
       << " index i using 1:2 with linespoints lc rgb '#b0b0b0' pt 7 ps 0.4 notitle, \\\n"
       << "     " << gnuplot_quote("ida_" + k.def.label + "_fractiles.dat")
       << " using 2:1 with lines lw 3 lc rgb '#2ca02c' title '16 %', \\\n"
       << "     '' using 3:1 with lines lw 3 lc rgb '#1f77b4' title '50 %', \\\n"
       << "     '' using 4:1 with lines lw 3 lc rgb '#d62728' title '84 %'\n";
  }
  gp << "unset multiplot\n"
     << "set terminal pngcairo size 900,620 noenhanced\nset output '../fragility.png'\n"
     << "set title " << gnuplot_quote("Fragility (lognormal, maximum likelihood): " + cfg.name) << "\n"
     << "set xlabel " << gnuplot_quote(im_name) << "\nset ylabel 'P(peak interstory drift ratio >= limit)'\n"
     << "set xrange [0:*]\nset yrange [0:1]\nset key bottom right\nplot ";
  const char* colors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};
  int col = 2;
  for (std::size_t c = 0; c < s.cases.size(); ++c) {
    for (std::size_t l = 0; l < cfg.drift_limits_pct.size(); ++l, ++col) {
      gp << (col > 2 ? ", \\\n     " : "") << "'fragility.dat' using 1:" << col << " with lines lw 2 dt " << c + 1
         << " lc rgb '" << colors[l % 6] << "' title "
         << gnuplot_quote(s.cases[c].def.label + ", " + format_shortest(cfg.drift_limits_pct[l]) + " %");
    }
  }
  gp << "\n";
  gp.close();
  const std::string plot_error =
      common::run_gnuplot(fs::absolute(plots / "plots.gp").string(), plots.string(), (plots / "gnuplot.log").string());
  if (!plot_error.empty())
    std::cerr << "hybridsim ida: warning: " << plot_error << "\n";
  else if (!quiet)
    std::cout << "plots: " << (fs::path(out) / "ida-curves.png").string() << ", "
              << (fs::path(out) / "fragility.png").string() << "\n";
  return o;
}

}  // namespace

int ida_command(const IdaOptions& o) {
  const auto t0 = Clock::now();
  IdaSet s;
  std::unique_ptr<BatchComm> comm_owner;
  try {
    s = prepare(o);
    if (o.mpi && o.slurm_task) throw BatchInputError("--mpi and --slurm-task exclude each other");
  } catch (const std::exception& e) {
    std::cerr << "hybridsim ida: " << e.what() << "\n";
    return 2;
  }
  if (o.mpi) {
    try {
      comm_owner = make_mpi_comm();
    } catch (const std::exception& e) {
      std::cerr << "hybridsim ida: " << e.what() << "\n";
      return 2;
    }
  }
  const int rank = comm_owner ? comm_owner->rank() : 0, size = comm_owner ? comm_owner->size() : 1;

  std::unique_ptr<bi::DirLock> lock;
  std::vector<std::size_t> my_records;
  try {
    fs::create_directories(bi::runs_dir(o.out));
    if (!o.mpi && !o.slurm_task) lock = std::make_unique<bi::DirLock>(o.out);
    const fs::path m = fs::path(o.out) / "ida.json";
    const json now = manifest(s);
    std::error_code ec;
    if (fs::exists(m, ec)) {
      const json before = json::parse(bi::read_file(m), nullptr, false);
      for (const char* key : {"intensity_measure", "damping_ratio", "records"})
        if (before.is_discarded() || before.value(key, json()) != now[key])
          throw BatchInputError(o.out + " holds an IDA of another record set or intensity measure (" + key +
                                " differs in ida.json): use another --out");
    }
    if (rank == 0 && !o.slurm_task) {
      std::ostringstream text;
      text << std::setw(2) << now << "\n";
      bi::write_file_atomic(m, text.str());
      bi::write_file_atomic(fs::path(o.out) / "effective-ida.yaml", ida_config_to_yaml(s.config));
    }
    if (o.slurm_task) {
      const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
      char* end = nullptr;
      const long task = id ? std::strtol(id, &end, 10) : -1;
      if (!id || *end != '\0' || task < 0)
        throw BatchInputError("--slurm-task needs SLURM_ARRAY_TASK_ID (0-based record index; sbatch --array=0-" +
                              std::to_string(s.records.size() - 1) + ")");
      if (static_cast<std::size_t>(task) < s.records.size()) my_records.push_back(static_cast<std::size_t>(task));
    } else {
      for (std::size_t r = 0; r < s.records.size(); ++r) my_records.push_back(r);
    }
  } catch (const std::exception& e) {
    std::cerr << "hybridsim ida: " << e.what() << "\n";
    return 2;
  }

  if (!o.quiet && rank == 0) {
    std::cout << "ida: " << s.cases.size() << " case(s) x " << s.records.size() << " record(s), up to "
              << s.config.hunt.max_runs << " runs each, IM " << s.config.intensity_measure << ", " << o.jobs
              << " at a time; results in " << o.out << "\n";
    for (const CaseInfo& c : s.cases) std::cout << "  case " << c.def.label << ": T1 " << format_fixed(c.t1_s, 4) << " s\n";
    for (const RecordInfo& r : s.records)
      if (!r.error.empty()) std::cout << "  record " << r.rec.label << " skipped: " << r.error << "\n";
  }

  BatchOptions bo;
  bo.out = o.out;
  bo.jobs = o.jobs;
  bo.mpi = o.mpi;
  bo.quiet = o.quiet;
  bo.duration_s = s.config.duration_s;
  bo.transport = s.config.transport == "in_process" ? "in_process" : "";
  bo.config = s.cases.front().def.config;

  int upper_bound = 0;
  for (std::size_t r : my_records)
    if (s.records[r].error.empty()) upper_bound += static_cast<int>(s.cases.size()) * s.config.hunt.max_runs;
  auto runs = finished_runs(o.out, s);
  int finished_before = 0;
  for (std::size_t r : my_records)
    for (std::size_t c = 0; c < s.cases.size(); ++c)
      finished_before += static_cast<int>(runs[{static_cast<int>(c), static_cast<int>(r)}].size());
  bi::Progress progress(upper_bound, finished_before, upper_bound - finished_before, o.jobs, o.quiet || rank != 0,
                        size > 1 ? "rank " + std::to_string(rank) + ": " : "", !o.mpi);
  if (!o.mpi) bi::install_interrupt_handlers();

  bool interrupted = false, stuck = false;
  int previous_finished = -1;
  std::string error;
  for (int round = 0; !interrupted; ++round) {
    bi::BatchSet b;
    b.config = bo.config;
    b.name = s.config.name;
    b.stories = s.cases.front().stories;
    b.duration_s = s.config.duration_s;
    int finished = 0;
    for (std::size_t r : my_records) {
      if (!s.records[r].error.empty()) continue;
      for (std::size_t c = 0; c < s.cases.size(); ++c) {
        const auto& done = runs[{static_cast<int>(c), static_cast<int>(r)}];
        finished += static_cast<int>(done.size());
        for (double im : next_runs(s.config.hunt, points(done))) {
          BatchRecord br = s.records[r].rec;
          br.scale = im / s.records[r].im_unit[c];
          br.label = run_label(s.cases[c], s.records[r], im);
          br.config = s.cases[c].def.config;
          b.records.push_back(br);
        }
      }
    }
    if (b.records.empty()) break;
    if (finished == previous_finished) {  // a whole round finished nothing: machinery failure
      stuck = true;
      break;
    }
    previous_finished = finished;
    std::vector<std::size_t> mine;
    for (std::size_t i = static_cast<std::size_t>(rank); i < b.records.size(); i += static_cast<std::size_t>(size))
      mine.push_back(i);
    try {
      interrupted = bi::run_records(bo, b, mine, "", &progress).interrupted;
    } catch (const std::exception& e) {
      error = e.what();
    }
    if (comm_owner && !comm_owner->all(error.empty())) break;
    if (!error.empty()) break;
    runs = finished_runs(o.out, s);
  }
  progress.end();
  if (!error.empty()) {
    std::cerr << "hybridsim ida: " << error << "\n";
    return 2;
  }
  if (stuck) std::cerr << "hybridsim ida: runs did not finish (see the worker.log files in " << o.out << "/runs)\n";
  if (rank != 0) return 0;
  if (o.slurm_task) {
    std::cout << "slurm task done; build the results with the same command without --slurm-task\n";
    std::cout << "cases=" << s.cases.size() << " records=" << my_records.size() << " runs=" << progress.finished_now()
              << " failed=" << progress.failed() << " seconds="
              << format_fixed(std::chrono::duration<double>(Clock::now() - t0).count(), 2) << std::endl;
    return 0;
  }
  Outputs out;
  try {
    out = write_results(o.out, s, runs, o.quiet);
  } catch (const std::exception& e) {
    std::cerr << "hybridsim ida: cannot write the results: " << e.what() << "\n";
    return 1;
  }
  for (const std::string& line : out.fragility_lines) std::cout << line << "\n";
  if (interrupted) std::cout << "interrupted: run the same command again to resume\n";
  std::cout << "cases=" << s.cases.size() << " records=" << s.records.size() << " runs=" << out.runs
            << " failed=" << out.failed
            << " seconds=" << format_fixed(std::chrono::duration<double>(Clock::now() - t0).count(), 2) << std::endl;
  if (interrupted) return 130;
  return stuck ? 1 : 0;
}

}  // namespace server::ida
