#pragma once
/// @file in_memory_lcm.h
/// The in-memory fake of LcmInterface (transport.h): deterministic, single process, simulated
/// clock. One InMemoryBus is the network and the clock; each process of the simulation gets
/// an endpoint (InMemoryLcm). A message published at simulated time t is delivered at t +
/// latency to every endpoint subscribed to its channel at that moment (publisher included, as
/// LCM multicast does), in publish order; a message nobody subscribes to is lost, as on LCM.
/// Nothing sleeps and nothing reads the wall clock: the clock only moves when a handle_until()
/// or the scheduler reaches the next event, so a simulation gives identical results every run.
///
/// How a test uses it:
///   messages::InMemoryBus bus;                       // clock at 0, latency 20 us
///   auto node_lcm = bus.endpoint(), test_lcm = bus.endpoint();
///   SomeNode node(*node_lcm, ...);                   // a LoopActor on the fake
///   messages::publish_message(*test_lcm, "X", msg);  // the test plays the other process
///   bus.run({&node}, [&] { return node.finished(); }, bus.now() + std::chrono::seconds(5));
/// or, with one actor, run_loop(*node_lcm, node) exactly as the process does.
/// Faults: fail_publishes(channel) makes publish() throw; drop_channel(channel) loses every
/// message on it; history() holds every message published (an lcm log of the simulation).

#include "messages/transport.h"

#include <map>
#include <set>

namespace messages {

class InMemoryLcm;

class InMemoryBus {
 public:
  /// Simulated time starts at TimePoint{} + 1 s; utime() maps it to a fixed epoch
  /// (2026-01-01T00:00:00Z + simulated time).
  explicit InMemoryBus(Duration latency = std::chrono::microseconds(20));
  ~InMemoryBus();
  InMemoryBus(const InMemoryBus&) = delete;
  InMemoryBus& operator=(const InMemoryBus&) = delete;

  /// A new endpoint (one process's LCM object) on this bus; it must not outlive the bus.
  std::unique_ptr<InMemoryLcm> endpoint();

  TimePoint now() const { return now_; }
  int64_t utime() const;
  /// Moves the clock forward to `t` (never back). Does not deliver.
  void advance_to(TimePoint t);
  Duration latency() const { return latency_; }
  void set_latency(Duration d) { latency_ = d; }

  /// Delivery time of the next queued message (TimePoint::max() when none).
  TimePoint next_delivery() const;
  /// Delivers every message due at or before now(), in order. Returns how many were
  /// delivered to at least one subscriber. Rethrows the first handler exception afterwards.
  int deliver_due();

  /// Discrete-event scheduler for several processes: repeatedly moves the clock to the
  /// earliest of the next delivery and the actors' next deadlines, delivers what is due and
  /// advances every unfinished actor, until `done()` or `limit` (simulated). Returns done().
  /// An actor that has run at the current time and asks for it again is run 1 us later.
  bool run(const std::vector<LoopActor*>& actors, const std::function<bool()>& done, TimePoint limit);

  /// Fault injection.
  void fail_publishes(const std::string& channel, bool fail = true);
  void drop_channel(const std::string& channel, bool drop = true);

  struct Record {
    TimePoint published_at;
    std::string channel;
    std::vector<uint8_t> bytes;
  };
  const std::vector<Record>& history() const { return history_; }
  void keep_history(bool keep) { keep_history_ = keep; }

 private:
  friend class InMemoryLcm;
  struct Pending {
    TimePoint at;
    uint64_t order;
    std::string channel;
    std::vector<uint8_t> bytes;
  };
  void publish(const std::string& channel, const uint8_t* data, std::size_t size);
  bool deliver_one(InMemoryLcm* wanted);  // delivers the front message; true if `wanted` got it
  void detach(InMemoryLcm* endpoint);

  Duration latency_;
  TimePoint now_;
  uint64_t order_ = 0;
  std::deque<Pending> queue_;  // ordered by (at, order): latency is the same for all
  std::vector<InMemoryLcm*> endpoints_;
  std::set<std::string> failing_, dropped_;
  std::vector<Record> history_;
  bool keep_history_ = true;
  HandlerGuard guard_;
};

class InMemoryLcm : public LcmInterface {
 public:
  ~InMemoryLcm() override;
  void publish(const std::string& channel, const uint8_t* data, std::size_t size) override;
  void subscribe(const std::string& channel, RawHandler handler) override;
  /// Delivers queued messages in order up to `deadline`, moving the bus clock to each; returns
  /// true as soon as one reached this endpoint, false (clock at `deadline`) when none did.
  bool handle_until(TimePoint deadline) override;
  TimePoint now() const override { return bus_.now(); }
  int64_t utime() const override { return bus_.utime(); }
  InMemoryBus& bus() { return bus_; }

 private:
  friend class InMemoryBus;
  explicit InMemoryLcm(InMemoryBus& bus) : bus_(bus) {}
  InMemoryBus& bus_;
  std::multimap<std::string, RawHandler> handlers_;
};

}  // namespace messages
