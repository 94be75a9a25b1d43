// A hostile process on the bus of a real run (issue 14; README "Reliability"; ctest label
// realtime). The test process enters a private network namespace (test_netns_main); hybridsim,
// brfd-substructure, brfd-rig and reliability_injector (injector_main.cc) all run in it.
// The injector listens to the run and, every 64 of the server's drift commands, injects one
// message of each class on every channel: garbage, another run's messages, forged ones (999
// kip replies, FAULT heartbeats, ABORT, 9 in commands, 999 kip sensor frames; wrong key),
// replays of authentic messages, and early replies for step k+1 signed with the run key.
// Asserted, by kind ("FORCE_FEEDBACK/bad_mac" ...):
//  - 100 % detected: each process's bad_messages in summary.json equals what was injected on
//    the channels it reads, kind by kind, and nothing else is counted;
//  - none applied: the virtual run's time history equals a clean run's byte for byte; the
//    physical run's forces (time history and physical.csv) never show an injected value;
//  - the run completes (exit 0, status ok, every step);
//  - under transport.on_bad_message: stop one forged reply ends the run, naming it.
// Counts and logic only: the injector is paced by the run's own commands, never by a timer.
#include "fault_support.h"
#include "messages/run_key.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace {

using namespace fault;

std::string injector() { return bin_dir() + "/reliability_injector"; }

/// Column `name` of a CSV file with a header.
std::vector<double> csv_column(const std::string& path, const std::string& name) {
  std::ifstream f(path);
  std::string line;
  std::getline(f, line);
  std::vector<std::string> header;
  {
    std::stringstream s(line);
    for (std::string h; std::getline(s, h, ',');) header.push_back(h);
  }
  const auto it = std::find(header.begin(), header.end(), name);
  if (it == header.end()) return {};
  const std::size_t col = static_cast<std::size_t>(it - header.begin());
  std::vector<double> v;
  while (std::getline(f, line)) {
    std::stringstream s(line);
    std::string cell;
    for (std::size_t i = 0; i <= col && std::getline(s, cell, ','); ++i) {
    }
    v.push_back(std::stod(cell));
  }
  return v;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

/// Kinds of `injected` whose channel is one of `channels`.
std::map<std::string, long> on_channels(const nlohmann::json& injected, const std::vector<std::string>& channels) {
  std::map<std::string, long> out;
  for (const auto& [kind, n] : injected.items())
    for (const std::string& c : channels)
      if (kind.rfind(c + "/", 0) == 0) out[kind] = n.get<long>();
  return out;
}

std::map<std::string, long> counted(const nlohmann::json& summary, const std::string& who) {
  std::map<std::string, long> out;
  if (!summary.contains("bad_messages") || !summary["bad_messages"].contains(who)) return out;
  for (const auto& [kind, n] : summary["bad_messages"][who].items()) out[kind] = n.get<long>();
  return out;
}

std::string show(const std::map<std::string, long>& m) {
  std::string s;
  for (const auto& [k, n] : m) s += k + "=" + std::to_string(n) + " ";
  return s;
}

struct Injected {
  nlohmann::json report;
  int exit_code = -1;
};

/// Runs hybridsim with `args` while the injector (with `injector_args`) is on the bus.
Injected run_with_injector(const std::string& dir, const std::string& out, const std::vector<std::string>& args,
                           std::vector<std::string> injector_args, test_support::ProcessResult& run) {
  fs::create_directories(dir + "/injector");
  std::vector<std::string> argv{injector(), "--url", "udpm://239.255.76.67:7667?ttl=0", "--key-file", out + "/run.key",
                                "--out", dir + "/injected.json", "--ready-file", dir + "/injector.ready"};
  argv.insert(argv.end(), injector_args.begin(), injector_args.end());
  Child inj = start(argv, dir + "/injector");
  // The run starts only once the injector is subscribed, so that it sees START (a fixed 200 ms
  // sleep could lose it on a loaded machine); 30 s at most.
  for (int i = 0; i < 3000 && !fs::exists(dir + "/injector.ready"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_TRUE(fs::exists(dir + "/injector.ready")) << "the injector did not subscribe in 30 s: " << inj.err();
  std::vector<std::string> cmd{hybridsim(), "run"};
  cmd.insert(cmd.end(), args.begin(), args.end());
  run = test_support::run_process(cmd);
  Injected r;
  r.exit_code = inj.wait();  // it ends 3 s after the run's last command at the latest
  EXPECT_EQ(r.exit_code, 0) << inj.err();
  r.report = read_json(dir + "/injected.json");
  return r;
}

TEST(Injector, VirtualRunDetectsEveryInjectedMessageAppliesNoneAndCompletes) {
  const std::string dir = test_support::fresh_temp_dir("inject-virtual");
  const std::string clean_out = dir + "/clean", out = dir + "/injected";
  const std::string clean_cfg = write_config(dir, "clean.yaml", config_text(clean_out, 2.5, "lcm"));
  const std::string cfg = write_config(dir, "run.yaml", config_text(out, 2.5, "lcm"));
  const auto clean = test_support::run_process({hybridsim(), "run", "--config", clean_cfg, "--quiet"});
  ASSERT_EQ(clean.exit_code, 0) << clean.err;

  test_support::ProcessResult run;
  const Injected inj = run_with_injector(dir, out, {"--config", cfg, "--quiet"}, {}, run);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json s = read_json(out + "/summary.json");
  EXPECT_EQ(s.value("status", ""), "ok") << s.dump(2);
  EXPECT_EQ(s.value("steps", 0L), 2560);
  EXPECT_EQ(inj.report.value("rounds", 0L), 24) << inj.report.dump();

  const nlohmann::json& injected = inj.report.at("injected");
  const auto server_side = on_channels(injected, {"FORCE_FEEDBACK", "HEARTBEAT"});
  const auto node_side = on_channels(injected, {"RUN_CONTROL", "DRIFT_COMMAND"});
  EXPECT_EQ(server_side.size(), 9u) << show(server_side);  // 5 classes on replies, 4 on heartbeats
  EXPECT_EQ(node_side.size(), 8u) << show(node_side);
  EXPECT_EQ(counted(s, "hybridsim"), server_side) << "counted " << show(counted(s, "hybridsim")) << "\ninjected "
                                                 << show(server_side) << "\n" << run.err;
  EXPECT_EQ(counted(s, "brfd-substructure"), node_side)
      << "counted " << show(counted(s, "brfd-substructure")) << "\ninjected " << show(node_side) << "\n"
      << test_support::read_text(out + "/substructure.log");
  long total = 0;
  for (const auto& [kind, n] : injected.items()) total += n.get<long>();
  EXPECT_EQ(s.value("bad_messages_total", -1L), total);
  // None applied: the same history as the run nobody disturbed, to the last digit.
  EXPECT_TRUE(test_support::read_text(out + "/time_history.csv") == test_support::read_text(clean_out + "/time_history.csv"))
      << "the injected run's time history differs from the clean run's";
  // Each kind said once on stderr (not once per message).
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n') <= 9 + 2, true) << run.err;
  std::printf("[ injector ] virtual run: %ld messages injected (%zu kinds), %ld counted, time history equal to the clean run\n",
              total, injected.size(), s.value("bad_messages_total", -1L));
  EXPECT_TRUE(no_orphans(out));
  fs::remove_all(dir);
}

TEST(Injector, PhysicalRunDetectsForgedSensorFramesAndEveryOtherInjectionAndCompletes) {
  const std::string dir = test_support::fresh_temp_dir("inject-physical");
  const std::string out = dir + "/injected";
  test_support::ProcessResult run;
  const Injected inj = run_with_injector(
      dir, out,
      {"--config", test_paths::source_dir() + "/configs/three-story-physical.yaml", "--out", out, "--duration", "2.5",
       "--quiet"},
      {"--physical"}, run);
  ASSERT_EQ(run.exit_code, 0) << run.err << test_support::read_text(out + "/substructure.log");
  const nlohmann::json s = read_json(out + "/summary.json");
  EXPECT_EQ(s.value("status", ""), "ok") << s.dump(2);
  EXPECT_EQ(inj.report.value("rounds", 0L), 24) << inj.report.dump();
  const nlohmann::json& injected = inj.report.at("injected");
  const auto server_side = on_channels(injected, {"FORCE_FEEDBACK", "HEARTBEAT"});
  const auto node_side = on_channels(injected, {"RUN_CONTROL", "DRIFT_COMMAND", "SENSOR_FRAME"});
  EXPECT_EQ(node_side.size(), 12u) << show(node_side);
  EXPECT_EQ(counted(s, "hybridsim"), server_side) << "counted " << show(counted(s, "hybridsim")) << "\ninjected "
                                                 << show(server_side);
  EXPECT_EQ(counted(s, "brfd-substructure"), node_side)
      << "counted " << show(counted(s, "brfd-substructure")) << "\ninjected " << show(node_side) << "\n"
      << test_support::read_text(out + "/substructure.log");
  // None applied: no 999 kip reply or frame, no 9 in command reached the building or the rig.
  const auto force = csv_column(out + "/time_history.csv", "damper1_force_kip");
  const auto measured = csv_column(out + "/physical.csv", "force_kip");
  const auto commanded = csv_column(out + "/physical.csv", "command_in");
  ASSERT_EQ(static_cast<long>(force.size()), s.value("steps", 0L) + 1);
  ASSERT_FALSE(measured.empty());
  EXPECT_LT(max_abs(force), 10.0);
  EXPECT_LT(max_abs(measured), 10.0);
  EXPECT_LT(max_abs(commanded), 1.0);
  EXPECT_EQ(read_json(out + "/safety.json").value("status", ""), "ok");
  long total = 0;
  for (const auto& [kind, n] : injected.items()) total += n.get<long>();
  std::printf("[ injector ] physical run: %ld messages injected (%zu kinds) incl. %ld forged/foreign/replayed/garbage sensor "
              "frames, %ld counted; peak force %.3f kip (injected 999)\n",
              total, injected.size(), static_cast<long>(on_channels(injected, {"SENSOR_FRAME"}).size() * 24),
              s.value("bad_messages_total", -1L), max_abs(force));
  EXPECT_TRUE(no_orphans(out));
  fs::remove_all(dir);
}

TEST(Injector, PolicyStopEndsTheRunAtTheFirstForgedReplyNamingIt) {
  const std::string dir = test_support::fresh_temp_dir("inject-stop");
  const std::string out = dir + "/injected";
  server::RunConfig c = run_config(out, 2.5, "lcm");
  c.transport.on_bad_message = "stop";
  const std::string cfg = write_config(dir, "run.yaml", config_text(c));
  test_support::ProcessResult run;
  const Injected inj =
      run_with_injector(dir, out, {"--config", cfg, "--quiet"}, {"--only", "FORCE_FEEDBACK/bad_mac", "--rounds", "1"}, run);
  EXPECT_EQ(inj.report.at("injected").value("FORCE_FEEDBACK/bad_mac", 0L), 1);
  EXPECT_EQ(run.exit_code, 1) << run.err;
  const nlohmann::json s = read_json(out + "/summary.json");
  EXPECT_EQ(s.value("status", ""), "failed");
  EXPECT_NE(s.value("error", "").find("FORCE_FEEDBACK/bad_mac"), std::string::npos) << s.value("error", "");
  EXPECT_LT(s.value("steps", 0L), 2560);
  EXPECT_TRUE(no_orphans(out));
  fs::remove_all(dir);
}

TEST(Injector, SubstructureWithAnotherKeyIsRefusedAndTheStartErrorSaysSo) {
  // An external substructure (damper.launch external) holding another key than the run's:
  // its heartbeats never count, START never reaches it, and the start error names the key.
  const std::string dir = test_support::fresh_temp_dir("inject-key");
  const std::string out = dir + "/out";
  messages::write_key_file(dir + "/run.key", messages::generate_run_key());
  messages::write_key_file(dir + "/other.key", messages::generate_run_key());
  server::RunConfig c = run_config(out, 1.0, "lcm");
  c.transport.start_timeout_s = 1.5;
  c.transport.key_file = dir + "/run.key";
  c.damper.launch = "external";
  const std::string cfg = write_config(dir, "run.yaml", config_text(c));
  fs::create_directories(dir + "/sub");
  Child sub = start({bin_dir() + "/brfd-substructure", "--model-config", test_paths::source_dir() + "/configs/brfd-default.yaml",
                     "--url", "udpm://239.255.76.67:7667?ttl=0", "--key-file", dir + "/other.key", "--watchdog-s", "5"},
                    dir + "/sub");
  const auto r = test_support::run_process({hybridsim(), "run", "--config", cfg, "--quiet"});
  kill(sub.pid, SIGTERM);
  sub.wait();
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("does it hold the run's key"), std::string::npos) << r.err;
  EXPECT_NE(sub.err().find("RUN_CONTROL/bad_mac"), std::string::npos) << sub.err();
  fs::remove_all(dir);
}

}  // namespace
