// Fault injection on LCM runs (hybridsim + brfd-substructure in hybridsim's private network
// namespace; ctest label `realtime`): a substructure that cannot start or dies, SIGINT/SIGTERM/
// SIGKILL of hybridsim or of the substructure at seeded random steps. Each case asserts exit
// code, summary status and reason, rows on disk against the steps reached, and that no
// process of the run is left behind.
#include "fault_support.h"

#include <gtest/gtest.h>

#include <random>

namespace {

using namespace fault;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

TEST(FaultRealtime, SubstructureThatExitsAtOnceIsNoticedAtOnce) {
  const std::string dir = test_support::fresh_temp_dir("spawn");
  const std::string out = dir + "/out";
  // /bin/false starts and exits 1: before, the run waited the whole 10 s start timeout.
  server::RunConfig c = run_config(out, 2.0, "lcm");
  c.damper.executable = "/bin/false";
  const std::string cfg = write_config(dir, "c.yaml", config_text(c));
  const auto t0 = Clock::now();
  const auto r = test_support::run_process({hybridsim(), "run", "--config", cfg, "--quiet"});
  const double s = seconds_since(t0);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("/bin/false exited with code 1"), std::string::npos) << r.err;
  EXPECT_LT(s, 3.0) << "start_timeout_s is 10 s";
  EXPECT_EQ(read_json(out + "/summary.json").value("status", ""), "failed");
  // A file that cannot be executed (exec fails): reported at once with the system's reason.
  test_support::write_text(dir + "/not-a-program", "just text\n");
  fs::permissions(dir + "/not-a-program", fs::perms::owner_all);
  c.damper.executable = dir + "/not-a-program";
  const std::string cfg2 = write_config(dir, "c2.yaml", config_text(c));
  const auto t1 = Clock::now();
  const auto r2 = test_support::run_process({hybridsim(), "run", "--config", cfg2, "--quiet"});
  EXPECT_EQ(r2.exit_code, 1) << r2.err;
  EXPECT_NE(r2.err.find("cannot start"), std::string::npos) << r2.err;
  EXPECT_NE(r2.err.find("not-a-program"), std::string::npos) << r2.err;
  EXPECT_LT(seconds_since(t1), 3.0);
  std::printf("[ fault    ] spawn failure noticed after %.2f s (exits at once) and %.2f s (exec fails); start timeout 10 s\n",
              s, seconds_since(t1));
  fs::remove_all(dir);
}

TEST(FaultRealtime, SignalsAtRandomStepsStopCleanlyWithoutOrphans) {
  std::mt19937 rng(1024);
  for (int sig : {SIGINT, SIGTERM}) {
    const std::string dir = test_support::fresh_temp_dir("rtsig");
    const std::string out = dir + "/out";
    const std::string cfg = write_config(dir, "c.yaml", config_text(out, 30.0, "lcm"));
    // somewhere between step ~1000 and ~20000 (the history has ~250 bytes per row)
    const std::uintmax_t at = 250'000 + std::uniform_int_distribution<std::uintmax_t>(0, 4'500'000)(rng);
    const SignalledRun run = run_until_signal(cfg, dir, out, at, sig);
    const int code = run.exit_code;
    ASSERT_TRUE(run.reached) << run.err;
    EXPECT_EQ(code, 128 + sig) << run.err;
    const nlohmann::json& s = run.summary;
    EXPECT_EQ(s.value("status", ""), "interrupted") << s.dump();
    const long steps = s.value("steps", -1L);
    EXPECT_EQ(count_lines(out + "/time_history.csv"), 2 + steps);
    EXPECT_GT(fs::file_size(out + "/run.lcmlog"), 0u);
    EXPECT_TRUE(no_orphans(out)) << "a process of the run is still alive";
    std::printf("[ fault    ] LCM run, %s at step %ld: exit %d, %ld rows, no orphans\n",
                sig == SIGINT ? "SIGINT" : "SIGTERM", steps, code, count_lines(out + "/time_history.csv") - 1);
    fs::remove_all(dir);
  }
}

TEST(FaultRealtime, SigkillOfTheServerLeavesNoOrphans) {
  const std::string dir = test_support::fresh_temp_dir("rtkill");
  const std::string out = dir + "/out";
  const std::string cfg = write_config(dir, "c.yaml", config_text(out, 30.0, "lcm"));
  Child c = start({hybridsim(), "run", "--config", cfg, "--quiet"}, dir);
  ASSERT_TRUE(wait_for_size(out + "/time_history.csv", 1'000'000, 60.0));
  ASSERT_FALSE(processes_mentioning(out).empty()) << "the substructure runs";
  kill(c.pid, SIGKILL);
  EXPECT_EQ(c.wait(), 128 + SIGKILL);
  EXPECT_TRUE(no_orphans(out)) << "brfd-substructure outlived a killed server";
  fs::remove_all(dir);
}

TEST(FaultRealtime, SigkillOfTheSubstructureIsNoticedAndRowsAreKept) {
  const std::string dir = test_support::fresh_temp_dir("rtsubkill");
  const std::string out = dir + "/out";
  const std::string cfg = write_config(dir, "c.yaml", config_text(out, 30.0, "lcm"));
  Child c = start({hybridsim(), "run", "--config", cfg, "--quiet"}, dir);
  ASSERT_TRUE(wait_for_size(out + "/time_history.csv", 1'000'000, 60.0));
  const std::vector<int> subs = processes_mentioning(out + "/damper-model.yaml");
  ASSERT_EQ(subs.size(), 1u);
  kill(subs[0], SIGKILL);
  const auto t0 = Clock::now();
  const int code = c.wait();
  const double s = seconds_since(t0);
  EXPECT_EQ(code, 1) << c.err();
  const nlohmann::json j = read_json(out + "/summary.json");
  EXPECT_EQ(j.value("status", ""), "failed");
  EXPECT_NE(j.value("error", "").find("exited with code 137"), std::string::npos) << j.dump();
  EXPECT_EQ(count_lines(out + "/time_history.csv"), 2 + j.value("steps", -1L));
  EXPECT_LT(s, 1.0) << "noticed only at the step timeout";
  std::printf("[ fault    ] substructure SIGKILLed at step %ld: run failed after %.3f s, rows kept\n",
              j.value("steps", -1L), s);
  fs::remove_all(dir);
}

}  // namespace
