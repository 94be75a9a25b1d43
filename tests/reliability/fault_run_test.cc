// Fault injection on whole runs (issue 14), in-process substructure so that the outcome does
// not depend on timing: SIGINT/SIGTERM/SIGKILL at seeded random steps, a full disk
// (RLIMIT_FSIZE), two runs into one folder, a reused folder, physics checks, record and
// resource limits, messages naming the input, the exit-code convention.
// Each case asserts the outcome: exit code, message naming the input, summary status, rows
// on disk against the steps reached.
#include "fault_support.h"
#include "server/run/time_history_sink.h"
#include "server/run/time_history_writer.h"

#include <gtest/gtest.h>

#include <random>
#include <regex>

namespace {

using namespace fault;

/// A run long enough to be interrupted anywhere: the whole record (53.7 s) at 16384 Hz,
/// one row every 16 steps.
std::string slow_config(const std::string& dir, const std::string& out) {
  server::RunConfig c = run_config(out, -1.0, "in_process");
  c.dt_s = 0.00006103515625;
  c.output.flush_every_steps = 4096;
  c.output.every_n_steps = 16;
  return write_config(dir, "slow.yaml", config_text(c));
}

TEST(FaultRun, SigintAndSigtermAtRandomStepsKeepEveryRow) {
  std::mt19937 rng(143130);
  int cases = 0;
  for (int sig : {SIGINT, SIGTERM, SIGINT, SIGTERM}) {
    const std::string dir = test_support::fresh_temp_dir("sig");
    const std::string out = dir + "/out";
    const std::string cfg = slow_config(dir, out);
    // Full history: 879,923 steps / 16 rows of 17 values, ~ 17 MB; stop somewhere in 5-60 %.
    const std::uintmax_t at = 1'000'000 + std::uniform_int_distribution<std::uintmax_t>(0, 9'000'000)(rng);
    const SignalledRun run = run_until_signal(cfg, dir, out, at, sig);
    const int code = run.exit_code;
    ASSERT_TRUE(run.reached) << run.err;
    EXPECT_EQ(code, 128 + sig) << run.err;
    const nlohmann::json& s = run.summary;
    EXPECT_EQ(s.value("status", ""), "interrupted");
    EXPECT_EQ(s.value("signal", ""), sig == SIGINT ? "SIGINT" : "SIGTERM");
    const long steps = s.value("steps", -1L);
    EXPECT_GT(steps, 0);
    EXPECT_LT(steps, 879923);
    // header + the t = 0 row + one row per 16 steps reached: every row computed is on disk
    EXPECT_EQ(count_lines(out + "/time_history.csv"), 2 + steps / 16) << "steps " << steps;
    EXPECT_NE(run.err.find(sig == SIGINT ? "SIGINT" : "SIGTERM"), std::string::npos) << run.err;
    std::printf("[ fault    ] %s at step %ld: exit %d, status interrupted, %ld rows on disk\n",
                sig == SIGINT ? "SIGINT" : "SIGTERM", steps, code, count_lines(out + "/time_history.csv") - 1);
    fs::remove_all(dir);
    ++cases;
  }
  EXPECT_EQ(cases, 4);
}

TEST(FaultRun, SigkillLeavesNoLockBehindAndTheFolderRunsAgain) {
  std::mt19937 rng(9);
  const std::string dir = test_support::fresh_temp_dir("kill");
  const std::string out = dir + "/out";
  const std::string cfg = slow_config(dir, out);
  Child c = start({hybridsim(), "run", "--config", cfg, "--quiet"}, dir);
  ASSERT_TRUE(wait_for_size(out + "/time_history.csv",
                            500'000 + std::uniform_int_distribution<std::uintmax_t>(0, 4'000'000)(rng), 60.0));
  kill(c.pid, SIGKILL);
  EXPECT_EQ(c.wait(), 128 + SIGKILL);
  EXPECT_FALSE(fs::exists(out + "/summary.json"));
  // The kernel dropped the lock with the process: a new run into the folder is not refused,
  // and it replaces the killed run's partial files.
  const std::string cfg2 = write_config(dir, "short.yaml", config_text(out, 1.0, "in_process"));
  const auto r = test_support::run_process({hybridsim(), "run", "--config", cfg2, "--quiet"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_json(out + "/summary.json").value("status", ""), "ok");
  EXPECT_EQ(count_lines(out + "/time_history.csv"), 2 + 1024);
  fs::remove_all(dir);
}

TEST(FaultRun, SecondRunIntoALockedFolderIsRefused) {
  const std::string dir = test_support::fresh_temp_dir("lock");
  const std::string out = dir + "/out";
  const std::string cfg = slow_config(dir, out);
  Child first = start({hybridsim(), "run", "--config", cfg, "--quiet"}, dir);
  ASSERT_TRUE(wait_for_size(out + "/time_history.csv", 100'000, 60.0));
  const std::string cfg2 = write_config(dir, "short.yaml", config_text(out, 1.0, "in_process"));
  const auto second = test_support::run_process({hybridsim(), "run", "--config", cfg2, "--quiet"});
  EXPECT_EQ(second.exit_code, 2) << second.err;
  EXPECT_NE(second.err.find("in use by another run"), std::string::npos) << second.err;
  EXPECT_NE(second.err.find(out), std::string::npos) << second.err;
  kill(first.pid, SIGTERM);  // the first run is untouched by the refused one: it stops cleanly
  EXPECT_EQ(first.wait(), 143);
  const nlohmann::json s = read_json(out + "/summary.json");
  EXPECT_EQ(s.value("run", ""), "fault");
  EXPECT_EQ(s.value("status", ""), "interrupted");
  EXPECT_EQ(count_lines(out + "/time_history.csv"), 2 + s.value("steps", 0L) / 16);
  fs::remove_all(dir);
}

TEST(FaultRun, ReusedFolderIsClearedOfTheEarlierRunsFiles) {
  const std::string dir = test_support::fresh_temp_dir("reuse");
  const std::string out = dir + "/out";
  for (const char* f : {"physical.csv", "safety.json", "run.key", "tracking.json", "rig.log", "run.lcmlog"})
    test_support::write_text(out + "/" + f, "from an earlier physical run\n");
  test_support::write_text(out + "/notes.txt", "the user's own file\n");
  const std::string cfg = write_config(dir, "c.yaml", config_text(out, 1.0, "in_process"));
  const auto r = test_support::run_process({hybridsim(), "run", "--config", cfg, "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"physical.csv", "safety.json", "run.key", "tracking.json", "rig.log", "run.lcmlog"})
    EXPECT_FALSE(fs::exists(out + "/" + f)) << f << " of the earlier run stands beside the new summary";
  EXPECT_TRUE(fs::exists(out + "/notes.txt")) << "only a run's own file names are cleared";
  fs::remove_all(dir);
}

TEST(FaultRun, DiskFullFailsTheRunAndKeepsWhatWasWritten) {
  const std::string dir = test_support::fresh_temp_dir("diskfull");
  const std::string out = dir + "/out";
  const std::string cfg = write_config(dir, "c.yaml", config_text(out, 20.0, "in_process"));
  const long limit = 300'000;  // bytes per file: the time history (~3 MB) cannot fit
  Child c = start({hybridsim(), "run", "--config", cfg}, dir, limit);
  const int code = c.wait();
  EXPECT_EQ(code, 1) << c.err();
  const nlohmann::json s = read_json(out + "/summary.json");
  EXPECT_EQ(s.value("status", ""), "failed");
  EXPECT_NE(s.value("error", "").find("time_history.csv"), std::string::npos) << s.dump();
  EXPECT_NE(c.err().find("time_history.csv"), std::string::npos) << c.err();
  // What fitted is on disk, in whole rows up to the limit.
  const auto size = fs::file_size(out + "/time_history.csv");
  EXPECT_GT(size, limit / 2);
  EXPECT_LE(size, static_cast<std::uintmax_t>(limit));
  fs::remove_all(dir);
}

TEST(FaultRun, NonFiniteStateFailsTheRunWithTheReason) {
  const std::string dir = test_support::fresh_temp_dir("nan");
  const std::string out = dir + "/out";
  // Masses of 1e308 kip·s²/in: M⁻¹ and the energies overflow.
  server::RunConfig c = run_config(out, 2.0, "in_process");
  c.building.story_mass_kip_s2_per_in = {1e308, 1e308, 1e308};
  const std::string cfg = write_config(dir, "c.yaml", config_text(c));
  const auto r = test_support::run_process({hybridsim(), "run", "--config", cfg, "--quiet"});
  EXPECT_NE(r.exit_code, 0) << r.out;
  if (r.exit_code == 1) {
    const nlohmann::json s = read_json(out + "/summary.json");
    EXPECT_EQ(s.value("status", ""), "failed");
    EXPECT_NE(s.value("error", "").find("physics check"), std::string::npos) << s.dump();
  } else {
    EXPECT_EQ(r.exit_code, 2) << r.err;  // or refused at load, naming the key
    EXPECT_NE(r.err.find("story_mass"), std::string::npos) << r.err;
  }
  fs::remove_all(dir);
}

TEST(FaultRun, EnergyBalanceAboveTheBoundFailsTheRun) {
  const std::string dir = test_support::fresh_temp_dir("energy");
  const std::string out = dir + "/out";
  // The run's ledger closes to round-off (~1e-15 over 30 s); a bound below round-off must
  // fail the run with the reason, the default bound (1e-6) must pass the same run.
  server::RunConfig c = run_config(out, 30.0, "in_process");
  c.max_energy_balance_error = 1e-17;
  const std::string cfg = write_config(dir, "c.yaml", config_text(c));
  const auto r = test_support::run_process({hybridsim(), "run", "--config", cfg, "--quiet"});
  const nlohmann::json s = read_json(out + "/summary.json");
  const double err = s["energy_kip_in"].value("balance_error", 0.0);
  ASSERT_GT(err, 1e-17) << "round-off vanished exactly; the bound cannot be exceeded";
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(s.value("status", ""), "failed");
  EXPECT_NE(s.value("error", "").find("run.max_energy_balance_error"), std::string::npos) << s.dump();
  EXPECT_LT(err, 1e-6);
  const std::string cfg2 = write_config(dir, "d.yaml", config_text(out, 30.0, "in_process"));
  const auto r2 = test_support::run_process({hybridsim(), "run", "--config", cfg2, "--quiet"});
  EXPECT_EQ(r2.exit_code, 0) << r2.err;
  fs::remove_all(dir);
}

/// Runs `hybridsim run` on `text` (written to `dir`/c.yaml); returns the result.
test_support::ProcessResult run_text(const std::string& dir, const std::string& text) {
  const std::string cfg = write_config(dir, "c.yaml", text);
  return test_support::run_process({hybridsim(), "run", "--config", cfg, "--out", dir + "/out", "--quiet"});
}

TEST(FaultRun, RecordLimitsAreInputErrorsNamingFileAndKey) {
  const std::string dir = test_support::fresh_temp_dir("record");
  const server::RunConfig valid = run_config(dir + "/out", 2.0, "in_process");
  const std::string base = config_text(valid);
  struct Case {
    std::string what, from, to, expect;
  };
  const std::vector<Case> cases = {
      {"duration 0 (docs: < 0 = whole record)", "duration_s: 2\n", "duration_s: 0\n", "record.duration_s"},
      {"duration longer than the record", "duration_s: 2\n", "duration_s: 60\n", "longer than the record"},
      {"duration 1e7 s (24 GB before)", "duration_s: 2\n", "duration_s: 1e7\n", "record.duration_s"},
      {"dt_s larger than the record's DT", "dt_s: 0.0009765625\n", "dt_s: 0.02\n", "run.dt_s"},
      {"empty run name", "name: fault\n", "name: \"\"\n", "run.name"},
      {"duplicated key", "  scale: 1\n", "  scale: 1\n  scale: 2\n", "duplicated key"},
  };
  for (const Case& c : cases) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto r = run_text(dir, std::regex_replace(base, std::regex(c.from), c.to));
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(r.exit_code, 2) << c.what << "\n" << r.err;
    EXPECT_NE(r.err.find(dir + "/c.yaml:"), std::string::npos) << c.what << ": names file and line\n" << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.what << "\n" << r.err;
    EXPECT_LT(s, 5.0) << c.what;
  }
  // Records whose header is out of bounds: refused naming the record and its line 4.
  const std::string rec = test_support::read_text(record_path());
  for (const std::string header : {"NPTS= 100000000000000000000, DT= .0100 SEC", "NPTS=   5372, DT= 1e-300 SEC",
                                   "NPTS=   5372, DT= 1e6 SEC"}) {
    const std::string path = dir + "/bad.AT2";
    test_support::write_text(path, std::regex_replace(rec, std::regex("NPTS=   5372, DT=   .0100 SEC"), header));
    server::RunConfig c = valid;
    c.record.path = path;
    const auto r = run_text(dir, config_text(c));
    EXPECT_EQ(r.exit_code, 2) << header << "\n" << r.err;
    EXPECT_NE(r.err.find(path + ":4:"), std::string::npos) << header << "\n" << r.err;
  }
  fs::remove_all(dir);
}

TEST(FaultRun, MessagesNameTheInput) {
  const std::string dir = test_support::fresh_temp_dir("names");
  // A folder as --config.
  auto r = test_support::run_process({hybridsim(), "run", "--config", dir});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(dir + ": is a folder"), std::string::npos) << r.err;
  // A folder as a BRFD test.
  r = test_support::run_process({hybridsim(), "damper", "predict", "--config",
                                 test_paths::source_dir() + "/configs/brfd-semiactive.yaml", "--test", dir});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  fs::remove_all(dir);
}

TEST(FaultRun, OneExitCodeConventionForEverySubcommand) {
  // Command-line errors are bad input (2), not CLI11's 105/106/109.
  for (const std::vector<std::string>& argv :
       {std::vector<std::string>{hybridsim(), "run"}, {hybridsim(), "nonsense"},
        {hybridsim(), "run", "--config", "x.yaml", "--bogus"}, {hybridsim(), "damper", "predict"},
        {hybridsim(), "batch", "--jobs", "abc"}, {bin_dir() + "/brfd-substructure"},
        {bin_dir() + "/brfd-substructure", "--url", "udpm://239.255.76.67:7667?ttl=0", "--run-id", ""},
        {bin_dir() + "/brfd-rig"}}) {
    const auto r = test_support::run_process(argv);
    std::string cmd;
    for (std::size_t i = 1; i < argv.size(); ++i) cmd += argv[i] + " ";
    EXPECT_EQ(r.exit_code, 2) << cmd << "\n" << r.err;
  }
  EXPECT_EQ(test_support::run_process({hybridsim(), "--help"}).exit_code, 0);
}

TEST(FaultRun, TimeHistoryIsStreamedNotPreallocated) {
  // 10^12 expected rows (a 30-year run): the writer must not try to hold them.
  const std::string dir = test_support::fresh_temp_dir("stream");
  server::TimeHistoryWriter w(server::make_csv_time_history(dir + "/t.csv", {"a", "b", "c"}), 3,
                              1'000'000'000'000L);
  EXPECT_LE(w.allocated_blocks(), 64u);
  for (int i = 0; i < 300'000; ++i) {  // 293 blocks through a pool of 64
    w.add(i);
    w.add(2.0 * i);
    w.add(-i);
    w.end_row();
  }
  w.finish();
  EXPECT_TRUE(w.error().empty());
  EXPECT_LE(w.allocated_blocks(), 1024u);
  EXPECT_EQ(count_lines(dir + "/t.csv"), 300'001);
  fs::remove_all(dir);
}

}  // namespace

namespace {

using namespace fault;

/// A batch of the shipped El Centro record at three scales, 2 s each, in-process.
std::string batch_setup(const std::string& dir) {
  test_support::write_text(dir + "/records.txt", record_path() + " 1.0 a\n" + record_path() + " 0.5 b\n" +
                                                      record_path() + " 0.25 c\n");
  return write_config(dir, "c.yaml", config_text(dir + "/unused", 2.0, "lcm"));
}

test_support::ProcessResult batch(const std::string& dir, const std::string& cfg, std::vector<std::string> extra = {}) {
  std::vector<std::string> argv{hybridsim(), "batch", "--config", cfg, "--records", dir + "/records.txt",
                                "--out", dir + "/out", "--jobs", "1", "--transport", "in_process", "--quiet"};
  argv.insert(argv.end(), extra.begin(), extra.end());
  return test_support::run_process(argv);
}

TEST(FaultBatch, DiskFullFailsRunsWithoutFakeResultsAndResumeRedoesThem) {
  const std::string dir = test_support::fresh_temp_dir("batch-full");
  const std::string cfg = batch_setup(dir);
  // 2 s per run: ~300 kB of time history each; a 100 kB file limit fills the "disk" in every run.
  Child c = start({hybridsim(), "batch", "--config", cfg, "--records", dir + "/records.txt", "--out", dir + "/out",
                   "--jobs", "1", "--transport", "in_process", "--quiet"},
                  dir, 100'000);
  const int code = c.wait();
  EXPECT_EQ(code, 1) << c.out() << c.err();
  // No run is counted ok on a full disk; every summary on disk is complete JSON.
  int summaries = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir + "/out/runs")) {
    if (e.path().filename() != "summary.json") continue;
    ++summaries;
    const nlohmann::json s = read_json(e.path().string());
    EXPECT_NE(s.value("status", ""), "ok") << e.path();
  }
  EXPECT_GT(summaries, 0);
  // Resume on a disk with room: --retry-failed redoes them, all ok.
  const auto r = batch(dir, cfg, {"--retry-failed"});
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("records=3 ok=3 failed=0"), std::string::npos) << r.out;
  fs::remove_all(dir);
}

TEST(FaultBatch, ResumeNamesAndRedoesAnUnreadableSummary) {
  const std::string dir = test_support::fresh_temp_dir("batch-zero");
  const std::string cfg = batch_setup(dir);
  auto r = batch(dir, cfg);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  // What a full disk left before summaries were atomic: a 0-byte summary and batch-run.json.
  test_support::write_text(dir + "/out/runs/b/summary.json", "");
  test_support::write_text(dir + "/out/runs/b/batch-run.json", "");
  r = batch(dir, cfg);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.err.find(dir + "/out/runs/b/summary.json is unreadable (0 bytes)"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("records=3 ok=3 failed=0"), std::string::npos) << r.out;
  EXPECT_EQ(read_json(dir + "/out/runs/b/summary.json").value("status", ""), "ok");
  // --retry-failed over a half-written summary: same, never an exit 2 without the file's name.
  test_support::write_text(dir + "/out/runs/c/summary.json", "{\"status\": \"ok\", \"pe");
  r = batch(dir, cfg, {"--retry-failed"});
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.err.find(dir + "/out/runs/c/summary.json is unreadable"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

}  // namespace
