// `hybridsim ida` as a user runs it: real batch workers (in-process transport), two shipped
// records, two cases, a small hunt-and-fill budget and 4 s of shaking per run. Checks the
// files it promises, the fragility fit it prints, and that a run killed midway (SIGKILL of
// the driver) and started again completes without redoing a finished run, with the results
// of an uninterrupted IDA.
#include "run_configs.h"
#include "run_process.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

namespace {

namespace fs = std::filesystem;

std::string hybridsim() { return test_paths::bin_dir() + "/hybridsim"; }

/// A run config (three-story.yaml, 4 s) and an IDA config with two cases over it, in `dir`.
std::string write_configs(const std::string& dir) {
  const std::string src = test_paths::source_dir();
  server::RunConfig run = test_support::short_three_story(4.0, dir + "/unused");
  test_support::write_run_config(dir + "/three-story-short.yaml", run);
  // The second case: the same building with the semi-active model's damper (paper Tables 1-2).
  test_support::use_damper_config(run, "brfd-semiactive.yaml");
  test_support::write_run_config(dir + "/three-story-semi.yaml", run);
  const std::string ida =
      "ida:\n  name: test IDA\n  intensity_measure: sa_t1\n  damping_ratio: 0.05\n  story_height_in: 48\n"
      "  drift_limits_pct: [0.5, 1.5]\n  collapse_drift_pct: 4.0\n  transport: in_process\n  duration_s: 0\n"
      "  hunt: {first_im_g: 0.3, step_g: 0.6, step_increment_g: 0.3, max_im_g: 6.0, bracket_resolution_g: 0.2,"
      " max_runs: 6}\n"
      "cases:\n  - {label: passive, config: three-story-short.yaml}\n  - {label: semi, config: three-story-semi.yaml}\n";
  test_support::write_text(dir + "/ida.yaml", ida);
  const std::string list = src + "/records/ImperialValley1940_ElCentroArray9_180_NS_RSN6.AT2 1 ElCentro\n" + src +
                           "/records/Northridge1994_SylmarConverterSta_142_RSN1084.AT2 1 Sylmar\n";
  test_support::write_text(dir + "/records.txt", list);
  return dir + "/ida.yaml";
}

std::vector<std::string> ida_args(const std::string& dir, const std::string& out) {
  return {hybridsim(), "ida", "--config", dir + "/ida.yaml", "--records", dir + "/records.txt", "--out", out,
          "--jobs", "2"};
}

std::set<std::string> finished_runs(const std::string& out) {
  std::set<std::string> s;
  for (const auto& e : fs::directory_iterator(out + "/runs"))
    if (e.path().extension() != ".partial" && fs::exists(e.path() / "summary.json")) s.insert(e.path().filename().string());
  return s;
}

long mtime_ns(const std::string& path) {
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) return -1;
  return st.st_mtim.tv_sec * 1000000000L + st.st_mtim.tv_nsec;
}

/// An uninterrupted IDA (computed once per test process).
const std::string& reference_ida() {
  static const std::string out = [] {
    const std::string dir = test_support::fresh_temp_dir("ida-reference");
    write_configs(dir);
    const auto r = test_support::run_process(ida_args(dir, dir + "/out"));
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_TRUE(std::regex_search(r.out, std::regex(R"(cases=2 records=2 runs=24 failed=0 seconds=[0-9.]+\s*$)")))
        << r.out;
    EXPECT_TRUE(std::regex_search(r.out, std::regex(R"(passive: drift 0.5 %: median [0-9.]+ g \[[0-9.]+, [0-9.]+\], beta)")))
        << r.out;
    return dir + "/out";
  }();
  return out;
}

TEST(IdaCli, TracesEveryRecordAndWritesCurvesAndFragility) {
  const std::string out = reference_ida();
  EXPECT_EQ(finished_runs(out).size(), 24u);  // 2 cases x 2 records x 6 runs
  for (const char* f : {"ida.json", "effective-ida.yaml", "ida_runs.csv", "ida_fractiles.csv", "capacities.csv",
                        "fragility.csv", "ida-curves.png", "fragility.png"})
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  const std::string fr = test_support::read_text(out + "/fragility.csv");
  EXPECT_NE(fr.find("maximum likelihood"), std::string::npos);
  // Every run's IM is its scale times the record's Sa(T1) at scale 1, and drift grows with IM
  // along each record's hunt (the building is linear, the damper adds friction).
  std::istringstream rows(test_support::read_text(out + "/ida_runs.csv"));
  std::string line;
  std::getline(rows, line);
  std::map<std::string, std::vector<std::pair<double, double>>> curves;
  int n = 0;
  while (std::getline(rows, line)) {
    std::vector<std::string> f;
    std::stringstream s(line);
    for (std::string x; std::getline(s, x, ',');) f.push_back(x);
    ASSERT_GE(f.size(), 7u) << line;
    EXPECT_EQ(f[6], "ok") << line;
    curves[f[0] + "/" + f[1]].push_back({std::stod(f[2]), std::stod(f[4])});
    ++n;
  }
  EXPECT_EQ(n, 24);
  for (auto& [key, c] : curves) {
    std::sort(c.begin(), c.end());
    for (std::size_t i = 1; i < c.size(); ++i) EXPECT_GT(c[i].second, c[i - 1].second) << key;
  }
}

TEST(IdaCli, KilledMidwayResumesWithoutRedoingFinishedRuns) {
  prctl(PR_SET_CHILD_SUBREAPER, 1);
  const std::string dir = test_support::fresh_temp_dir("ida-resume");
  write_configs(dir);
  const std::string out = dir + "/out";
  const std::vector<std::string> argv = ida_args(dir, out);
  const pid_t driver = test_support::start_process(argv, dir + "/first.log");
  // Kill the driver (SIGKILL: no clean-up) once 8 of the 24 runs are final.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!(fs::exists(out + "/runs") && finished_runs(out).size() >= 8)) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << test_support::read_text(dir + "/first.log");
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_TRUE(test_support::kill_and_reap(driver));
  const std::set<std::string> before = finished_runs(out);
  ASSERT_GE(before.size(), 8u);
  ASSERT_LT(before.size(), 24u) << "the kill came too late to test a resume";
  std::map<std::string, long> stamp;
  for (const std::string& l : before) stamp[l] = mtime_ns(out + "/runs/" + l + "/summary.json");

  const auto r = test_support::run_process(argv);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  // Nothing finished was redone: same files, and the progress lines name only the others.
  for (const std::string& l : before) {
    EXPECT_EQ(mtime_ns(out + "/runs/" + l + "/summary.json"), stamp[l]) << l;
    EXPECT_EQ(r.out.find(" " + l + " ("), std::string::npos) << "redone: " << l << "\n" << r.out;
  }
  // The same runs and results as the uninterrupted IDA.
  EXPECT_EQ(finished_runs(out), finished_runs(reference_ida()));
  for (const char* f : {"ida_runs.csv", "fragility.csv", "capacities.csv", "ida_fractiles.csv"})
    EXPECT_EQ(test_support::read_text(out + "/" + f), test_support::read_text(reference_ida() + "/" + f)) << f;
}

TEST(IdaCli, BadInputIsExitCode2NamingTheProblem) {
  const std::string dir = test_support::fresh_temp_dir("ida-bad");
  write_configs(dir);
  std::string text = test_support::read_text(dir + "/ida.yaml");
  test_support::write_text(dir + "/bad.yaml", std::regex_replace(text, std::regex("story_height_in: 48"),
                                                                 "story_height_in: -1"));
  auto r = test_support::run_process({hybridsim(), "ida", "--config", dir + "/bad.yaml", "--records",
                                      dir + "/records.txt", "--out", dir + "/out"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("story_height_in"), std::string::npos) << r.err;
  test_support::write_text(dir + "/scaled.txt", test_paths::source_dir() +
                                                    "/records/Kocaeli1999_Duzce_270_RSN1158.AT2 1.5\n");
  r = test_support::run_process({hybridsim(), "ida", "--config", dir + "/ida.yaml", "--records", dir + "/scaled.txt",
                                 "--out", dir + "/out2"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("scale 1.5"), std::string::npos) << r.err;
}

}  // namespace
