// An injector process on the run's LCM bus (issue 14): this test enters a private network
// namespace (test_netns_main), starts `hybridsim run` in it, and from a thread of its own
// publishes, during the whole run, garbage datagrams on FORCE_FEEDBACK and HEARTBEAT,
// well-formed force feedback of a foreign run id carrying 999 kip, and replays of the run's
// own earlier replies (captured off the bus) carrying 999 kip. Every one must be counted and
// dropped, none applied: the run completes "ok" with the peaks of a clean in-process run.
#include "fault_support.h"
#include "hybrid_lcm/drift_command_t.hpp"
#include "hybrid_lcm/force_feedback_t.hpp"

#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include <atomic>
#include <random>
#include <thread>

namespace {

using namespace fault;

const char* kUrl = "udpm://239.255.76.67:7667?ttl=0";

struct Injector {
  std::atomic<bool> stop{false};
  std::atomic<long> garbage{0}, foreign{0}, replays{0};
  std::vector<hybrid_lcm::force_feedback_t> captured;  // the run's own replies
  std::mutex mutex;

  void on_feedback(const lcm::ReceiveBuffer* rbuf, const std::string&, const hybrid_lcm::force_feedback_t* fb) {
    (void)rbuf;
    if (fb->run_id == "intruder" || fb->force_kip.empty() || fb->force_kip[0] == 999.0) return;
    std::lock_guard<std::mutex> lock(mutex);
    if (captured.size() < 100000) captured.push_back(*fb);
  }

  void run() {
    lcm::LCM lcm(kUrl);
    lcm.subscribe("BRFD_FORCE_FEEDBACK", &Injector::on_feedback, this);
    std::mt19937 rng(666);
    std::vector<uint8_t> junk;
    long k = 0;
    while (!stop) {
      lcm.handleTimeout(1);
      // garbage: random bytes, random length
      junk.resize(1 + rng() % 64);
      for (uint8_t& b : junk) b = static_cast<uint8_t>(rng());
      lcm.publish(k % 2 ? "BRFD_FORCE_FEEDBACK" : "BRFD_HEARTBEAT", junk.data(), static_cast<unsigned>(junk.size()));
      ++garbage;
      // a foreign run's reply for a plausible step
      hybrid_lcm::force_feedback_t f;
      f.run_id = "intruder";
      f.step = k;
      f.num_dampers = 1;
      f.force_kip = {999.0};
      f.measured_drift_in = {0.0};
      f.status = 0;
      lcm.publish("BRFD_FORCE_FEEDBACK", &f);
      ++foreign;
      // a replay of one of the run's own earlier replies, with a forged force
      hybrid_lcm::force_feedback_t old;
      bool have = false;
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (captured.size() > 5) {
          old = captured[captured.size() - 5];
          have = true;
        }
      }
      if (have) {
        old.force_kip.assign(old.num_dampers, 999.0);
        lcm.publish("BRFD_FORCE_FEEDBACK", &old);
        ++replays;
      }
      ++k;
      std::this_thread::sleep_for(std::chrono::microseconds(700));
    }
  }
};

TEST(Injector, GarbageForeignRunsAndReplaysAreCountedDroppedAndNeverApplied) {
  const std::string dir = test_support::fresh_temp_dir("inject");
  // Reference: the same run in-process (no bus at all).
  const auto ref = test_support::run_process({hybridsim(), "run", "--config",
                                              write_config(dir, "ref.yaml", config_text(dir + "/ref", 5.0, "in_process")),
                                              "--quiet"});
  ASSERT_EQ(ref.exit_code, 0) << ref.err;
  Injector injector;
  std::thread t([&] { injector.run(); });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const auto r = test_support::run_process({hybridsim(), "run", "--config",
                                            write_config(dir, "c.yaml", config_text(dir + "/out", 5.0, "lcm")),
                                            "--quiet"});
  injector.stop = true;
  t.join();
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json s = read_json(dir + "/out/summary.json"), sref = read_json(dir + "/ref/summary.json");
  EXPECT_EQ(s.value("status", ""), "ok") << s.dump();
  EXPECT_EQ(s["peak_drift_in"], sref["peak_drift_in"]) << "a forged force entered the building";
  EXPECT_EQ(s["peak_damper_force_kip"], sref["peak_damper_force_kip"]);
  EXPECT_LT(s["peak_damper_force_kip"][0].get<double>(), 10.0);
  const nlohmann::json& d = s["dropped_messages"];
  long dropped = 0;
  for (const auto& kv : d.items()) dropped += kv.value().get<long>();
  EXPECT_GT(d.value("malformed message on BRFD_FORCE_FEEDBACK", 0L), 0) << d.dump();
  EXPECT_GT(d.value("malformed message on BRFD_HEARTBEAT", 0L), 0) << d.dump();
  EXPECT_GT(d.value("foreign run id on BRFD_FORCE_FEEDBACK", 0L), 0) << d.dump();
  EXPECT_GT(d.value("out-of-order step on BRFD_FORCE_FEEDBACK", 0L), 0) << d.dump();
  // said once per kind
  std::size_t lines = 0;
  for (std::size_t p = r.err.find("hybridsim: dropped "); p != std::string::npos; p = r.err.find("hybridsim: dropped ", p + 1))
    ++lines;
  EXPECT_EQ(lines, d.size()) << r.err;
  std::printf("[ inject   ] sent %ld garbage, %ld foreign-run, %ld replayed datagrams during the run; server dropped "
              "%ld (%s); peaks equal to the in-process run\n",
              injector.garbage.load(), injector.foreign.load(), injector.replays.load(), dropped, d.dump().c_str());
  fs::remove_all(dir);
}

}  // namespace
