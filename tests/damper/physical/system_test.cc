// Physical mode end to end, with real processes over LCM inside a private network namespace
// (this process enters one first: test_netns_main; hybridsim, brfd-substructure and brfd-rig
// are its children). Runs are real time at 1024 Hz, so records are kept short.
//  - ATS cuts the measured delay and the RMS tracking error (20 ms emulated delay).
//  - Each safety limit trips when it should; the rig's log shows that no out-of-limit
//    command ever reached it; after a trip: hold, ramp to the safe state, end.
//  - Watchdogs: the server goes silent; the rig is killed mid-run (the server stops within 5
//    steps with a clear message, everything up to the failure on disk).
//  - Forged, replayed and stale commands are rejected by a running brfd-rig, which says so.
//  - The same config runs virtual and physical by changing one key.
#include "damper/physical/command_auth.h"
#include "messages/run_key.h"
#include "hybrid_lcm/actuator_command_t.hpp"
#include "hybrid_lcm/sensor_frame_t.hpp"
#include "messages/lcm_bus.h"
#include "run_process.h"
#include "server/run/hybrid_run.h"
#include "server/run/substructure_session.h"
#include "actuator_commands.h"
#include "test_paths.h"
#include "trip_cases.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <dirent.h>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <thread>

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using json = nlohmann::json;

// Copies of the actuator_command_t MODE_ constants (the generated ones are not ODR-usable).
constexpr int kModeHold = hybrid_lcm::actuator_command_t::MODE_HOLD;
constexpr int kModeSafeRamp = hybrid_lcm::actuator_command_t::MODE_SAFE_RAMP;
constexpr int kModeEnd = hybrid_lcm::actuator_command_t::MODE_END;

std::string src(const std::string& rel) { return test_paths::source_dir() + "/" + rel; }
std::string bin(const std::string& name) { return test_paths::bin_dir() + "/" + name; }

void write_yaml(const std::string& path, const YAML::Node& node) {
  YAML::Emitter out;
  out << node;
  test_support::write_text(path, std::string(out.c_str()) + "\n");
}

/// A channel prefix of its own for every test: all tests share this process's network
/// namespace, and a process of an earlier test may still be ramping down.
std::string prefix_for(const std::string& dir) {
  return "T" + std::to_string(std::hash<std::string>{}(dir) % 1000000) + "_";
}

/// rig-default.yaml with an absolute model path, edited, written to dir/rig.yaml.
std::string write_rig_config(const std::string& dir, const std::function<void(YAML::Node&)>& edit = {}) {
  YAML::Node r = YAML::LoadFile(src("configs/rig-default.yaml"));
  r["damper_model"] = src("configs/brfd-default.yaml");
  if (edit) edit(r);
  write_yaml(dir + "/rig.yaml", r);
  return dir + "/rig.yaml";
}

/// three-story-physical.yaml with absolute paths, a short record, the given rig config, edited,
/// written to dir/run.yaml.
std::string write_run_config(const std::string& dir, double duration_s, const std::string& rig_config,
                             const std::function<void(YAML::Node&)>& edit = {}) {
  YAML::Node c = YAML::LoadFile(src("configs/three-story-physical.yaml"));
  c["record"]["path"] = src("configs/" + c["record"]["path"].as<std::string>());
  c["record"]["duration_s"] = duration_s;
  c["damper"]["model_config"] = src("configs/brfd-default.yaml");
  c["rig"]["config"] = rig_config;
  c["output"]["dir"] = dir + "/out";
  c["transport"]["channel_prefix"] = prefix_for(dir);
  if (edit) edit(c);
  write_yaml(dir + "/run.yaml", c);
  return dir + "/run.yaml";
}

json read_json(const std::string& path) {
  std::ifstream f(path);
  if (!f) return json();
  json j;
  f >> j;
  return j;
}

std::vector<std::vector<double>> read_csv(const std::string& path) {
  std::ifstream f(path);
  std::string line;
  std::getline(f, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(f, line)) {
    std::vector<double> row;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

/// One row of rig-commands.csv.
struct RigLogRow {
  long long sequence = 0;
  int mode = -1;
  double drum = 0, a1 = 0, a2 = 0;
  std::string verdict, reason;
};

std::vector<RigLogRow> read_rig_log(const std::string& path) {
  std::ifstream f(path);
  std::string line;
  std::getline(f, line);
  std::vector<RigLogRow> rows;
  while (std::getline(f, line)) {
    std::vector<std::string> cells;
    std::size_t start = 0;
    for (int i = 0; i < 9; ++i) {
      const std::size_t comma = line.find(',', start);
      cells.push_back(line.substr(start, comma - start));
      start = comma + 1;
    }
    RigLogRow r;
    if (!cells[2].empty()) {
      r.sequence = std::stoll(cells[2]);
      r.mode = std::stoi(cells[3]);
      r.drum = std::stod(cells[4]);
      r.a1 = std::stod(cells[5]);
      r.a2 = std::stod(cells[6]);
    }
    r.verdict = cells[7];
    r.reason = line.substr(start);
    rows.push_back(r);
  }
  return rows;
}

test_support::ProcessResult hybridsim_run(const std::string& config, const std::string& out_dir = "") {
  if (out_dir.empty()) return test_support::run_process({bin("hybridsim"), "run", "--config", config});
  return test_support::run_process({bin("hybridsim"), "run", "--config", config, "--out", out_dir});
}

// ---------------------------------------------------------------------------------------------

TEST(PhysicalSystem, AtsCutsMeasuredDelayAndRmsTrackingErrorWith20msEmulatedDelay) {
  json tracking[2];
  for (int ats = 0; ats < 2; ++ats) {
    const std::string dir = test_support::fresh_temp_dir(ats ? "ats-on" : "ats-off");
    const std::string rig = write_rig_config(dir, [](YAML::Node& r) { r["hydraulic"]["delay_s"] = 0.020; });
    const std::string cfg = write_run_config(dir, 4.0, rig, [&](YAML::Node& c) {
      c["rig"]["ats"]["enabled"] = ats == 1;
      // Uncompensated, the 26 ms lag of the measured force feeds energy into the structure
      // (delay acts as negative damping) and the 0.3 in tracking limit trips after ~5 s.
      c["rig"]["limits"]["tracking_error_in"] = 1.0;
    });
    const auto r = hybridsim_run(cfg);
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err << test_support::read_text(dir + "/out/substructure.log");
    const json s = read_json(dir + "/out/summary.json");
    tracking[ats] = s["physical"]["tracking"];
    ASSERT_TRUE(tracking[ats].is_object()) << s.dump(2);
    EXPECT_NE(r.out.find("tracking: delay"), std::string::npos) << r.out;  // printed by hybridsim run
    EXPECT_TRUE(fs::exists(dir + "/out/tracking.json"));
  }
  const json& off = tracking[0];
  const json& on = tracking[1];
  std::printf("El Centro 4 s, rig delay 20 ms + lag 6 ms, over LCM in real time:\n"
              "  loop: %.4f / %.4f controller periods per step; delay counted in steps %.2f / %.2f ms\n"
              "  no compensation: delay %.2f ms, NRMS %.2f %%, RMS %.4f in, peak %.4f in\n"
              "  ATS:             delay %.2f ms, NRMS %.2f %%, RMS %.4f in, peak %.4f in (a1/a0 = %.2f ms)\n",
              off.value("controller_periods_per_step", 0.0), on.value("controller_periods_per_step", 0.0),
              off.value("step_delay_ms", 0.0), on.value("step_delay_ms", 0.0),
              off["delay_ms"].get<double>(), off["nrms_error_pct"].get<double>(), off["rms_error_in"].get<double>(),
              off["peak_error_in"].get<double>(), on["delay_ms"].get<double>(), on["nrms_error_pct"].get<double>(),
              on["rms_error_in"].get<double>(), on["peak_error_in"].get<double>(),
              on["ats"]["equivalent_delay_ms"].get<double>());
  // Uncompensated, the delay on the controller's clock is the rig's: the 20 ms delay line plus
  // the discrete 6 ms lag, D + tau - T/2 = 25.51 ms for slow motion (T = 1/1024 s; closed form
  // and estimator checked to 0.01 ms in tracking_test.cc). Bound: one period (0.98 ms) for the
  // ramp-in blend, the LVDT noise and commands held when the loop falls behind; measured
  // 25.32-25.47 ms, also with the loop at 1.4-1.7 controller periods per step (no SCHED_FIFO,
  // two busy processes), where the old per-step figure read 16.7-22.8 ms (issue 18).
  EXPECT_NEAR(off["delay_ms"].get<double>(), 1e3 * (0.020 + 0.006 - 0.5 / 1024.0), 1.0);
  // ATS: the residual delay converges to within two samples (ats_test.cc); over 4 s that
  // include its convergence from a1 = 0 we measure 0.2-0.5 ms. Bound: 30 % of uncompensated.
  EXPECT_LT(std::abs(on["delay_ms"].get<double>()), 0.3 * off["delay_ms"].get<double>());
  // Per-step errors, not wall-clock figures: measured 0.0046 vs 0.0557 in (12x); bound 2x.
  EXPECT_LT(on["rms_error_in"].get<double>(), 0.5 * off["rms_error_in"].get<double>());
  EXPECT_LT(on["nrms_error_pct"].get<double>(), 0.5 * off["nrms_error_pct"].get<double>());
}

// ---------------------------------------------------------------------------------------------

using trip_cases::TripCase;

class SafetyTrip : public ::testing::TestWithParam<TripCase> {};

TEST_P(SafetyTrip, TripsHoldsRampsToSafeAndNoOutOfLimitCommandReachesTheRig) {
  const TripCase tc = GetParam();
  const std::string key = tc.limit_key;
  const std::string dir = test_support::fresh_temp_dir(std::string("trip-") + tc.name);
  // The rig enforces the same stroke/rate/actuator limits, so its own count of out-of-limit
  // commands received is a second, independent proof.
  const double stroke = trip_cases::rig_stroke_in(tc);
  const double rate = trip_cases::rig_rate_in_per_s(tc);
  const std::string rig = write_rig_config(dir, [&](YAML::Node& r) {
    r["limits"]["stroke_in"] = stroke;
    r["limits"]["velocity_in_per_s"] = rate;
    r["limits"]["actuator_min_in"] = 0.30;
    r["limits"]["actuator_max_in"] = 1.20;
  });
  const std::string cfg = write_run_config(dir, 5.0, rig, [&](YAML::Node& c) {
    c["rig"]["limits"][key] = tc.value;
    c["rig"]["ats"]["enabled"] = tc.ats;
    if (key == "velocity_in_per_s") c["rig"]["ramp"]["ramp_velocity_in_per_s"] = tc.value / 3;  // ramps stay below
  });
  const auto t0 = Clock::now();
  const auto r = hybridsim_run(cfg);
  const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
  const std::string out = dir + "/out";
  const json summary = read_json(out + "/summary.json");
  const json safety = read_json(out + "/safety.json");
  ASSERT_TRUE(summary.is_object() && safety.is_object()) << r.out << r.err;
  const std::string reason = safety.value("reason", std::string());
  std::printf("[%s] trip after %ld steps (%.2f s wall): %s\n", tc.name, summary.value("steps", 0L), wall, reason.c_str());

  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_EQ(summary.value("status", std::string()), "failed");
  const std::string error = summary.value("error", std::string());
  EXPECT_NE(error.find("safety trip"), std::string::npos) << error;
  EXPECT_NE(error.find("limits." + key), std::string::npos) << error;
  EXPECT_EQ(safety.value("status", std::string()), "tripped");
  EXPECT_NE(reason.find("limits." + key), std::string::npos) << reason;
  EXPECT_NE(r.err.find("limits." + key), std::string::npos) << r.err;  // the user is told why
  // The run really started and stopped early; every step computed is on disk. Step counts, not
  // wall-clock figures: each limit is reached while El Centro's motion grows (measured
  // 700-3000 steps; on the simulated clock 666-1026 for the closed-form target), after the
  // 0.25 s (256-step) ramp-in and before the 5 s record ends.
  const long steps = summary.value("steps", 0L);
  EXPECT_GT(steps, 500);
  EXPECT_LT(steps, 5 * 1024);
  EXPECT_EQ(static_cast<long>(read_csv(out + "/time_history.csv").size()), steps + 1);
  const auto rows = read_csv(out + "/physical.csv");
  ASSERT_GE(static_cast<long>(rows.size()), steps);
  // "When it should": every step answered before the trip was within the limit.
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    const auto& w = rows[i];  // step, t, target, compensated, command, measured, force, a1, a2, F1, F2, ...
    if (key == "stroke_in") {
      ASSERT_LE(std::abs(w[4]), tc.value) << "row " << i;
    }
    if (key == "drift_in") {
      ASSERT_LE(std::abs(w[2]), tc.value) << "row " << i;
    }
    if (key == "actuator_force_lb") {
      ASSERT_LE(std::max(std::abs(w[9]), std::abs(w[10])), tc.value) << "row " << i;
    }
    if (key == "tracking_error_in") {
      ASSERT_LE(std::abs(w[5] - w[4]), tc.value) << "row " << i;  // ATS off: command = target (ramped in)
    }
    if (key == "velocity_in_per_s" && i > 0) {
      ASSERT_LE(std::abs(w[4] - rows[i - 1][4]) * 1024.0, tc.value * (1 + 1e-9));
    }
  }

  // The rig's log: every command it received, none beyond the limits; after the trip it was
  // held, ramped to the safe state and ended.
  const auto log = read_rig_log(out + "/rig-commands.csv");
  ASSERT_GT(log.size(), 100u);
  double max_drum = 0, max_rate = 0;
  for (std::size_t i = 0; i < log.size(); ++i) {
    EXPECT_EQ(log[i].verdict, "accepted") << "row " << i << ": " << log[i].reason;
    max_drum = std::max(max_drum, std::abs(log[i].drum));
    if (i > 0) max_rate = std::max(max_rate, std::abs(log[i].drum - log[i - 1].drum) * 1024.0);
    ASSERT_GE(log[i].a1, 0.30);
    ASSERT_LE(log[i].a2, 1.20);
  }
  std::printf("[%s] rig received %zu commands: max |drum| %.4f in (limit %.4f), max rate %.3f in/s (limit %.3f)\n",
              tc.name, log.size(), max_drum, stroke, max_rate, rate);
  EXPECT_LE(max_drum, stroke);
  EXPECT_LE(max_rate, rate * (1 + 1e-9));
  const json rig_summary = read_json(out + "/rig-summary.json");
  EXPECT_EQ(rig_summary.value("out_of_limit_received", -1L), 0);
  EXPECT_EQ(rig_summary.value("commands_rejected", -1L), 0);
  bool held = false, ramped = false;
  for (const auto& row : log) {
    held = held || row.mode == kModeHold;
    ramped = ramped || (held && row.mode == kModeSafeRamp);
  }
  EXPECT_TRUE(held && ramped);
  EXPECT_EQ(log.back().mode, kModeEnd);
  EXPECT_NEAR(log.back().drum, 0.0, 1e-12);  // the safe state
}

INSTANTIATE_TEST_SUITE_P(EachLimit, SafetyTrip, trip_cases::all(), trip_cases::name);

TEST(PhysicalSystem, ElectricActuatorRangeRefusesTheFirstCommandAndNothingIsPublished) {
  const std::string dir = test_support::fresh_temp_dir("trip-actuator-range");
  const std::string rig = write_rig_config(dir, [](YAML::Node& r) { r["start_timeout_s"] = 2.0; });
  const std::string cfg = write_run_config(dir, 3.0, rig, [](YAML::Node& c) {
    c["rig"]["limits"]["actuator_max_in"] = 0.80;  // below x'_2 = 0.8559 of the damper model
    c["transport"]["start_timeout_s"] = 3.0;
  });
  const auto r = hybridsim_run(cfg);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  const json safety = read_json(dir + "/out/safety.json");
  EXPECT_EQ(safety.value("status", std::string()), "start_failed");
  EXPECT_NE(safety.value("reason", std::string()).find("actuator 2"), std::string::npos) << safety.dump(2);
  EXPECT_EQ(safety.value("commands_sent", -1L), 0);
  EXPECT_TRUE(read_rig_log(dir + "/out/rig-commands.csv").empty());
  EXPECT_NE(r.out.find("safety: start_failed"), std::string::npos) << r.out;
}

// ---------------------------------------------------------------------------------------------

TEST(PhysicalSystem, ServerGoesSilentAndTheSubstructureTripsOnItsCommandWatchdog) {
  const std::string dir = test_support::fresh_temp_dir("server-silent");
  const std::string out = dir + "/out";
  fs::create_directories(out);
  const std::string cfg_path = write_run_config(dir, 3.0, write_rig_config(dir));
  server::RunConfig c = server::load_run_config(cfg_path);
  c.damper.executable = bin("brfd-substructure");
  c.rig.rig.executable = bin("brfd-rig");
  const std::string run_id = "silent-server";
  const damper::physical::RunKey run_key = damper::physical::generate_run_key();
  damper::physical::write_key_file(server::run_key_path(c, out), run_key);
  server::ChildProcess rig = server::spawn_rig(c, out, run_id, out + "/rig.log");
  server::ChildProcess sub = server::spawn_substructure(c, out, run_id, out + "/substructure.log");
  server::LcmLinkSettings link;
  link.url = c.transport.url;
  link.channels.prefix = c.transport.channel_prefix;
  link.step_timeout_s = 0.5;
  link.start_timeout_s = 10.0;
  link.key = run_key;
  server::LcmSubstructure lcm(link);
  lcm.start(run_id, 1, c.dt_s);
  server::SubstructureReply reply{Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1), Eigen::MatrixX2d::Zero(1, 2)};
  Eigen::VectorXd d(1), v(1);
  for (long k = 1; k <= 600; ++k) {
    const double t = k * c.dt_s;
    d[0] = 0.1 * std::sin(2 * M_PI * t);
    v[0] = 0.2 * M_PI * std::cos(2 * M_PI * t);
    lcm.exchange(k, t, d, v, reply);
  }
  const auto silent_from = Clock::now();
  const int code = sub.wait_or_kill(5.0);  // no more commands, no STOP
  const double after = std::chrono::duration<double>(Clock::now() - silent_from).count();
  const json safety = read_json(out + "/safety.json");
  std::printf("server silent: substructure exited %.3f s later with code %d: %s\n", after, code,
              safety.value("reason", std::string()).c_str());
  EXPECT_EQ(code, 4) << test_support::read_text(out + "/substructure.log");
  EXPECT_NE(safety.value("reason", std::string()).find("server command watchdog"), std::string::npos) << safety.dump(2);
  EXPECT_EQ(safety.value("last_answered_step", -1L), 600);
  // Wall clock. Expected: the watchdog (server_command_timeout_s, 0.25 s; exactly 0.25 s + one
  // period on the simulated clock, sim_system_test.cc) + hold_s 0.05 s + the safe ramp
  // (>= ramp_out_s 0.5 s) + writing results and exiting (~0.1 s): ~0.9 s. Bound: 0.25 + 1.5 s,
  // i.e. 0.85 s of margin for scheduling on a loaded 2-core machine.
  EXPECT_LT(after, c.rig.watchdogs.server_command_timeout_s + 1.5);
  EXPECT_EQ(rig.wait_or_kill(5.0), 0);
  const auto log = read_rig_log(out + "/rig-commands.csv");
  ASSERT_FALSE(log.empty());
  EXPECT_EQ(log.back().mode, kModeEnd);
  EXPECT_EQ(static_cast<long>(read_csv(out + "/physical.csv").size()), 600);
}

/// Pid of the child of `parent` whose command name is `comm`, or -1.
pid_t child_named(pid_t parent, const std::string& comm) {
  DIR* proc = opendir("/proc");
  pid_t found = -1;
  while (dirent* e = readdir(proc)) {
    const pid_t pid = static_cast<pid_t>(std::atol(e->d_name));
    if (pid <= 0) continue;
    std::ifstream f(std::string("/proc/") + e->d_name + "/stat");
    std::string stat((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    const auto open = stat.find('('), close = stat.rfind(')');
    if (open == std::string::npos || close == std::string::npos) continue;
    std::istringstream rest(stat.substr(close + 2));
    char state;
    long ppid;
    rest >> state >> ppid;
    if (ppid == parent && state != 'Z' && stat.substr(open + 1, close - open - 1) == comm) found = pid;
  }
  closedir(proc);
  return found;
}

TEST(PhysicalSystem, RigKilledMidRunStopsTheServerWithinFiveStepsWithEverythingOnDisk) {
  const std::string dir = test_support::fresh_temp_dir("kill-rig");
  const std::string out = dir + "/out";
  // Time-history rows flushed every 64 steps so that the test can see from the file how far the
  // run is (below).
  const std::string cfg = write_run_config(dir, 10.0, write_rig_config(dir),
                                           [](YAML::Node& c) { c["output"]["flush_every_steps"] = 64; });
  const std::string out_path = dir + "/hybridsim.out", err_path = dir + "/hybridsim.err";
  const pid_t pid = fork();
  if (pid == 0) {
    if (!freopen(out_path.c_str(), "w", stdout) || !freopen(err_path.c_str(), "w", stderr)) _exit(126);
    const std::string exe = bin("hybridsim");
    execl(exe.c_str(), exe.c_str(), "run", "--config", cfg.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  ASSERT_GT(pid, 0);
  // Mid-run, judged by the run's own progress, not by wall clock: a fixed 2.5 s sleep found the
  // run only 992 steps in on a loaded CI machine (start-up, positioning and handshake took longer
  // than measured here). The rig is killed once the time history on disk holds more than 1100
  // steps (of the 10 s record's 10240), or the test fails after 30 s.
  const std::string history = out + "/time_history.csv";
  const auto waiting_since = Clock::now();
  long lines_on_disk = 0;
  while (lines_on_disk < 1100 + 2) {  // + header + the t = 0 row
    if (std::chrono::duration<double>(Clock::now() - waiting_since).count() > 30.0) {
      kill(pid, SIGKILL);
      waitpid(pid, nullptr, 0);
      FAIL() << "the run did not reach step 1100 in 30 s: " << lines_on_disk << " lines in " << history;
    }
    ASSERT_EQ(waitpid(pid, nullptr, WNOHANG), 0) << "hybridsim ended before the rig was killed: "
                                                 << test_support::read_text(err_path);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    std::ifstream f(history);
    lines_on_disk = std::count(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>(), '\n');
  }
  const pid_t rig = child_named(pid, "brfd-rig");
  ASSERT_GT(rig, 0) << "brfd-rig not found among hybridsim's children";
  ASSERT_EQ(kill(rig, SIGKILL), 0);
  const auto killed = Clock::now();
  int status = 0;
  waitpid(pid, &status, 0);
  const double after = std::chrono::duration<double>(Clock::now() - killed).count();
  const std::string err = test_support::read_text(err_path);
  const json summary = read_json(out + "/summary.json");
  const json safety = read_json(out + "/safety.json");
  const long steps = summary.value("steps", 0L);
  const auto physical_rows = read_csv(out + "/physical.csv");
  ASSERT_FALSE(physical_rows.empty());
  const long last_step_with_a_frame = static_cast<long>(physical_rows.back()[0]);
  std::printf("rig killed after %ld steps: server stopped %ld steps after the last sensor frame, hybridsim exited "
              "%.3f s after the kill: %s\n",
              last_step_with_a_frame, steps - last_step_with_a_frame, after, summary.value("error", std::string()).c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1) << err;
  EXPECT_EQ(summary.value("status", std::string()), "failed");
  const std::string error = summary.value("error", std::string());
  EXPECT_NE(error.find("safety trip"), std::string::npos) << error;
  EXPECT_NE(error.find("sensor frame watchdog"), std::string::npos) << error;
  EXPECT_NE(err.find("sensor frame watchdog"), std::string::npos) << err;  // a clear message to the user
  EXPECT_GT(steps, 1100);           // really mid-run (see the wait above)
  EXPECT_LT(steps, 10 * 1024);
  // Steps, not wall clock: every step waits for a frame, so none is answered without one
  // (measured 0; simulated 0); 5 is the requirement.
  EXPECT_LE(steps - last_step_with_a_frame, 5);
  // Wall clock. Expected: frame watchdog 0.05 s + hold 0.05 s + safe ramp >= 0.5 s + results
  // written, processes reaped: measured 0.65-0.9 s. Bound 3 s: 2 s of margin for a loaded
  // machine.
  EXPECT_LT(after, 3.0);
  // Everything up to the failure is on disk: one time-history row per step (+ t = 0), one
  // physical row per answered step.
  EXPECT_EQ(static_cast<long>(read_csv(out + "/time_history.csv").size()), steps + 1);
  EXPECT_EQ(static_cast<long>(physical_rows.size()), steps);
  EXPECT_EQ(safety.value("status", std::string()), "tripped");
}

// ---------------------------------------------------------------------------------------------

class FrameWatcher {
 public:
  FrameWatcher(lcm::LCM& lcm, const std::string& prefix) {
    lcm.subscribe(prefix + "SENSOR_FRAME", &FrameWatcher::on_frame, this);
  }
  void on_frame(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    frame.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size));
    ++frames;
  }
  hybrid_lcm::sensor_frame_t frame;
  long frames = 0;
};

TEST(PhysicalSystem, RunningRigRejectsForgedReplayedAndStaleCommandsAndSaysSo) {
  const std::string dir = test_support::fresh_temp_dir("auth-rig");
  const damper::physical::RunKey key = damper::physical::generate_run_key();
  damper::physical::write_key_file(dir + "/run.key", key);
  const std::string url = "udpm://239.255.76.67:7667?ttl=0";
  const std::string prefix = prefix_for(dir);
  server::ChildProcess rig(bin("brfd-rig"),
                           {"--config", write_rig_config(dir), "--url", url, "--channel-prefix", prefix, "--run-id",
                            "auth-run", "--key-file", dir + "/run.key", "--log-dir", dir},
                           dir + "/rig.log");
  auto lcm = messages::open_lcm(url, false);
  FrameWatcher w(*lcm, prefix);
  // Each wait is for one frame of a 1024 Hz rig (~1 ms); 5 s is a deadline, not a measurement.
  // The good commands must reach the rig within auth.max_command_age_s (50 ms) of their utime:
  // loopback delivery takes ~0.1 ms (a 500x margin; the rig runs SCHED_FIFO when allowed).
  auto pump_until = [&](const std::function<bool()>& done) {
    const auto deadline = Clock::now() + std::chrono::seconds(5);
    while (!done() && Clock::now() < deadline) lcm->handleTimeout(10);
    return done();
  };
  ASSERT_TRUE(pump_until([&] { return w.frames > 5; })) << test_support::read_text(dir + "/rig.log");

  damper::physical::CommandSigner signer(key);
  auto make = [](int64_t seq, int64_t utime) { return actuator_commands::run_command("auth-run", seq, utime, 0.0); };
  auto send = [&](const hybrid_lcm::actuator_command_t& c) {
    std::vector<uint8_t> b(static_cast<std::size_t>(c.getEncodedSize()));
    c.encode(b.data(), 0, static_cast<int>(b.size()));
    lcm->publish(prefix + "ACTUATOR_COMMAND", b.data(), static_cast<unsigned>(b.size()));
  };

  auto good = make(1, messages::now_utime());
  signer.sign(good);
  send(good);
  ASSERT_TRUE(pump_until([&] { return w.frame.command_sequence == 1; }));
  EXPECT_EQ(w.frame.rejected_commands, 0);

  auto forged = make(2, messages::now_utime());
  damper::physical::CommandSigner(damper::physical::generate_run_key()).sign(forged);
  send(forged);
  ASSERT_TRUE(pump_until([&] { return w.frame.rejected_commands == 1; }));
  EXPECT_NE(w.frame.last_rejection.find("forged"), std::string::npos) << w.frame.last_rejection;

  send(good);  // a replay: the very same bytes again
  ASSERT_TRUE(pump_until([&] { return w.frame.rejected_commands == 2; }));
  EXPECT_NE(w.frame.last_rejection.find("replayed"), std::string::npos) << w.frame.last_rejection;

  auto stale = make(3, messages::now_utime() - 1000000);  // signed, but a second old
  signer.sign(stale);
  send(stale);
  ASSERT_TRUE(pump_until([&] { return w.frame.rejected_commands == 3; }));
  EXPECT_NE(w.frame.last_rejection.find("stale"), std::string::npos) << w.frame.last_rejection;

  auto out_of_limit = make(4, messages::now_utime());
  out_of_limit.drum_displacement_in = 2.9;  // authentic, within the stroke, but a 2.9 in step
  signer.sign(out_of_limit);
  send(out_of_limit);
  ASSERT_TRUE(pump_until([&] { return w.frame.rejected_commands == 4; }));
  EXPECT_NE(w.frame.last_rejection.find("out of limit"), std::string::npos) << w.frame.last_rejection;
  EXPECT_EQ(w.frame.command_sequence, 1);  // nothing but the good command was taken

  auto end = make(5, messages::now_utime());
  end.mode = kModeEnd;
  signer.sign(end);
  send(end);
  EXPECT_EQ(rig.wait_or_kill(3.0), 0);
  const auto log = read_rig_log(dir + "/rig-commands.csv");
  ASSERT_EQ(log.size(), 6u);
  const char* verdicts[] = {"accepted", "forged", "replayed", "stale", "out_of_limit", "accepted"};
  for (std::size_t i = 0; i < log.size(); ++i) EXPECT_EQ(log[i].verdict, verdicts[i]) << "row " << i << log[i].reason;
  EXPECT_NE(test_support::read_text(dir + "/rig.log").find("rejected command"), std::string::npos);
  const json s = read_json(dir + "/rig-summary.json");
  EXPECT_EQ(s["rejected_by_kind"].value("forged", 0), 1);
  EXPECT_EQ(s["rejected_by_kind"].value("replayed", 0), 1);
  EXPECT_EQ(s["rejected_by_kind"].value("stale", 0), 1);
}

// ---------------------------------------------------------------------------------------------

TEST(PhysicalSystem, SameConfigRunsVirtualAndPhysicalByChangingOneKey) {
  const std::string dir = test_support::fresh_temp_dir("swap");
  const std::string physical_cfg = write_run_config(dir, 4.0, src("configs/rig-default.yaml"));
  std::string text = test_support::read_text(physical_cfg);
  const std::string virtual_cfg = dir + "/virtual.yaml";
  const auto at = text.find("mode: physical");
  ASSERT_NE(at, std::string::npos);
  std::string vtext = text;
  vtext.replace(at, 14, "mode: virtual");
  test_support::write_text(virtual_cfg, vtext);
  int differing = 0;  // exactly one line: the key
  std::istringstream a(text), b(vtext);
  for (std::string la, lb; std::getline(a, la) && std::getline(b, lb);) differing += la != lb;
  EXPECT_EQ(differing, 1);

  const auto rv = hybridsim_run(virtual_cfg, dir + "/out-virtual");  // --out keeps both results
  ASSERT_EQ(rv.exit_code, 0) << rv.out << rv.err;
  const auto rp = hybridsim_run(physical_cfg);
  ASSERT_EQ(rp.exit_code, 0) << rp.out << rp.err << test_support::read_text(dir + "/out/substructure.log");
  const json sv = read_json(dir + "/out-virtual/summary.json");
  const json sp = read_json(dir + "/out/summary.json");
  EXPECT_FALSE(sv.contains("physical"));
  EXPECT_FALSE(fs::exists(dir + "/out-virtual/rig-commands.csv"));
  ASSERT_TRUE(sp.contains("physical"));
  const double dv = sv["peak_drift_in"][0], dp = sp["peak_drift_in"][0];
  const double fv = sv["peak_damper_force_kip"][0], fp = sp["peak_damper_force_kip"][0];
  std::printf("4 s of El Centro: virtual peak drift %.4f in, force %.3f kip; physical (emulated rig) %.4f in, %.3f kip\n",
              dv, fv, dp, fp);
  EXPECT_EQ(sv["steps"], sp["steps"]);
  EXPECT_NEAR(dp, dv, 0.25 * dv);  // the same structure and damper, seen through a rig
  EXPECT_NEAR(fp, fv, 0.25 * fv);
}

/// Semi-active control in physical mode: three-story-physical-controlled.yaml (rig with the
/// semi-active model), the given law, optionally an edited damper model (inline).
std::string write_controlled_config(const std::string& dir, double duration_s, const std::string& law,
                                    const std::function<void(YAML::Node&)>& edit_model = {}) {
  YAML::Node rig = YAML::LoadFile(src("configs/rig-semiactive.yaml"));
  rig["damper_model"] = src("configs/brfd-semiactive.yaml");
  write_yaml(dir + "/rig.yaml", rig);
  YAML::Node c = YAML::LoadFile(src("configs/three-story-physical-controlled.yaml"));
  c["record"]["path"] = src("configs/" + c["record"]["path"].as<std::string>());
  c["record"]["duration_s"] = duration_s;
  YAML::Node model = YAML::LoadFile(src("configs/brfd-semiactive.yaml"));
  if (edit_model) edit_model(model);
  c["damper"].remove("model_config");
  c["damper"]["model"] = model;
  c["rig"]["config"] = dir + "/rig.yaml";
  c["output"]["dir"] = dir + "/out";
  c["transport"]["channel_prefix"] = prefix_for(dir);
  c["control"]["law"] = law;
  write_yaml(dir + "/run.yaml", c);
  return dir + "/run.yaml";
}

TEST(PhysicalSystem, ControlledRunTheRigsElectricActuatorsFollowTheTargets) {
  const std::string dir = test_support::fresh_temp_dir("control-follow");
  const auto r = hybridsim_run(write_controlled_config(dir, 3.0, "passive_on"));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err << test_support::read_text(dir + "/out/substructure.log");
  const json s = read_json(dir + "/out/summary.json");
  ASSERT_TRUE(s.contains("control")) << s.dump(2);
  // time history: damper1_target1_in, _target2_in, _actuator1_in, _actuator2_in (measured by the rig)
  std::ifstream f(dir + "/out/time_history.csv");
  std::string header;
  std::getline(f, header);
  std::vector<std::string> cols;
  std::stringstream hs(header);
  for (std::string c; std::getline(hs, c, ',');) cols.push_back(c);
  auto col = [&](const std::string& n) { return static_cast<int>(std::find(cols.begin(), cols.end(), n) - cols.begin()); };
  const auto rows = read_csv(dir + "/out/time_history.csv");
  ASSERT_GT(rows.size(), 3000u);
  const auto& last = rows.back();
  const double t1 = last[col("damper1_target1_in")], t2 = last[col("damper1_target2_in")];
  const double x1 = last[col("damper1_actuator1_in")], x2 = last[col("damper1_actuator2_in")];
  std::printf("passive_on through the rig: targets %.4f %.4f in, rig actuators at %.4f %.4f in (x' 0.655 0.8559)\n", t1, t2,
              x1, x2);
  EXPECT_LT(t1, 0.655 - 0.02);  // passive_on retracts both actuators
  EXPECT_NEAR(x1, t1, 0.002);   // the rig's actuators got there (noise 0.0002 in std)
  EXPECT_NEAR(x2, t2, 0.002);
  // Every command the rig received was accepted and inside the limits.
  const auto log = read_rig_log(dir + "/out/rig-commands.csv");
  ASSERT_GT(log.size(), 1000u);
  for (const auto& row : log) {
    ASSERT_EQ(row.verdict, "accepted") << row.reason;
    ASSERT_GE(row.a1, 0.30);
  }
}

TEST(PhysicalSystem, ControlCommandBeyondTheActuatorStrokeIsCutByTheSafetyLayer) {
  const std::string dir = test_support::fresh_temp_dir("control-stroke");
  // The controller is told its actuators reach 0.0 in with no force limit: passive_on then
  // targets x1 = 0.0 in, far beyond the safety layer's actuator_min_in 0.30 in.
  const auto r = hybridsim_run(write_controlled_config(dir, 4.0, "passive_on", [](YAML::Node& m) {
    m["electric_actuators"]["min_in"] = 0.0;
    m["electric_actuators"]["force_limit_lb"] = 1e6;
  }));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  const json summary = read_json(dir + "/out/summary.json");
  const json safety = read_json(dir + "/out/safety.json");
  const std::string error = summary.value("error", std::string());
  EXPECT_NE(error.find("safety trip"), std::string::npos) << error;
  EXPECT_NE(error.find("electric actuator stroke limit"), std::string::npos) << error;
  EXPECT_EQ(safety.value("status", std::string()), "tripped");
  // Nothing beyond the stroke reached the rig; it was held, ramped to the safe state, ended.
  const auto log = read_rig_log(dir + "/out/rig-commands.csv");
  ASSERT_GT(log.size(), 100u);
  double lowest = 1e9;
  bool held = false;
  for (const auto& row : log) {
    EXPECT_EQ(row.verdict, "accepted") << row.reason;
    lowest = std::min({lowest, row.a1, row.a2});
    held = held || row.mode == kModeHold;
  }
  std::printf("stroke cut: lowest actuator command the rig received %.4f in (limit 0.30); %s\n", lowest,
              safety.value("reason", std::string()).c_str());
  EXPECT_GE(lowest, 0.30);
  EXPECT_TRUE(held);
  EXPECT_EQ(log.back().mode, kModeEnd);
  EXPECT_NEAR(log.back().a1, 0.655, 1e-9);  // the safe state: x'
  EXPECT_EQ(read_json(dir + "/out/rig-summary.json").value("out_of_limit_received", -1L), 0);
}

TEST(PhysicalSystem, RigReplaysAMeasuredTest) {
  if (!test_paths::have_shared()) GTEST_SKIP() << "../shared/data/brfd not present";
  const std::string dir = test_support::fresh_temp_dir("replay");
  const damper::physical::RunKey key = damper::physical::generate_run_key();
  damper::physical::write_key_file(dir + "/run.key", key);
  YAML::Node r = YAML::LoadFile(src("configs/rig-replay.yaml"));
  r["damper_model"] = src("configs/brfd-default.yaml");
  r["replay"]["file"] = test_paths::shared_dir() + "/data/brfd/semiactive/harmonic0.015forward.json";
  r["start_timeout_s"] = 1.0;
  write_yaml(dir + "/replay.yaml", r);
  const std::string url = "udpm://239.255.76.67:7667?ttl=0";
  const std::string prefix = prefix_for(dir);
  server::ChildProcess rig(bin("brfd-rig"),
                           {"--config", dir + "/replay.yaml", "--url", url, "--channel-prefix", prefix, "--key-file",
                            dir + "/run.key", "--log-dir", dir},
                           dir + "/rig.log");
  auto lcm = messages::open_lcm(url, false);
  std::vector<hybrid_lcm::sensor_frame_t> frames;
  struct Sink {
    std::vector<hybrid_lcm::sensor_frame_t>* out;
    void on(const lcm::ReceiveBuffer* b, const std::string&) {
      hybrid_lcm::sensor_frame_t f;
      f.decode(b->data, 0, static_cast<int>(b->data_size));
      out->push_back(f);
    }
  } sink{&frames};
  lcm->subscribe(prefix + "SENSOR_FRAME", &Sink::on, &sink);
  // 300 frames at 1024 Hz take 0.29 s; 5 s is a deadline (17x), not a measurement.
  const auto deadline = Clock::now() + std::chrono::seconds(5);
  while (frames.size() < 300 && Clock::now() < deadline) lcm->handleTimeout(10);
  ASSERT_GE(frames.size(), 300u) << test_support::read_text(dir + "/rig.log");
  std::ifstream f(test_paths::shared_dir() + "/data/brfd/semiactive/harmonic0.015forward.json");
  json data;
  f >> data;
  // Frames are the file's rows in order (frame sequence n = row n-1).
  for (std::size_t i = 0; i < 300; ++i) {
    const auto& row = data["data"][static_cast<std::size_t>(frames[i].sequence - 1)];
    ASSERT_DOUBLE_EQ(frames[i].drum_displacement_in, row[1].get<double>());
    ASSERT_DOUBLE_EQ(frames[i].friction_force_kip, row[2].get<double>());
    ASSERT_DOUBLE_EQ(frames[i].actuator2_force_lb, row[7].get<double>());
  }
  EXPECT_EQ(rig.wait_or_kill(5.0), 1);  // no command came: it gives up after start_timeout_s
}

}  // namespace
