// hybridsim batch --laws: the record set once per control law (control/controller.h), one
// ordinary batch per law in OUT/<law>/, then one law x record table and plots.
#include "server/batch/batch.h"

#include "control/controller.h"
#include "server/run/run_config.h"

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

namespace server {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

std::vector<std::string> split_laws(const std::string& list) {
  std::vector<std::string> laws;
  std::stringstream s(list);
  for (std::string law; std::getline(s, law, ',');)
    if (!law.empty()) laws.push_back(law);
  return laws;
}

double sum_of(const json& j, const char* key) {
  double t = 0.0;
  if (j.contains(key))
    for (const auto& v : j[key]) t += v.get<double>();
  return t;
}

double max_of(const json& j, const char* key) {
  double t = 0.0;
  if (j.contains(key))
    for (const auto& v : j[key]) t = std::max(t, v.get<double>());
  return t;
}

std::string num(double v) {
  std::ostringstream o;
  o << std::setprecision(6) << v;
  return o.str();
}

}  // namespace

int batch_laws_command(const BatchOptions& o) {
  const std::vector<std::string> laws = split_laws(o.laws);
  std::vector<BatchRecord> records;
  RunConfig base;
  try {
    if (laws.empty()) throw std::invalid_argument("--laws: give at least one law");
    for (const std::string& law : laws) control::law_from_string(law);
    base = load_run_config(o.config);
    if (base.damper_model.kind != damper::DamperKind::semiactive)
      throw std::invalid_argument(o.config + ": --laws needs the semi-active damper model (damper model: semiactive)");
    records = load_record_set(o.records);
  } catch (const std::exception& e) {
    std::cerr << "hybridsim batch: " << e.what() << "\n";
    return 2;
  }
  if (o.out.empty()) {
    std::cerr << "hybridsim batch: --out is required\n";
    return 2;
  }
  fs::create_directories(fs::path(o.out) / "configs");
  int rc = 0;
  for (const std::string& law : laws) {
    RunConfig c = base;
    c.control.enabled = true;
    c.control.law = control::law_from_string(law);
    c.name = base.name + "-" + law;
    const std::string cfg = (fs::path(o.out) / "configs" / (law + ".yaml")).string();
    std::ofstream(cfg) << "# " << o.config << " with control.law " << law << " (hybridsim batch --laws)\n"
                       << run_config_to_yaml(c);
    BatchOptions sub = o;
    sub.laws.clear();
    sub.config = cfg;
    sub.out = (fs::path(o.out) / law).string();
    if (!o.quiet) std::cout << "== law " << law << " ==" << std::endl;
    const int r = batch_command(sub);
    if (r == 130) return r;  // interrupted: stop here (resume later)
    rc = std::max(rc, r);
  }

  // law x record table
  std::ostringstream csv;
  csv << "law,record,status,J1_peak_drift_ratio,J2_peak_floor_accel,J3_peak_base_shear,J1_rms,J2_rms,J3_rms,"
         "peak_drift_in,peak_damper_force_kip,damper_energy_kip_in,actuator_travel_in\n";
  const fs::path plots = fs::path(o.out) / "plots";
  fs::create_directories(plots);
  std::map<std::string, std::map<std::string, json>> s;  // law -> label -> summary
  for (const std::string& law : laws)
    for (const BatchRecord& r : records) {
      const fs::path p = fs::path(o.out) / law / "runs" / r.label / "summary.json";
      json j;
      if (fs::exists(p)) {
        try {
          std::ifstream(p) >> j;
        } catch (const std::exception&) {
        }
      }
      s[law][r.label] = j;
      const std::string status = j.is_object() ? j.value("status", std::string("?")) : std::string("not run");
      csv << law << "," << r.label << "," << status;
      if (status == "ok" && j.contains("criteria")) {
        const json& c = j["criteria"];
        csv << "," << num(c["J1_peak_drift_ratio"].get<double>()) << "," << num(c["J2_peak_floor_accel"].get<double>())
            << "," << num(c["J3_peak_base_shear"].get<double>()) << "," << num(c["J1_rms_drift_ratio"].get<double>())
            << "," << num(c["J2_rms_floor_accel"].get<double>()) << "," << num(c["J3_rms_base_shear"].get<double>()) << ","
            << num(max_of(j, "peak_drift_in")) << "," << num(max_of(j, "peak_damper_force_kip")) << ","
            << num(sum_of(j, "damper_energy_kip_in")) << ","
            << num(j.contains("control") ? sum_of(j["control"], "actuator_travel_in") : 0.0) << "\n";
      } else {
        csv << ",,,,,,,,,,\n";
      }
    }
  std::ofstream(fs::path(o.out) / "laws-summary.csv") << csv.str();

  // Plots: criteria per law (one cluster per record), drift envelopes per record with the laws.
  std::ofstream crit(plots / "criteria.dat");
  crit << "# law";
  for (const BatchRecord& r : records) crit << " " << r.label << "_J1 " << r.label << "_J2 " << r.label << "_J3";
  crit << "\n";
  for (const std::string& law : laws) {
    crit << law;
    for (const BatchRecord& r : records) {
      const json& j = s[law][r.label];
      for (const char* k : {"J1_peak_drift_ratio", "J2_peak_floor_accel", "J3_peak_base_shear"})
        crit << " " << (j.is_object() && j.contains("criteria") ? num(j["criteria"][k].get<double>()) : std::string("NaN"));
    }
    crit << "\n";
  }
  crit.close();
  std::ofstream gp(plots / "laws.gp");
  gp << "# gnuplot script written by hybridsim batch --laws; run from " << plots.string() << "\n"
     << "set terminal pngcairo size 1100,650 noenhanced\nset grid ytics\nset key outside right\n"
     << "set style data histogram\nset style histogram clustered gap 1\nset style fill solid 0.8 border -1\n"
     << "set xtics rotate by -20\nset yrange [0:*]\n";
  const char* names[] = {"J1 peak drift ratio", "J2 peak floor acceleration", "J3 peak base shear"};
  for (int k = 0; k < 3; ++k) {
    gp << "set output '../criteria-J" << k + 1 << ".png'\n"
       << "set title '" << names[k] << " relative to the building without dampers: " << base.name << "'\n"
       << "set ylabel 'J" << k + 1 << "'\n"
       << "plot for [r=0:" << records.size() - 1 << "] 'criteria.dat' using " << 2 + k << "+3*r:xtic(1) title columnhead("
       << 2 + k << "+3*r)\n";
  }
  const int stories = static_cast<int>(base.building.story_mass_kip_s2_per_in.size());
  gp << "set style data linespoints\nunset style\nset xtics norotate\nset xtics auto\nset grid\n";
  for (const BatchRecord& r : records) {
    std::ofstream env(plots / ("drift-" + r.label + ".dat"));
    env << "# story then peak drift (in) per law:";
    for (const std::string& law : laws) env << " " << law;
    env << "\n0";
    for (std::size_t l = 0; l < laws.size(); ++l) env << " 0";
    env << "\n";
    for (int st = 0; st < stories; ++st) {
      env << st + 1;
      for (const std::string& law : laws) {
        const json& j = s[law][r.label];
        env << " "
            << (j.is_object() && j.contains("peak_drift_in") && static_cast<int>(j["peak_drift_in"].size()) > st
                    ? num(j["peak_drift_in"][st].get<double>())
                    : std::string("NaN"));
      }
      env << "\n";
    }
    gp << "set output '../drift-envelope-" << r.label << ".png'\n"
       << "set title 'Peak interstory drift, " << r.label << ": " << base.name << " by control law'\n"
       << "set xlabel 'peak interstory drift (in)'\nset ylabel 'story'\nset ytics 1\nset yrange [0:" << stories
       << "]\nset xrange [0:*]\n"
       << "plot for [l=1:" << laws.size() << "] 'drift-" << r.label
       << ".dat' using (column(l+1)):1 with linespoints lw 2 pt 7 title word('";
    for (std::size_t l = 0; l < laws.size(); ++l) gp << (l ? " " : "") << laws[l];
    gp << "', l)\n";
  }
  gp.close();
  const std::string cmd = "cd '" + plots.string() + "' && gnuplot laws.gp > gnuplot.log 2>&1";
  if (std::system(cmd.c_str()) != 0)
    std::cerr << "hybridsim batch: warning: gnuplot failed: see " << (plots / "gnuplot.log").string() << "\n";
  if (!o.quiet) {
    std::cout << "\nlaw x record (J1 peak drift ratio / J2 peak accel / J3 base shear, vs. no damper):\n";
    std::cout << std::left << std::setw(22) << "law";
    for (const BatchRecord& r : records) std::cout << std::setw(24) << r.label;
    std::cout << "\n";
    for (const std::string& law : laws) {
      std::cout << std::setw(22) << law;
      for (const BatchRecord& r : records) {
        const json& j = s[law][r.label];
        std::ostringstream cell;
        cell << std::fixed << std::setprecision(3);
        if (j.is_object() && j.contains("criteria"))
          cell << j["criteria"]["J1_peak_drift_ratio"].get<double>() << "/" << j["criteria"]["J2_peak_floor_accel"].get<double>()
               << "/" << j["criteria"]["J3_peak_base_shear"].get<double>();
        else
          cell << "-";
        std::cout << std::setw(24) << cell.str();
      }
      std::cout << "\n";
    }
    std::cout << "table: " << (fs::path(o.out) / "laws-summary.csv").string() << "\nplots: "
              << (fs::path(o.out) / "criteria-J1.png").string() << " (J2, J3), drift-envelope-<record>.png\n";
  }
  return rc;
}

}  // namespace server
