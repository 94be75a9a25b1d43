// output.format: hdf5 (server/run/hdf5_time_history.h) as a user runs it: `hybridsim run` of
// the 3-story building under El Centro (in-process, 6 s) once with CSV and once with HDF5.
// Every column of time_history.h5 holds exactly the doubles of time_history.csv (read back
// with the HDF5 C API and compared bit for bit with the CSV's round-trip text), h5dump from
// Debian's hdf5-tools (a reader that is not ours) prints the same numbers, and the units and
// the effective config are attributes.
#include "run_configs.h"
#include "run_process.h"
#include "test_paths.h"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>

namespace {

namespace fs = std::filesystem;

struct Runs {
  std::string csv_dir, h5_dir;
};

/// configs/three-story.yaml, in-process, 6 s, in the given output format.
std::string write_config(const std::string& dir, const std::string& format) {
  server::RunConfig c = test_support::short_three_story(6.0, dir);
  c.transport.kind = "in_process";
  c.output.format = format;
  return test_support::write_run_config(dir + "-" + format + ".yaml", c);
}

const Runs& runs() {
  static const Runs r = [] {
    const std::string base = test_support::fresh_temp_dir("hdf5-output");
    Runs out{base + "/csv", base + "/h5"};
    for (const auto& [dir, format] : {std::pair{out.csv_dir, "csv"}, std::pair{out.h5_dir, "hdf5"}}) {
      const auto p = test_support::run_process(
          {test_paths::bin_dir() + "/hybridsim", "run", "--quiet", "--config", write_config(dir, format)});
      EXPECT_EQ(p.exit_code, 0) << p.out << p.err;
    }
    return out;
  }();
  return r;
}

/// Columns of a CSV file, parsed with strtod (exact for round-trip text).
std::map<std::string, std::vector<double>> read_csv(const std::string& path, std::vector<std::string>* order) {
  std::istringstream in(test_support::read_text(path));
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream h(line);
  for (std::string c; std::getline(h, c, ',');) names.push_back(c);
  std::map<std::string, std::vector<double>> cols;
  while (std::getline(in, line)) {
    std::stringstream r(line);
    std::size_t i = 0;
    for (std::string v; std::getline(r, v, ','); ++i) cols[names.at(i)].push_back(std::strtod(v.c_str(), nullptr));
  }
  *order = names;
  return cols;
}

std::vector<double> read_dataset(hid_t file, const std::string& name) {
  const hid_t ds = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
  EXPECT_GE(ds, 0) << name;
  if (ds < 0) return {};
  const hid_t space = H5Dget_space(ds);
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space, &n, nullptr);
  std::vector<double> v(n);
  EXPECT_GE(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
  H5Sclose(space);
  H5Dclose(ds);
  return v;
}

std::string read_string_attribute(hid_t obj, const std::string& name) {
  const hid_t attr = H5Aopen(obj, name.c_str(), H5P_DEFAULT);
  EXPECT_GE(attr, 0) << name;
  if (attr < 0) return "";
  const hid_t type = H5Aget_type(attr);
  std::string s(H5Tget_size(type), '\0');
  H5Aread(attr, type, s.data());
  H5Tclose(type);
  H5Aclose(attr);
  return s.substr(0, s.find('\0'));
}

TEST(Hdf5Output, ColumnsHoldTheCsvDoublesBitForBit) {
  std::vector<std::string> order;
  const auto csv = read_csv(runs().csv_dir + "/time_history.csv", &order);
  ASSERT_EQ(order.size(), 2u + 3 * 3 + 2);  // t, ag, 3 floors x (disp, accel, drift), drum, force
  ASSERT_GT(csv.at("time_s").size(), 6000u);
  const hid_t file = H5Fopen((runs().h5_dir + "/time_history.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  EXPECT_FALSE(fs::exists(runs().h5_dir + "/time_history.csv"));
  std::size_t compared = 0;
  for (const std::string& name : order) {
    const std::vector<double> h5 = read_dataset(file, "/time_history/" + name);
    const std::vector<double>& ref = csv.at(name);
    ASSERT_EQ(h5.size(), ref.size()) << name;
    EXPECT_EQ(std::memcmp(h5.data(), ref.data(), ref.size() * sizeof(double)), 0) << name;
    compared += ref.size();
  }
  EXPECT_EQ(compared, order.size() * csv.at("time_s").size());
  H5Fclose(file);
}

TEST(Hdf5Output, UnitsAndEffectiveConfigAreAttributes) {
  const hid_t file = H5Fopen((runs().h5_dir + "/time_history.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  EXPECT_EQ(read_string_attribute(file, "effective_config_yaml"),
            test_support::read_text(runs().h5_dir + "/effective-config.yaml"));
  EXPECT_EQ(read_string_attribute(file, "run"), "three-story");
  EXPECT_EQ(read_string_attribute(file, "columns").substr(0, 21), "time_s,ground_accel_g");
  double dt = 0.0;
  const hid_t a = H5Aopen(file, "dt_s", H5P_DEFAULT);
  H5Aread(a, H5T_NATIVE_DOUBLE, &dt);
  H5Aclose(a);
  EXPECT_EQ(dt, 1.0 / 1024.0);
  for (const auto& [column, unit] : std::map<std::string, std::string>{{"time_s", "s"},
                                                                       {"ground_accel_g", "g"},
                                                                       {"floor2_disp_in", "in"},
                                                                       {"floor3_abs_accel_g", "g"},
                                                                       {"story1_drift_in", "in"},
                                                                       {"damper1_force_kip", "kip"}}) {
    const hid_t ds = H5Dopen2(file, ("/time_history/" + column).c_str(), H5P_DEFAULT);
    ASSERT_GE(ds, 0) << column;
    EXPECT_EQ(read_string_attribute(ds, "units"), unit) << column;
    H5Dclose(ds);
  }
  H5Fclose(file);
  // The summaries agree (same run), apart from the file they name and wall times.
  auto a_json = nlohmann::json::parse(test_support::read_text(runs().csv_dir + "/summary.json"));
  auto b_json = nlohmann::json::parse(test_support::read_text(runs().h5_dir + "/summary.json"));
  EXPECT_EQ(b_json.at("time_history_file"), "time_history.h5");
  for (const char* key : {"peak_drift_in", "peak_floor_accel_g", "peak_damper_force_kip", "energy_kip_in", "steps"})
    EXPECT_EQ(a_json.at(key), b_json.at(key)) << key;
}

TEST(Hdf5Output, H5dumpReadsTheSameNumbers) {
  const std::string h5dump = "/usr/bin/h5dump";
  if (!fs::exists(h5dump)) GTEST_SKIP() << "h5dump (Debian hdf5-tools) not installed";
  std::vector<std::string> order;
  const auto csv = read_csv(runs().csv_dir + "/time_history.csv", &order);
  for (const std::string column : {"time_s", "story1_drift_in", "damper1_force_kip"}) {
    const auto p = test_support::run_process({h5dump, "-d", "/time_history/" + column, "-m", "%.17g", "-w", "0", "-y",
                                              runs().h5_dir + "/time_history.h5"});
    ASSERT_EQ(p.exit_code, 0) << p.err;
    const std::size_t open = p.out.find("DATA {"), close = p.out.find('}', open);
    ASSERT_NE(open, std::string::npos) << p.out.substr(0, 400);
    std::string data = p.out.substr(open + 6, close - open - 6);
    for (char& c : data)
      if (c == ',') c = ' ';
    std::istringstream in(data);
    std::vector<double> values;
    for (std::string v; in >> v;) values.push_back(std::strtod(v.c_str(), nullptr));
    const std::vector<double>& ref = csv.at(column);
    ASSERT_EQ(values.size(), ref.size()) << column;
    for (std::size_t i = 0; i < ref.size(); ++i) ASSERT_EQ(values[i], ref[i]) << column << " row " << i;
  }
  const auto attrs = test_support::run_process({h5dump, "-a", "/time_history/damper1_force_kip/units",
                                                runs().h5_dir + "/time_history.h5"});
  EXPECT_NE(attrs.out.find("\"kip\""), std::string::npos) << attrs.out;
}

TEST(Hdf5Output, UnknownFormatIsAConfigError) {
  const std::string dir = test_support::fresh_temp_dir("hdf5-bad-format");
  std::string text = test_support::read_text(write_config(dir + "/x", "csv"));
  text = std::regex_replace(text, std::regex("format: csv"), "format: netcdf");
  test_support::write_text(dir + "/bad.yaml", text);
  const auto p = test_support::run_process({test_paths::bin_dir() + "/hybridsim", "run", "--config", dir + "/bad.yaml"});
  EXPECT_EQ(p.exit_code, 2);
  EXPECT_NE(p.err.find("output.format"), std::string::npos) << p.err;
  EXPECT_NE(p.err.find("netcdf"), std::string::npos) << p.err;
}

}  // namespace
