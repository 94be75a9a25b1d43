#include "server/batch/batch_report.h"

#include "common/gnuplot.h"
#include "common/number_format.h"
#include "server/batch/batch_files.h"

#include <algorithm>
#include <fstream>
#include <iostream>
#include <sstream>

namespace server::batch_internal {

namespace fs = std::filesystem;
using nlohmann::json;

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) {
    if (c == '"') q += '"';
    q += (c == '\n' || c == '\r') ? ' ' : c;
  }
  return q + "\"";
}

std::string summary_csv(const BatchSet& b, const std::vector<RunResult>& results) {
  std::ostringstream o;
  o << "record,label,scale,pga_g";
  for (int i = 1; i <= b.stories; ++i) o << ",peak_drift_story" << i << "_in";
  for (int i = 1; i <= b.stories; ++i) o << ",residual_drift_story" << i << "_in";
  for (int i = 1; i <= b.stories; ++i) o << ",peak_floor_accel_floor" << i << "_g";
  for (int k = 1; k <= b.dampers; ++k) o << ",peak_damper_force_damper" << k << "_kip";
  for (int k = 1; k <= b.dampers; ++k) o << ",damper_energy_damper" << k << "_kip_in";
  o << ",status,error\n";
  for (std::size_t i = 0; i < b.records.size(); ++i) {
    const BatchRecord& r = b.records[i];
    const RunResult& res = results[i];
    o << csv_field(r.shown) << "," << csv_field(r.label) << "," << common::format_shortest(r.scale);
    const json& s = res.summary;
    // Figures only when the run got going (the record was read): a run that failed on its
    // record has empty arrays.
    const bool figures = s.is_object() && s.contains("peak_drift_in") && s["peak_drift_in"].is_array() &&
                         !s["peak_drift_in"].empty();
    o << "," << (figures ? common::format_shortest(s["pga_g"].get<double>()) : "");
    auto vec = [&](const char* key, int n) {
      for (int k = 0; k < n; ++k) {
        o << ",";
        if (figures && s.contains(key) && s[key].is_array() && static_cast<int>(s[key].size()) > k)
          o << common::format_shortest(s[key][k].get<double>());
      }
    };
    vec("peak_drift_in", b.stories);
    vec("residual_drift_in", b.stories);
    vec("peak_floor_accel_g", b.stories);
    vec("peak_damper_force_kip", b.dampers);
    vec("damper_energy_kip_in", b.dampers);
    std::string error = s.is_object() ? s.value("error", "") : "";
    if (res.state == "failed" && !res.finished && !error.empty()) error += " (not final: redone on resume)";
    o << "," << res.state << "," << csv_field(error) << "\n";
  }
  return o.str();
}

std::string make_plots(const std::string& out, const BatchSet& b, const std::vector<RunResult>& results) {
  const fs::path dir = fs::path(out) / "plots";
  fs::create_directories(dir);
  std::ofstream env(dir / "drift-envelope.dat"), stats(dir / "drift-envelope-stats.dat"), pga(dir / "drift-vs-pga.dat");
  env << "# story peak_drift_in; one block per ok record (gnuplot index)\n";
  pga << "# pga_g peak_drift_story1_in ... (ok records)\n";
  int blocks = 0;
  std::vector<double> sum(b.stories, 0.0), mx(b.stories, 0.0);
  for (std::size_t i = 0; i < b.records.size(); ++i) {
    if (results[i].state != "ok") continue;
    const json& s = results[i].summary;
    if (!s.contains("peak_drift_in") || static_cast<int>(s["peak_drift_in"].size()) != b.stories) continue;
    env << "# " << b.records[i].label << "\n0 0\n";
    pga << common::format_shortest(s["pga_g"].get<double>());
    for (int k = 0; k < b.stories; ++k) {
      const double d = s["peak_drift_in"][k].get<double>();
      env << k + 1 << " " << common::format_shortest(d) << "\n";
      pga << " " << common::format_shortest(d);
      sum[k] += d;
      mx[k] = std::max(mx[k], d);
    }
    env << "\n\n";
    pga << "\n";
    ++blocks;
  }
  stats << "# story mean_peak_drift_in max_peak_drift_in\n0 0 0\n";
  for (int k = 0; k < b.stories; ++k)
    stats << k + 1 << " " << common::format_shortest(blocks ? sum[k] / blocks : 0.0) << " " << common::format_shortest(mx[k]) << "\n";
  env.close();
  stats.close();
  pga.close();
  if (blocks == 0) return "no ok runs: no plots";

  std::ofstream gp(dir / "plots.gp");
  gp << "# gnuplot script written by hybridsim batch; run from " << dir.string() << "\n"
     << "set terminal pngcairo size 900,650 noenhanced\n"
     << "set grid\n"
     << "set key outside right\n"
     << "set output '../drift-envelope.png'\n"
     << "set title " << common::gnuplot_quote("Peak interstory drift envelope: " + b.name + ", " + std::to_string(blocks) + " records") << "\n"
     << "set xlabel 'peak interstory drift (in)'\nset ylabel 'story'\n"
     << "set ytics 1\nset yrange [0:" << b.stories << "]\nset xrange [0:*]\n"
     << "plot for [i=0:" << blocks - 1
     << "] 'drift-envelope.dat' index i using 2:1 with linespoints lc rgb '#b0b0b0' pt 7 ps 0.5 notitle, \\\n"
     << "     'drift-envelope-stats.dat' using 2:1 with linespoints lw 3 lc rgb '#1f77b4' pt 7 title 'mean', \\\n"
     << "     'drift-envelope-stats.dat' using 3:1 with linespoints lw 3 lc rgb '#d62728' pt 5 title 'max'\n"
     << "set output '../drift-vs-pga.png'\n"
     << "set title " << common::gnuplot_quote("Peak interstory drift vs PGA: " + b.name) << "\n"
     << "set xlabel 'PGA (g)'\nset ylabel 'peak interstory drift (in)'\n"
     << "set autoscale\nset ytics auto\nset xrange [0:*]\nset yrange [0:*]\n"
     << "plot for [s=1:" << b.stories << "] 'drift-vs-pga.dat' using 1:(column(s+1)) with points pt 7 ps 1.3 title sprintf('story %d', s)\n";
  gp.close();
  return common::run_gnuplot(fs::absolute(dir / "plots.gp").string(), dir.string(), (dir / "gnuplot.log").string());
}

Counts count(const std::vector<RunResult>& results) {
  Counts c;
  c.records = static_cast<int>(results.size());
  for (const RunResult& r : results) {
    if (r.state == "ok") ++c.ok;
    else if (r.state == "failed") ++c.failed;
    else ++c.not_run;
  }
  return c;
}

void write_outputs(const std::string& out, const BatchSet& b, const std::vector<RunResult>& results, bool quiet) {
  write_file_atomic(fs::path(out) / "summary.csv", summary_csv(b, results));
  const std::string warning = make_plots(out, b, results);
  if (!warning.empty()) std::cerr << "hybridsim batch: warning: " << warning << "\n";
  if (!quiet) {
    std::cout << "summary: " << (fs::path(out) / "summary.csv").string() << "\n";
    if (warning.empty())
      std::cout << "plots: " << (fs::path(out) / "drift-envelope.png").string() << ", "
                << (fs::path(out) / "drift-vs-pga.png").string() << "\n";
  }
}

void print_final_line(const Counts& c, double seconds) {
  std::cout << "records=" << c.records << " ok=" << c.ok << " failed=" << c.failed
            << " seconds=" << common::format_fixed(seconds, 2) << std::endl;
}

}  // namespace server::batch_internal
