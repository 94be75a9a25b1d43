#include "messages/in_memory_lcm.h"

#include <algorithm>
#include <stdexcept>

namespace messages {

namespace {
constexpr int64_t kEpochUtime = 1767225600LL * 1000000LL;  // 2026-01-01T00:00:00Z
}

InMemoryBus::InMemoryBus(Duration latency) : latency_(latency), now_(TimePoint{} + std::chrono::seconds(1)) {}

InMemoryBus::~InMemoryBus() = default;

std::unique_ptr<InMemoryLcm> InMemoryBus::endpoint() {
  std::unique_ptr<InMemoryLcm> e(new InMemoryLcm(*this));
  endpoints_.push_back(e.get());
  return e;
}

void InMemoryBus::detach(InMemoryLcm* endpoint) {
  endpoints_.erase(std::remove(endpoints_.begin(), endpoints_.end(), endpoint), endpoints_.end());
}

int64_t InMemoryBus::utime() const {
  return kEpochUtime + std::chrono::duration_cast<std::chrono::microseconds>(now_ - TimePoint{}).count();
}

void InMemoryBus::advance_to(TimePoint t) {
  if (t > now_) now_ = t;
}

TimePoint InMemoryBus::next_delivery() const { return queue_.empty() ? TimePoint::max() : queue_.front().at; }

void InMemoryBus::publish(const std::string& channel, const uint8_t* data, std::size_t size) {
  if (failing_.count(channel)) throw TransportError("LCM publish failed on channel '" + channel + "' (in-memory bus, injected)");
  if (keep_history_) history_.push_back(Record{now_, channel, std::vector<uint8_t>(data, data + size)});
  if (dropped_.count(channel)) return;
  queue_.push_back(Pending{now_ + latency_, order_++, channel, std::vector<uint8_t>(data, data + size)});
  // Latency may have been changed between publishes: keep the queue ordered by delivery time.
  if (queue_.size() > 1 && queue_[queue_.size() - 2].at > queue_.back().at) {
    std::stable_sort(queue_.begin(), queue_.end(),
                     [](const Pending& a, const Pending& b) { return a.at < b.at || (a.at == b.at && a.order < b.order); });
  }
}

bool InMemoryBus::deliver_one(InMemoryLcm* wanted) {
  Pending p = std::move(queue_.front());
  queue_.pop_front();
  bool reached_wanted = false, reached_any = false;
  const std::vector<InMemoryLcm*> endpoints = endpoints_;  // a handler may create endpoints
  for (InMemoryLcm* e : endpoints) {
    auto range = e->handlers_.equal_range(p.channel);
    for (auto it = range.first; it != range.second; ++it) {
      const RawMessage m{p.channel, p.bytes.data(), p.bytes.size(), utime()};
      guard_.call(it->second, m);
      reached_any = true;
      if (e == wanted) reached_wanted = true;
    }
  }
  return wanted ? reached_wanted : reached_any;
}

int InMemoryBus::deliver_due() {
  int n = 0;
  while (!queue_.empty() && queue_.front().at <= now_) n += deliver_one(nullptr) ? 1 : 0;
  guard_.rethrow_pending();
  return n;
}

bool InMemoryBus::run(const std::vector<LoopActor*>& actors, const std::function<bool()>& done, TimePoint limit) {
  bool advanced_at_now = false;  // the actors already ran at now_
  while (!done()) {
    TimePoint t = next_delivery();
    TimePoint actor_t = TimePoint::max();
    for (LoopActor* a : actors)
      if (!a->finished()) actor_t = std::min(actor_t, a->next_deadline(now_));
    // An actor that ran at now_ and asks for now_ again is waiting for time to pass (on the
    // wall clock its loop would spin until it does): give it the next microsecond.
    if (advanced_at_now && actor_t <= now_) actor_t = now_ + std::chrono::microseconds(1);
    t = std::min(t, actor_t);
    if (t > limit) {
      advance_to(limit);
      return done();
    }
    if (t > now_) {
      now_ = t;
      advanced_at_now = false;
    }
    deliver_due();
    for (LoopActor* a : actors)
      if (!a->finished()) a->advance(now_);
    advanced_at_now = true;
  }
  return true;
}

void InMemoryBus::fail_publishes(const std::string& channel, bool fail) {
  if (fail) failing_.insert(channel);
  else failing_.erase(channel);
}

void InMemoryBus::drop_channel(const std::string& channel, bool drop) {
  if (drop) dropped_.insert(channel);
  else dropped_.erase(channel);
}

InMemoryLcm::~InMemoryLcm() { bus_.detach(this); }

void InMemoryLcm::publish(const std::string& channel, const uint8_t* data, std::size_t size) {
  bus_.publish(channel, data, size);
}

void InMemoryLcm::subscribe(const std::string& channel, RawHandler handler) {
  handlers_.emplace(channel, std::move(handler));
}

bool InMemoryLcm::handle_until(TimePoint deadline) {
  for (;;) {
    const TimePoint t = bus_.next_delivery();
    if (t > deadline) {
      bus_.advance_to(deadline);
      return false;
    }
    bus_.advance_to(t);
    const bool got = bus_.deliver_one(this);
    bus_.guard_.rethrow_pending();
    if (got) return true;
  }
}

}  // namespace messages
