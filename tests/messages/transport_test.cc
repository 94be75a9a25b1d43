// The transport seam (messages/transport.h, messages/in_memory_lcm.h):
//  - the in-memory fake delivers in publish order after its latency, to every subscriber
//    (publisher included), loses messages nobody subscribes to, and moves its simulated clock
//    only to the next event: handle_until at a deadline leaves the clock there;
//  - strict decode: another type's bytes, a truncated message and trailing bytes are a
//    DecodeError naming the channel and type, handed to on_error or rethrown after dispatch;
//  - a handler's exception never escapes a dispatch midway: the other handlers still run, the
//    first exception is rethrown after the dispatch returns;
//  - publish failures are TransportErrors naming the channel (fake and liblcm alike);
//  - the same checks through liblcm itself (memq:// provider: in process, no network);
//  - a LoopActor on the fake gives the identical message history on every run.
#include "hybrid_lcm/force_feedback_t.hpp"
#include "hybrid_lcm/heartbeat_t.hpp"
#include "messages/in_memory_lcm.h"
#include "messages/transport.h"

#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>

namespace {

using namespace std::chrono_literals;
using hybrid_lcm::force_feedback_t;
using hybrid_lcm::heartbeat_t;
using messages::DecodeError;
using messages::InMemoryBus;
using messages::RawMessage;

heartbeat_t heartbeat(int64_t sequence) {
  heartbeat_t hb;
  hb.utime = 1;
  hb.run_id = "run";
  hb.sender = "test";
  hb.sequence = sequence;
  hb.state = heartbeat_t::STATE_IDLE;
  hb.hmac_length = 0;  // unsigned: the transport tests do not authenticate
  return hb;
}

TEST(InMemoryLcm, DeliversInOrderAfterTheLatencyToEverySubscriberIncludingThePublisher) {
  InMemoryBus bus(100us);
  auto a = bus.endpoint(), b = bus.endpoint();
  std::vector<std::pair<char, int64_t>> got;
  heartbeat_t scratch_a, scratch_b;
  messages::subscribe_message<heartbeat_t>(*a, "HB", scratch_a,
                                           [&](heartbeat_t& m, const RawMessage&) { got.push_back({'a', m.sequence}); });
  messages::subscribe_message<heartbeat_t>(*b, "HB", scratch_b,
                                           [&](heartbeat_t& m, const RawMessage&) { got.push_back({'b', m.sequence}); });
  const auto t0 = bus.now();
  messages::publish_message(*a, "HB", heartbeat(1));
  messages::publish_message(*a, "HB", heartbeat(2));
  messages::publish_message(*a, "NOBODY", heartbeat(3));  // lost, as on LCM
  EXPECT_FALSE(b->handle_until(t0 + 50us));  // not yet delivered
  EXPECT_EQ(bus.now(), t0 + 50us);           // the clock went to the deadline, no further
  EXPECT_TRUE(b->handle_until(t0 + 1s));
  EXPECT_EQ(bus.now(), t0 + 100us);  // the clock went to the delivery, no further
  EXPECT_TRUE(b->handle_until(t0 + 1s));
  EXPECT_FALSE(b->handle_until(t0 + 1s));  // the unsubscribed message reaches nobody
  EXPECT_EQ(bus.now(), t0 + 1s);
  EXPECT_EQ(got, (std::vector<std::pair<char, int64_t>>{{'a', 1}, {'b', 1}, {'a', 2}, {'b', 2}}));
  EXPECT_EQ(bus.history().size(), 3u);
  EXPECT_EQ(bus.utime() - 1767225600LL * 1000000LL, 2000000);  // simulated clock, 1 s + 1 s
}

TEST(InMemoryLcm, StrictDecodeNamesChannelAndType) {
  InMemoryBus bus;
  auto lcm = bus.endpoint();
  force_feedback_t scratch;
  std::vector<std::string> errors;
  long ok = 0;
  messages::subscribe_message<force_feedback_t>(
      *lcm, "FB", scratch, [&](force_feedback_t&, const RawMessage&) { ++ok; },
      [&](const DecodeError& e, const RawMessage&) { errors.push_back(e.what()); });
  messages::publish_message(*lcm, "FB", heartbeat(1));  // another type: hash mismatch
  force_feedback_t fb{};  // every field zero (hmac_length, seq, ...): lcm-gen types leave scalars uninitialized
  fb.run_id = "r";
  fb.num_dampers = 1;
  fb.force_kip = {1.0};
  fb.measured_drift_in = {0.1};
  fb.actuator1_position_in = {0.655};  // every array is sized num_dampers
  fb.actuator2_position_in = {0.8559};
  std::vector<uint8_t> bytes;
  messages::publish_message(*lcm, "FB", fb, bytes);
  lcm->publish("FB", bytes.data(), bytes.size() - 3);  // truncated
  bytes.push_back(0);
  lcm->publish("FB", bytes.data(), bytes.size());      // a trailing byte
  while (lcm->handle_until(bus.now() + 1s)) {
  }
  EXPECT_EQ(ok, 1);
  ASSERT_EQ(errors.size(), 3u);
  for (const std::string& e : errors) {
    EXPECT_NE(e.find("LCM channel 'FB'"), std::string::npos) << e;
    EXPECT_NE(e.find("force_feedback_t"), std::string::npos) << e;
  }

  // Without on_error the DecodeError is rethrown by handle_until, after the dispatch.
  heartbeat_t hb_scratch;
  messages::subscribe_message<heartbeat_t>(*lcm, "HB", hb_scratch, [](heartbeat_t&, const RawMessage&) {});
  messages::publish_message(*lcm, "HB", fb);
  EXPECT_THROW(lcm->handle_until(bus.now() + 1s), DecodeError);
}

TEST(InMemoryLcm, AHandlerExceptionIsRethrownAfterEveryHandlerRan) {
  InMemoryBus bus;
  auto a = bus.endpoint(), b = bus.endpoint();
  int later_handler_calls = 0;
  a->subscribe("X", [](const RawMessage&) { throw std::runtime_error("first"); });
  a->subscribe("X", [](const RawMessage&) { throw std::runtime_error("second"); });
  b->subscribe("X", [&](const RawMessage&) { ++later_handler_calls; });
  const uint8_t byte = 7;
  a->publish("X", &byte, 1);
  try {
    a->handle_until(bus.now() + 1s);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "first");
  }
  EXPECT_EQ(later_handler_calls, 1);  // the dispatch was not cut short
  EXPECT_FALSE(a->handle_until(bus.now() + 1s));  // nothing left pending
}

TEST(InMemoryLcm, InjectedPublishFailureIsATransportErrorNamingTheChannel) {
  InMemoryBus bus;
  auto lcm = bus.endpoint();
  bus.fail_publishes("HB");
  try {
    messages::publish_message(*lcm, "HB", heartbeat(1));
    FAIL() << "publish succeeded";
  } catch (const messages::TransportError& e) {
    EXPECT_NE(std::string(e.what()).find("'HB'"), std::string::npos) << e.what();
  }
  bus.fail_publishes("HB", false);
  EXPECT_NO_THROW(messages::publish_message(*lcm, "HB", heartbeat(2)));
}

/// Answers every PING with a PONG after 3 ms of "work", and publishes a TICK every 10 ms.
class PingActor : public messages::LoopActor {
 public:
  explicit PingActor(messages::LcmInterface& lcm) : lcm_(lcm) {
    messages::subscribe_message<heartbeat_t>(lcm_, "PING", scratch_, [this](heartbeat_t& m, const RawMessage&) {
      pending_.push_back({lcm_.now() + 3ms, m.sequence});
    });
    next_tick_ = lcm_.now();
  }
  void advance(messages::TimePoint now) override {
    while (!pending_.empty() && pending_.front().first <= now) {
      messages::publish_message(lcm_, "PONG", heartbeat(pending_.front().second), buffer_);
      pending_.erase(pending_.begin());
    }
    if (now >= next_tick_) {
      messages::publish_message(lcm_, "TICK", heartbeat(ticks_++), buffer_);
      next_tick_ += 10ms;
    }
  }
  messages::TimePoint next_deadline(messages::TimePoint) const override {
    return pending_.empty() ? next_tick_ : std::min(next_tick_, pending_.front().first);
  }
  bool finished() const override { return ticks_ >= 20; }

 private:
  messages::LcmInterface& lcm_;
  heartbeat_t scratch_;
  std::vector<std::pair<messages::TimePoint, int64_t>> pending_;
  messages::TimePoint next_tick_;
  int64_t ticks_ = 0;
  std::vector<uint8_t> buffer_;
};

std::vector<std::pair<long long, std::string>> simulate_ping_pong() {
  InMemoryBus bus(150us);
  auto actor_lcm = bus.endpoint(), test_lcm = bus.endpoint();
  PingActor actor(*actor_lcm);
  long pongs = 0;
  test_lcm->subscribe("PONG", [&](const RawMessage&) { ++pongs; });
  // A second "process" that pings every 7 ms, as an actor of its own.
  struct Pinger : messages::LoopActor {
    messages::LcmInterface& lcm;
    messages::TimePoint next;
    int64_t seq = 0;
    explicit Pinger(messages::LcmInterface& l) : lcm(l), next(l.now()) {}
    void advance(messages::TimePoint now) override {
      if (now >= next) {
        messages::publish_message(lcm, "PING", heartbeat(seq++));
        next += 7ms;
      }
    }
    messages::TimePoint next_deadline(messages::TimePoint) const override { return next; }
    bool finished() const override { return seq >= 25; }
  } pinger(*test_lcm);
  EXPECT_TRUE(bus.run({&actor, &pinger}, [&] { return actor.finished(); }, bus.now() + 10s));
  std::vector<std::pair<long long, std::string>> h;
  for (const auto& r : bus.history())
    h.push_back({static_cast<long long>(std::chrono::duration_cast<std::chrono::microseconds>(r.published_at.time_since_epoch()).count()),
                 r.channel});
  EXPECT_GT(pongs, 20);
  return h;
}

TEST(InMemoryLcm, TwoActorsOnTheSimulatedClockGiveTheSameHistoryEveryRun) {
  const auto first = simulate_ping_pong();
  const auto second = simulate_ping_pong();
  ASSERT_FALSE(first.empty());
  EXPECT_EQ(first, second);
  // Pong n is published 3 ms (work) + 150 us (latency) after ping n: ping at 7n ms.
  long long ping0 = -1, pong0 = -1;
  for (const auto& [t, ch] : first) {
    if (ch == "PING" && ping0 < 0) ping0 = t;
    if (ch == "PONG" && pong0 < 0) pong0 = t;
  }
  EXPECT_EQ(pong0 - ping0, 3150);
}

// liblcm itself, through the memq:// provider (in process, no socket, no network namespace).
TEST(LcmTransport, MemqPublishSubscribeStrictDecodeAndExceptionAfterDispatch) {
  messages::LcmTransport lcm("memq://", false);
  heartbeat_t scratch;
  std::vector<int64_t> got;
  std::vector<std::string> errors;
  messages::subscribe_message<heartbeat_t>(
      lcm, "HB", scratch, [&](heartbeat_t& m, const RawMessage&) { got.push_back(m.sequence); },
      [&](const DecodeError& e, const RawMessage&) { errors.push_back(e.what()); });
  messages::publish_message(lcm, "HB", heartbeat(5));
  force_feedback_t fb{};  // zero dampers: a valid message of another type
  messages::publish_message(lcm, "HB", fb);
  const auto deadline = lcm.now() + 2s;
  while ((got.size() + errors.size()) < 2 && lcm.now() < deadline) lcm.handle_until(deadline);
  EXPECT_EQ(got, std::vector<int64_t>{5});
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("LCM channel 'HB'"), std::string::npos) << errors[0];

  lcm.subscribe("BOOM", [](const RawMessage&) { throw std::runtime_error("from a handler"); });
  const uint8_t byte = 1;
  lcm.publish("BOOM", &byte, 1);
  EXPECT_THROW(
      {
        while (lcm.now() < deadline) lcm.handle_until(deadline);
      },
      std::runtime_error);
  EXPECT_THROW(messages::LcmTransport("", false), messages::TransportError);

  // An uninitialised array length is caught before anything is published.
  force_feedback_t bad{};
  bad.num_dampers = -3;
  EXPECT_THROW(messages::publish_message(lcm, "FB", bad), messages::EncodeError);
}

}  // namespace
