// The virtual node of brfd-substructure (damper::SubstructureNode) and the node-side endpoint
// it shares with the physical node (messages/substructure_endpoint.h), on the in-memory
// transport with a simulated clock: the test plays the server.
//  - START -> READY heartbeat; each drift command -> one reply whose force is BrfdModel's
//    (stepped independently here: equal to the last bit); a repeated command is answered
//    again without stepping twice; commands of another run are ignored;
//  - a command out of range is a FAULT naming the value; a START out of range is ignored;
//  - undecodable run control is reported and dropped, the node keeps running;
//  - the command watchdog ends a silent run (exit 1) exactly command_watchdog_s after the last
//    command; STOP ends with 0, ABORT with 3;
//  - authentication (messages/message_auth.h): every heartbeat and reply verifies under the
//    run key and a reply echoes the command's sequence; a forged ABORT, a forged or replayed
//    drift command, another run's command and garbage are each counted by kind and dropped
//    (nothing stepped, nothing answered, the run goes on); under policy stop the next command
//    is answered with a FAULT naming the first bad message.
#include "damper/model/brfd_config.h"
#include "damper/substructure/substructure_node.h"
#include "messages/in_memory_lcm.h"
#include "messages/message_auth.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

namespace {

using namespace std::chrono_literals;
using hybrid_lcm::force_feedback_t;
using hybrid_lcm::heartbeat_t;
using hybrid_lcm::run_control_t;

constexpr int kStatusOk = force_feedback_t::STATUS_OK;
constexpr int kStatusFault = force_feedback_t::STATUS_FAULT;
constexpr int8_t kStateRunning = heartbeat_t::STATE_RUNNING;

/// The run key of these tests: bytes 0, 1, ..., 31 (docs/physical.md's test-vector key).
messages::RunKey test_key() {
  messages::RunKey k{};
  for (int i = 0; i < 32; ++i) k[static_cast<std::size_t>(i)] = static_cast<uint8_t>(i);
  return k;
}

struct Harness {
  messages::InMemoryBus bus;
  std::unique_ptr<messages::InMemoryLcm> node_lcm = bus.endpoint(), server = bus.endpoint();
  messages::Channels ch;
  damper::SubstructureNodeOptions o;
  std::unique_ptr<damper::SubstructureNode> node;
  heartbeat_t hb;
  force_feedback_t fb;
  std::vector<force_feedback_t> replies;
  int8_t last_state = -1;
  messages::MessageAuth auth{test_key()};
  int64_t sequence = 0;          ///< the server's: one counter for run control and commands
  std::vector<uint8_t> buffer;
  long unsigned_replies = 0;     ///< heartbeats and replies whose HMAC did not verify

  explicit Harness(double watchdog_s = 30.0, messages::BadMessagePolicy policy = messages::BadMessagePolicy::drop) {
    o.key = test_key();
    o.on_bad_message = policy;
    o.url = "in-memory";
    o.channels = ch;
    o.model = damper::load_brfd_params(test_paths::source_dir() + "/configs/brfd-default.yaml");
    o.command_watchdog_s = watchdog_s;
    node = std::make_unique<damper::SubstructureNode>(*node_lcm, o);
    messages::subscribe_message<heartbeat_t>(*server, ch.heartbeat(), hb,
                                             [this](heartbeat_t& h, const messages::RawMessage& raw) {
                                               if (!auth.verify(raw)) ++unsigned_replies;
                                               last_state = h.state;
                                             });
    messages::subscribe_message<force_feedback_t>(*server, ch.force_feedback(), fb,
                                                  [this](force_feedback_t& f, const messages::RawMessage& raw) {
                                                    if (!auth.verify(raw)) ++unsigned_replies;
                                                    replies.push_back(f);
                                                  });
  }
  void control(int8_t command, int32_t dampers = 2, double dt = 1.0 / 1024.0, const std::string& run = "r1") {
    run_control_t m{};
    m.utime = bus.utime();
    m.run_id = run;
    m.command = command;
    m.num_dampers = dampers;
    m.dt_s = dt;
    m.reason = "test";
    m.sequence = ++sequence;
    auth.publish(*server, ch.run_control(), m, buffer);
  }
  /// The bytes of the last message published on `channel` (to replay or tamper with them).
  std::vector<uint8_t> last_bytes_on(const std::string& channel) const {
    for (auto it = bus.history().rbegin(); it != bus.history().rend(); ++it)
      if (it->channel == channel) return it->bytes;
    return {};
  }
  hybrid_lcm::drift_command_t command(int64_t step, double d1, double v1, const std::string& run = "r1") {
    hybrid_lcm::drift_command_t c{};
    c.utime = bus.utime();
    c.run_id = run;
    c.step = step;
    c.sim_time_s = step / 1024.0;
    c.num_dampers = 2;
    c.drift_in = {d1, -0.5 * d1};
    c.drift_velocity_in_per_s = {v1, -0.5 * v1};
    // Passive run: the electric actuators held at x'_1, x'_2 (the control issue's targets).
    c.actuator1_target_in.assign(2, o.model.semiactive.actuator1_initial_in);
    c.actuator2_target_in.assign(2, o.model.semiactive.actuator2_initial_in);
    c.actuator_targets_valid = 0;
    c.sequence = ++sequence;
    return c;
  }
  void drift(int64_t step, double d1, double v1, const std::string& run = "r1") {
    hybrid_lcm::drift_command_t c = command(step, d1, v1, run);
    auth.publish(*server, ch.drift_command(), c, buffer);
  }
  long count(const std::string& kind) const {
    const auto& c = node->bad_messages().counts();
    const auto it = c.find(kind);
    return it == c.end() ? 0 : it->second;
  }
  /// Runs the node until `done` or `for_s` of simulated time.
  bool run(const std::function<bool()>& done, double for_s = 1.0) {
    return bus.run({node.get()}, done, bus.now() + messages::seconds_to_duration(for_s));
  }
};

TEST(SubstructureNode, AnswersEachStepWithTheModelsForceOnceAndRepeatsWithoutSteppingTwice) {
  Harness h;
  h.control(run_control_t::COMMAND_START);
  ASSERT_TRUE(h.run([&] { return h.last_state == heartbeat_t::STATE_READY; }));
  damper::BrfdModel ref1(h.o.model), ref2(h.o.model);
  auto expected = [&](damper::BrfdModel& m, double d, double v) {
    damper::DamperInput in;
    in.drum_disp_in = d;
    in.drum_vel_in_per_s = v;
    in.actuator1_in = h.o.model.semiactive.actuator1_initial_in;
    in.actuator2_in = h.o.model.semiactive.actuator2_initial_in;
    return m.step(in, 1.0 / 1024.0);
  };
  for (int64_t k = 1; k <= 50; ++k) {
    const double d = 0.3 * std::sin(0.05 * k), v = 0.3 * 0.05 * 1024 * std::cos(0.05 * k);
    h.drift(k, d, v);
    ASSERT_TRUE(h.run([&] { return static_cast<int64_t>(h.replies.size()) == k; }));
    const force_feedback_t& r = h.replies.back();
    ASSERT_EQ(r.step, k);
    ASSERT_EQ(r.status, kStatusOk);
    EXPECT_EQ(r.force_kip[0], expected(ref1, d, v));
    EXPECT_EQ(r.force_kip[1], expected(ref2, -0.5 * d, -0.5 * v));
    EXPECT_EQ(r.measured_drift_in[0], d);
  }
  EXPECT_EQ(h.node->steps(), 50);
  h.drift(50, 9.0, 9.0);  // a repeat (lost reply): answered again, not stepped
  h.drift(51, 0.1, 0.0, "other-run");  // another run: ignored
  ASSERT_TRUE(h.run([&] { return h.replies.size() == 51; }));
  EXPECT_FALSE(h.run([&] { return h.replies.size() > 51; }, 0.1));
  EXPECT_EQ(h.replies.back().step, 50);
  EXPECT_EQ(h.replies.back().force_kip[0], h.replies[49].force_kip[0]);
  EXPECT_EQ(h.replies.back().command_sequence, h.sequence - 1);  // bound to the repeat, not the first
  EXPECT_EQ(h.node->steps(), 50);
  EXPECT_EQ(h.count("DRIFT_COMMAND/foreign_run"), 1);
  EXPECT_EQ(h.unsigned_replies, 0);
  // The next heartbeat (every heartbeat_period_s, 0.2 s) says RUNNING.
  EXPECT_TRUE(h.run([&] { return h.last_state == kStateRunning; }, h.o.heartbeat_period_s + 1e-3));
  h.control(run_control_t::COMMAND_STOP);
  ASSERT_TRUE(h.run([&] { return h.node->finished(); }));
  EXPECT_EQ(h.node->exit_code(), 0);
}

TEST(SubstructureNode, OutOfRangeCommandIsAFaultNamingTheValueAndBadStartIsIgnored) {
  Harness h;
  h.control(run_control_t::COMMAND_START, 0);  // no dampers: out of range, ignored
  EXPECT_FALSE(h.run([&] { return h.last_state == heartbeat_t::STATE_READY; }, 0.5));
  // Another type's bytes on the run-control channel: reported on stderr, counted, dropped.
  heartbeat_t garbage{};
  garbage.hmac_length = 0;
  messages::publish_message(*h.server, h.ch.run_control(), garbage);
  h.control(run_control_t::COMMAND_START);
  ASSERT_TRUE(h.run([&] { return h.last_state == heartbeat_t::STATE_READY; }));
  h.drift(1, 13.5, 0.0);  // beyond max_drum_displacement_in = 12 in
  ASSERT_TRUE(h.run([&] { return h.replies.size() == 1; }));
  EXPECT_EQ(h.replies[0].status, kStatusFault);
  EXPECT_NE(h.replies[0].message.find("13.5"), std::string::npos) << h.replies[0].message;
  EXPECT_EQ(h.node->steps(), 0);
  EXPECT_EQ(h.count("RUN_CONTROL/malformed"), 1);
  h.control(run_control_t::COMMAND_ABORT);
  ASSERT_TRUE(h.run([&] { return h.node->finished(); }));
  EXPECT_EQ(h.node->exit_code(), 3);
}

TEST(SubstructureNode, CommandWatchdogEndsASilentRunExactlyOnTime) {
  Harness h(0.5);
  h.control(run_control_t::COMMAND_START);
  ASSERT_TRUE(h.run([&] { return h.last_state == heartbeat_t::STATE_READY; }));
  h.drift(1, 0.1, 0.0);
  ASSERT_TRUE(h.run([&] { return h.replies.size() == 1; }));
  const auto last_command_arrived = h.bus.now();  // the reply goes out when the command arrives
  ASSERT_TRUE(h.run([&] { return h.node->finished(); }, 5.0));
  EXPECT_EQ(h.node->exit_code(), 1);
  // Its deadline is 1 ms past the limit: exit between 0.5 s and 0.5 s + 1 ms after the command.
  const double after_s = messages::seconds_between(last_command_arrived, h.bus.now());
  EXPECT_GT(after_s, 0.5 - 25e-6);
  EXPECT_LE(after_s, 0.501);
}

TEST(SubstructureNode, ForgedReplayedForeignAndGarbageMessagesAreCountedByKindAndDropped) {
  Harness h;
  h.control(run_control_t::COMMAND_START);
  ASSERT_TRUE(h.run([&] { return h.last_state == heartbeat_t::STATE_READY; }));
  h.drift(1, 0.1, 1.0);
  ASSERT_TRUE(h.run([&] { return h.replies.size() == 1; }));
  EXPECT_EQ(h.replies[0].command_sequence, h.sequence);
  EXPECT_EQ(h.replies[0].run_id, "r1");
  const std::vector<uint8_t> command1 = h.last_bytes_on(h.ch.drift_command());  // signed, step 1

  // 1. A forged ABORT: right run id, fresh sequence, signed with another key.
  messages::RunKey other = test_key();
  other[0] ^= 1;
  run_control_t abort{};
  abort.utime = h.bus.utime();
  abort.run_id = "r1";
  abort.command = run_control_t::COMMAND_ABORT;
  abort.num_dampers = 2;
  abort.dt_s = 0.0;
  abort.reason = "forged";
  abort.sequence = h.sequence + 100;
  messages::MessageAuth(other).publish(*h.server, h.ch.run_control(), abort, h.buffer);
  // 2. The step-1 command replayed byte for byte (valid HMAC, old sequence).
  h.server->publish(h.ch.drift_command(), command1.data(), command1.size());
  // 3. A drift command of step 2 with one bit of its drift flipped after signing.
  hybrid_lcm::drift_command_t c2 = h.command(2, 0.2, 1.0);
  h.auth.sign(c2, h.buffer);
  std::vector<uint8_t> tampered = h.buffer;
  tampered[8 + 8 + 4 + 3 + 8 + 8 + 4 + 2] ^= 0x10;  // inside drift_in[0] (after utime .. num_dampers)
  h.server->publish(h.ch.drift_command(), tampered.data(), tampered.size());
  // 4. Another run's command, garbage bytes, a truncated command.
  h.drift(2, 0.2, 1.0, "r2");
  const std::vector<uint8_t> noise{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
  h.server->publish(h.ch.drift_command(), noise.data(), noise.size());
  h.server->publish(h.ch.drift_command(), command1.data(), command1.size() - 7);
  EXPECT_FALSE(h.run([&] { return h.replies.size() > 1 || h.node->finished(); }, 0.1));
  EXPECT_EQ(h.node->steps(), 1);
  EXPECT_EQ(h.count("RUN_CONTROL/bad_mac"), 1);
  EXPECT_EQ(h.count("DRIFT_COMMAND/replayed"), 1);
  EXPECT_EQ(h.count("DRIFT_COMMAND/bad_mac"), 2);  // the tampered one and the truncated one
  EXPECT_EQ(h.count("DRIFT_COMMAND/foreign_run"), 1);
  EXPECT_EQ(h.count("DRIFT_COMMAND/malformed"), 1);
  EXPECT_EQ(h.node->bad_messages().total(), 6);

  // The run goes on: the genuine step 2 is answered, bound to its own sequence.
  h.drift(2, 0.2, 1.0);
  ASSERT_TRUE(h.run([&] { return h.replies.size() == 2; }));
  EXPECT_EQ(h.replies[1].step, 2);
  EXPECT_EQ(h.replies[1].status, kStatusOk);
  EXPECT_EQ(h.replies[1].command_sequence, h.sequence);
  EXPECT_GT(h.replies[1].sequence, h.replies[0].sequence);
  EXPECT_EQ(h.unsigned_replies, 0);
  h.control(run_control_t::COMMAND_STOP);
  ASSERT_TRUE(h.run([&] { return h.node->finished(); }));
  EXPECT_EQ(h.node->exit_code(), 0);
}

TEST(SubstructureNode, PolicyStopAnswersTheNextCommandWithAFaultNamingTheBadMessage) {
  Harness h(30.0, messages::BadMessagePolicy::stop);
  h.control(run_control_t::COMMAND_START);
  ASSERT_TRUE(h.run([&] { return h.last_state == heartbeat_t::STATE_READY; }));
  hybrid_lcm::drift_command_t c = h.command(1, 0.1, 1.0);
  messages::RunKey other = test_key();
  other[31] ^= 0x80;
  messages::MessageAuth(other).publish(*h.server, h.ch.drift_command(), c, h.buffer);
  h.drift(1, 0.1, 1.0);
  ASSERT_TRUE(h.run([&] { return h.replies.size() == 1; }));
  EXPECT_EQ(h.replies[0].status, kStatusFault);
  EXPECT_NE(h.replies[0].message.find("DRIFT_COMMAND/bad_mac"), std::string::npos) << h.replies[0].message;
  EXPECT_EQ(h.node->steps(), 0);
}

}  // namespace
