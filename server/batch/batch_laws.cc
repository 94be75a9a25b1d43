// hybridsim batch --laws: the record set once per control law (control/controller.h), one
// ordinary batch per law in OUT/<law>/, then one law x record table and plots.
#include "server/batch/batch.h"

#include "common/gnuplot.h"
#include "common/number_format.h"
#include "control/controller.h"
#include "control/friction_inverse.h"
#include "server/batch/batch_files.h"
#include "server/run/run_config.h"

#include <nlohmann/json.hpp>

#include <cmath>
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

std::string num(double v) { return std::isfinite(v) ? common::format_shortest(v) : std::string("NaN"); }

}  // namespace

int batch_laws_command(const BatchOptions& o) {
  const std::vector<std::string> laws = split_laws(o.laws);
  std::vector<BatchRecord> records;
  RunConfig base;
  try {
    if (laws.empty()) throw std::invalid_argument("--laws: give at least one law");
    for (const std::string& law : laws) control::law_from_string(law);
    base = load_run_config(o.config);
    try {
      control::FrictionInverse check(base.damper_model, base.control.min_kinetic_friction_kip);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(o.config + ": --laws: the damper model cannot be controlled: " + e.what());
    }
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

  // law x record table: the criteria of Ohtori et al. (2004) (J1-J3 peaks, their RMS
  // counterparts), peak drift, peak damper force, dissipated energy and actuator effort, all in
  // full (round-trip) precision so that a row can be compared with a plain run's summary.json.
  std::ostringstream csv;
  csv << "law,record,status,J1_peak_drift_ratio,J2_peak_floor_accel,J3_peak_base_shear,J1_rms_drift_ratio,"
         "J2_rms_floor_accel,J3_rms_base_shear,peak_drift_in,peak_floor_accel_g,peak_damper_force_kip,"
         "damper_energy_kip_in,input_energy_kip_in,actuator_travel_in,actuator_peak_speed_in_per_s,"
         "controller_us_per_step\n";
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
          j = json();
        }
      }
      s[law][r.label] = j;
      const std::string status = j.is_object() ? j.value("status", std::string("?")) : std::string("not run");
      csv << law << "," << r.label << "," << status;
      if (status == "ok" && j.contains("criteria")) {
        const json& c = j["criteria"];
        const json ctl = j.contains("control") ? j["control"] : json::object();
        const double input = j.contains("energy_kip_in") && j["energy_kip_in"].contains("input")
                                 ? j["energy_kip_in"]["input"].get<double>()
                                 : std::nan("");
        for (const char* k : {"J1_peak_drift_ratio", "J2_peak_floor_accel", "J3_peak_base_shear", "J1_rms_drift_ratio",
                              "J2_rms_floor_accel", "J3_rms_base_shear"})
          csv << "," << num(c[k].get<double>());
        csv << "," << num(max_of(j, "peak_drift_in")) << "," << num(max_of(j, "peak_floor_accel_g")) << ","
            << num(max_of(j, "peak_damper_force_kip")) << "," << num(sum_of(j, "damper_energy_kip_in")) << ","
            << num(input) << "," << num(sum_of(ctl, "actuator_travel_in")) << ","
            << num(max_of(ctl, "actuator_peak_speed_in_per_s")) << ","
            << num(ctl.contains("controller_us_per_step") ? ctl["controller_us_per_step"].get<double>() : 0.0) << "\n";
      } else {
        csv << ",,,,,,,,,,,,,,\n";
      }
    }
  batch_internal::write_file_atomic(fs::path(o.out) / "laws-summary.csv", csv.str());

  // Plots: criteria per law (one bar per record), drift envelopes per record with the laws.
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
     << "set terminal pngcairo size 900,540 noenhanced font ',10'\nset grid ytics\nset key outside right\n"
     << "set style data histogram\nset style histogram clustered gap 1\nset style fill solid 0.8 border -1\n"
     << "set xtics rotate by -20\nset yrange [0:*]\n";
  std::string record_words;
  for (const BatchRecord& r : records) record_words += (record_words.empty() ? "" : " ") + r.label;
  const char* names[] = {"J1 peak drift ratio", "J2 peak floor acceleration", "J3 peak base shear"};
  for (int k = 0; k < 3; ++k) {
    gp << "set output '../criteria-J" << k + 1 << ".png'\n"
       << "set title " << common::gnuplot_quote(std::string(names[k]) + " relative to the building without dampers: " + base.name) << "\n"
       << "set ylabel 'J" << k + 1 << "'\n"
       << "plot for [r=0:" << records.size() - 1 << "] 'criteria.dat' using " << 2 + k
       << "+3*r:xtic(1) title word('" << record_words << "', r+1)\n";
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
    gp << "set output " << common::gnuplot_quote("../drift-envelope-" + r.label + ".png") << "\n"
       << "set title " << common::gnuplot_quote("Peak interstory drift, " + r.label + ": " + base.name + " by control law") << "\n"
       << "set xlabel 'peak interstory drift (in)'\nset ylabel 'story'\nset ytics 1\nset yrange [0:" << stories
       << "]\nset xrange [0:*]\n"
       << "plot for [l=1:" << laws.size() << "] " << common::gnuplot_quote("drift-" + r.label + ".dat")
       << " using (column(l+1)):1 with linespoints lw 2 pt 7 title word('";
    for (std::size_t l = 0; l < laws.size(); ++l) gp << (l ? " " : "") << laws[l];
    gp << "', l)\n";
  }
  gp.close();
  const std::string warning = common::run_gnuplot("laws.gp", plots.string(), (plots / "gnuplot.log").string());
  if (!warning.empty()) std::cerr << "hybridsim batch: warning: " << warning << "\n";
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
