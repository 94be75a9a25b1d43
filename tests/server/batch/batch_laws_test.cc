// `hybridsim batch --laws` as a user runs it (the driver and its worker processes, in-process
// substructure so that it is deterministic and fast): the law x record table has one row per
// law and record in order, its passive_off rows carry exactly the numbers of a plain batch of
// the same config without a control block (today's passive run), the plots are drawn, and over
// the whole batch the electric actuators never leave their stroke nor exceed their velocity
// limit (asserted from every run's time history, not from the summaries).
#include "run_process.h"
#include "damper/model/brfd_config.h"
#include "server/run/run_config.h"
#include "test_paths.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::vector<std::string> kLaws{"passive_off", "passive_on", "lyapunov", "clipped_optimal"};
const std::vector<std::string> kLabels{"ElCentro", "Sylmar"};
constexpr double kDurationS = 4.0;  // shorter than both records (53.7 s, 40 s)

struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  int col(const std::string& name) const {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) ADD_FAILURE() << "no column " << name;
    return static_cast<int>(it - header.begin());
  }
};

Table read_csv(const std::string& path) {
  Table t;
  std::ifstream f(path);
  std::string line;
  bool first = true;
  while (std::getline(f, line)) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    (first ? t.header : t.rows.emplace_back()) = cells;
    first = false;
  }
  return t;
}

json read_json(const std::string& path) {
  std::ifstream f(path);
  json j;
  f >> j;
  return j;
}

double max_of(const json& a) {
  double m = -1e300;
  for (const auto& v : a) m = std::max(m, v.get<double>());
  return m;
}

double sum_of(const json& a) {
  double s = 0.0;
  for (const auto& v : a) s += v.get<double>();
  return s;
}

test_support::ProcessResult hybridsim(const std::vector<std::string>& args) {
  std::vector<std::string> argv{test_paths::bin_dir() + "/hybridsim"};
  argv.insert(argv.end(), args.begin(), args.end());
  return test_support::run_process(argv);
}

TEST(BatchLaws, TableRowsPerLawAndRecordPassiveOffIsThePlainRunActuatorsWithinLimits) {
  const std::string dir = test_support::fresh_temp_dir("batch-laws");
  const std::string records = test_paths::source_dir() + "/records/";
  test_support::write_text(dir + "/records.txt",
                           records + "ImperialValley1940_ElCentroArray9_180_NS_RSN6.AT2 1.0 ElCentro\n" + records +
                               "Northridge1994_SylmarConverterSta_142_RSN1084.AT2 1.0 Sylmar\n");
  const std::string config = test_paths::source_dir() + "/configs/three-story-controlled.yaml";
  const std::string duration = std::to_string(kDurationS);
  std::string laws;
  for (const std::string& l : kLaws) laws += (laws.empty() ? "" : ",") + l;

  const auto r = hybridsim({"batch", "--config", config, "--records", dir + "/records.txt", "--out", dir + "/laws",
                            "--laws", laws, "--duration", duration, "--transport", "in_process", "--jobs", "2", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;

  // The plain run: the same config without its control block (no controller at all).
  server::RunConfig plain = server::load_run_config(config);
  plain.control = control::ControlConfig{};
  test_support::write_text(dir + "/plain.yaml", server::run_config_to_yaml(plain));
  const auto p = hybridsim({"batch", "--config", dir + "/plain.yaml", "--records", dir + "/records.txt", "--out",
                            dir + "/plain", "--duration", duration, "--transport", "in_process", "--jobs", "2", "--quiet"});
  ASSERT_EQ(p.exit_code, 0) << p.out << p.err;

  const Table t = read_csv(dir + "/laws/laws-summary.csv");
  ASSERT_EQ(t.rows.size(), kLaws.size() * kLabels.size());
  for (const auto& row : t.rows) ASSERT_EQ(row.size(), t.header.size());
  const int c_law = t.col("law"), c_rec = t.col("record"), c_status = t.col("status");
  for (std::size_t l = 0; l < kLaws.size(); ++l)
    for (std::size_t k = 0; k < kLabels.size(); ++k) {
      const auto& row = t.rows[l * kLabels.size() + k];
      EXPECT_EQ(row[c_law], kLaws[l]);
      EXPECT_EQ(row[c_rec], kLabels[k]);
      EXPECT_EQ(row[c_status], "ok");
    }

  // passive_off rows = the plain run's summary.json, number for number (round-trip printed).
  const std::vector<std::pair<std::string, std::string>> criteria{
      {"J1_peak_drift_ratio", "J1_peak_drift_ratio"}, {"J2_peak_floor_accel", "J2_peak_floor_accel"},
      {"J3_peak_base_shear", "J3_peak_base_shear"},   {"J1_rms_drift_ratio", "J1_rms_drift_ratio"},
      {"J2_rms_floor_accel", "J2_rms_floor_accel"},   {"J3_rms_base_shear", "J3_rms_base_shear"}};
  for (std::size_t k = 0; k < kLabels.size(); ++k) {
    SCOPED_TRACE(kLabels[k]);
    const auto& row = t.rows[k];
    const json s = read_json(dir + "/plain/runs/" + kLabels[k] + "/summary.json");
    ASSERT_EQ(s.at("status"), "ok");
    EXPECT_FALSE(s.contains("control") && s["control"].is_object() && !s["control"].empty());
    for (const auto& [column, key] : criteria) EXPECT_EQ(std::stod(row[t.col(column)]), s["criteria"][key].get<double>()) << column;
    EXPECT_EQ(std::stod(row[t.col("peak_drift_in")]), max_of(s["peak_drift_in"]));
    EXPECT_EQ(std::stod(row[t.col("peak_floor_accel_g")]), max_of(s["peak_floor_accel_g"]));
    EXPECT_EQ(std::stod(row[t.col("peak_damper_force_kip")]), max_of(s["peak_damper_force_kip"]));
    EXPECT_EQ(std::stod(row[t.col("damper_energy_kip_in")]), sum_of(s["damper_energy_kip_in"]));
    EXPECT_EQ(std::stod(row[t.col("input_energy_kip_in")]), s["energy_kip_in"]["input"].get<double>());
    EXPECT_EQ(std::stod(row[t.col("actuator_travel_in")]), 0.0);
    // The time histories agree too, cell by cell, in the plain run's columns.
    const Table a = read_csv(dir + "/plain/runs/" + kLabels[k] + "/time_history.csv");
    const Table b = read_csv(dir + "/laws/passive_off/runs/" + kLabels[k] + "/time_history.csv");
    ASSERT_EQ(a.rows.size(), b.rows.size());
    ASSERT_GT(b.header.size(), a.header.size());
    for (std::size_t i = 0; i < a.rows.size(); ++i)
      for (std::size_t j = 0; j < a.header.size(); ++j) ASSERT_EQ(a.rows[i][j], b.rows[i][b.col(a.header[j])]) << i;
  }
  // The laws do differ (the table is not the same run four times).
  EXPECT_NE(t.rows[0][t.col("J1_peak_drift_ratio")], t.rows[2][t.col("J1_peak_drift_ratio")]);

  // Stroke and velocity limits of the electric actuators over the whole batch, from the time
  // histories (every row of every run of every law).
  const damper::ElectricActuatorParams& lim = plain.damper_model.electric_actuators;
  double fastest_lyapunov = 0.0;
  for (const std::string& law : kLaws)
    for (const std::string& label : kLabels) {
      SCOPED_TRACE(law + " " + label);
      const Table h = read_csv(dir + "/laws/" + law + "/runs/" + label + "/time_history.csv");
      ASSERT_GT(h.rows.size(), static_cast<std::size_t>(kDurationS * 1000 / 2));
      const int time = h.col("time_s");
      double travel = 0.0;
      for (int a = 1; a <= 2; ++a) {
        const int c = h.col("damper1_actuator" + std::to_string(a) + "_in");
        for (std::size_t i = 0; i < h.rows.size(); ++i) {
          const double x = std::stod(h.rows[i][c]);
          ASSERT_GE(x, lim.min_in) << "row " << i;
          ASSERT_LE(x, lim.max_in) << "row " << i;
          if (i == 0) continue;
          const double dx = std::abs(x - std::stod(h.rows[i - 1][c]));
          const double dt = std::stod(h.rows[i][time]) - std::stod(h.rows[i - 1][time]);
          ASSERT_LE(dx / dt, lim.velocity_limit_in_per_s * (1 + 1e-9)) << "row " << i;
          travel += dx;
          if (law == "lyapunov") fastest_lyapunov = std::max(fastest_lyapunov, dx / dt);
        }
      }
      if (law == "passive_off") EXPECT_EQ(travel, 0.0);
      else EXPECT_GT(travel, 0.0);
    }
  // The rate limit is reached (bang-bang switching), so the bound above is exercised.
  EXPECT_GT(fastest_lyapunov, 0.99 * lim.velocity_limit_in_per_s);

  if (fs::exists("/usr/bin/gnuplot")) {
    for (const char* png : {"criteria-J1.png", "criteria-J2.png", "criteria-J3.png", "drift-envelope-ElCentro.png",
                                   "drift-envelope-Sylmar.png"})
      EXPECT_GT(fs::file_size(dir + "/laws/" + std::string(png)), 2000u) << png;
  } else {
    std::cout << "gnuplot not installed: plots not checked\n";
  }
}

TEST(BatchLaws, RunsTheBandBrakeModelAndRefusesAPassiveDamperNamingIt) {
  const std::string dir = test_support::fresh_temp_dir("batch-laws-bb");
  test_support::write_text(dir + "/records.txt", test_paths::source_dir() +
                                                     "/records/Kocaeli1999_Duzce_270_RSN1158.AT2 1.0 Duzce\n");
  server::RunConfig c = server::load_run_config(test_paths::source_dir() + "/configs/three-story-controlled.yaml");
  c.damper_model = damper::load_brfd_params(test_paths::source_dir() + "/configs/brfd-band-brake.yaml");
  test_support::write_text(dir + "/band-brake.yaml", server::run_config_to_yaml(c));
  const auto r = hybridsim({"batch", "--config", dir + "/band-brake.yaml", "--records", dir + "/records.txt", "--out",
                            dir + "/bb", "--laws", "passive_off,lyapunov", "--duration", "3", "--transport", "in_process",
                            "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const Table t = read_csv(dir + "/bb/laws-summary.csv");
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[1][t.col("status")], "ok");
  EXPECT_GT(std::stod(t.rows[1][t.col("actuator_travel_in")]), 0.0);

  c.damper_model = damper::load_brfd_params(test_paths::source_dir() + "/configs/brfd-default.yaml");
  ASSERT_EQ(c.damper_model.kind, damper::DamperKind::passive_lugre);
  test_support::write_text(dir + "/passive.yaml", server::run_config_to_yaml(c));
  const auto p = hybridsim({"batch", "--config", dir + "/passive.yaml", "--records", dir + "/records.txt", "--out",
                            dir + "/p", "--laws", "passive_off", "--duration", "3", "--transport", "in_process"});
  EXPECT_EQ(p.exit_code, 2) << p.out << p.err;
  EXPECT_NE(p.err.find("passive.yaml"), std::string::npos) << p.err;
  EXPECT_NE(p.err.find("passive_lugre"), std::string::npos) << p.err;
}

}  // namespace
