#pragma once
// Helpers of the fault-injection suite: run configs made in code (independent of the shipped
// configs) and written by the one config serializer, processes started with signals, resource
// limits and timed kills, and a scan of /proc for processes left behind.
#include "damper/model/brfd_config.h"
#include "run_process.h"
#include "server/run/run_config.h"
#include "test_paths.h"

#include <nlohmann/json.hpp>

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace fault {

namespace fs = std::filesystem;

/// Where hybridsim and its siblings are: the build's bin folder, or RELIABILITY_BIN_DIR (to
/// run this suite against another build, e.g. main before a fix, and see it fail).
inline std::string bin_dir() {
  const char* e = std::getenv("RELIABILITY_BIN_DIR");
  return e && *e ? e : test_paths::bin_dir();
}
inline std::string hybridsim() { return bin_dir() + "/hybridsim"; }

inline std::string record_path() {
  return test_paths::source_dir() + "/records/ImperialValley1940_ElCentroArray9_180_NS_RSN6.AT2";
}

/// A three-story run config made in code (the building and damper of
/// configs/three-story.yaml, the LuGre model of configs/brfd-default.yaml, El Centro),
/// `duration_s` of shaking, results in `out_dir`; `transport` "in_process" or "lcm". Tests
/// change its fields and write it with config_text() (the one serializer).
inline server::RunConfig run_config(const std::string& out_dir, double duration_s, const std::string& transport) {
  server::RunConfig c;
  c.name = "fault";
  c.dt_s = 0.0009765625;
  c.record.path = record_path();
  c.record.scale = 1.0;
  c.record.duration_s = duration_s;
  c.building.story_mass_kip_s2_per_in = {0.02, 0.02, 0.02};
  c.building.story_stiffness_kip_per_in = {16.0, 16.0, 16.0};
  c.building.damping_modes = {1, 2};
  c.building.damping_ratios = {0.02, 0.02};
  c.building.dampers = {structure::DamperPlacement{1, 1.0}};
  c.damper.mode = "virtual";
  c.damper.model_config = test_paths::source_dir() + "/configs/brfd-default.yaml";
  c.damper_model = damper::load_brfd_params(c.damper.model_config);
  c.transport.kind = transport;
  if (transport == "lcm") {
    c.transport.url = "udpm://239.255.76.67:7667?ttl=0";
    c.transport.private_netns = true;
    c.transport.step_timeout_s = 1.0;
    c.transport.start_timeout_s = 10.0;
  }
  c.output.dir = out_dir;
  c.output.flush_every_steps = 256;
  return c;
}

/// `c` as YAML (server::run_config_to_yaml).
inline std::string config_text(const server::RunConfig& c) { return server::run_config_to_yaml(c); }

/// run_config(out_dir, duration_s, transport) as YAML.
inline std::string config_text(const std::string& out_dir, double duration_s, const std::string& transport) {
  return config_text(run_config(out_dir, duration_s, transport));
}

inline std::string write_config(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string p = dir + "/" + name;
  test_support::write_text(p, text);
  return p;
}

/// A started process with stdout/stderr to files.
struct Child {
  pid_t pid = -1;
  std::string out_path, err_path;
  int wait() {
    int status = 0;
    waitpid(pid, &status, 0);
    pid = -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
  std::string err() const { return test_support::read_text(err_path); }
  std::string out() const { return test_support::read_text(out_path); }
};

/// Starts argv; `fsize_limit_bytes` > 0 sets RLIMIT_FSIZE in the child (a full disk: writes
/// beyond it fail with EFBIG; SIGXFSZ is ignored so the process sees the error).
inline Child start(const std::vector<std::string>& argv, const std::string& log_dir, long fsize_limit_bytes = 0) {
  Child c;
  c.out_path = log_dir + "/stdout.txt";
  c.err_path = log_dir + "/stderr.txt";
  std::fflush(stdout);  // the child must not inherit (and print again) our buffered output
  c.pid = fork();
  if (c.pid == 0) {
    if (!freopen(c.out_path.c_str(), "w", stdout) || !freopen(c.err_path.c_str(), "w", stderr)) _exit(126);
    if (fsize_limit_bytes > 0) {
      signal(SIGXFSZ, SIG_IGN);
      struct rlimit rl {static_cast<rlim_t>(fsize_limit_bytes), static_cast<rlim_t>(fsize_limit_bytes)};
      setrlimit(RLIMIT_FSIZE, &rl);
    }
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  return c;
}

/// Lines of a file (0 if missing).
inline long count_lines(const std::string& path) {
  std::ifstream f(path);
  long n = 0;
  for (std::string l; std::getline(f, l);) ++n;
  return n;
}

/// Waits until `path` has at least `bytes` bytes (or `timeout_s`); true if it got there.
inline bool wait_for_size(const std::string& path, std::uintmax_t bytes, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < end) {
    std::error_code ec;
    if (fs::file_size(path, ec) >= bytes && !ec) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return false;
}

/// Pids of live processes whose command line mentions `needle` (e.g. a test's own folder).
inline std::vector<int> processes_mentioning(const std::string& needle) {
  std::vector<int> pids;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream f(e.path() / "cmdline", std::ios::binary);
    std::string cmd((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    if (cmd.find(needle) != std::string::npos) {
      // zombies of our own children are not orphans
      std::ifstream s(e.path() / "stat");
      std::string pid, comm, state;
      s >> pid >> comm >> state;
      if (state != "Z") pids.push_back(std::stoi(name));
    }
  }
  return pids;
}

/// No process mentioning `needle` within `timeout_s` (children exit on their own watchdogs).
inline bool no_orphans(const std::string& needle, double timeout_s = 3.0) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!processes_mentioning(needle).empty()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

inline nlohmann::json read_json(const std::string& path) {
  std::ifstream f(path);
  nlohmann::json j;
  f >> j;
  return j;
}

/// A run stopped by a signal.
struct SignalledRun {
  bool reached = false;   ///< the history reached the size before the signal (else: 60 s passed)
  int exit_code = -1;
  nlohmann::json summary;  ///< its summary.json (null if none)
  std::string err;        ///< its stderr
};

/// `hybridsim run --config cfg --quiet` (logs in `dir`), sent `sig` once `out`/time_history.csv
/// holds `at_bytes` (or after 60 s), waited for.
inline SignalledRun run_until_signal(const std::string& cfg, const std::string& dir, const std::string& out,
                                     std::uintmax_t at_bytes, int sig) {
  Child c = start({hybridsim(), "run", "--config", cfg, "--quiet"}, dir);
  SignalledRun r;
  r.reached = wait_for_size(out + "/time_history.csv", at_bytes, 60.0);
  kill(c.pid, sig);
  r.exit_code = c.wait();
  r.err = c.err();
  if (fs::exists(out + "/summary.json")) r.summary = read_json(out + "/summary.json");
  return r;
}

}  // namespace fault
