#include "messages/transport.h"

#include <poll.h>

#include <cerrno>
#include <cstring>

namespace messages {

void HandlerGuard::call(const RawHandler& handler, const RawMessage& message) noexcept {
  try {
    handler(message);
  } catch (...) {
    if (pending_) ++dropped_;
    else pending_ = std::current_exception();
  }
}

void HandlerGuard::rethrow_pending() {
  if (!pending_) return;
  std::exception_ptr e = pending_;
  pending_ = nullptr;
  std::rethrow_exception(e);
}

struct LcmTransport::Subscription {
  LcmTransport* owner;
  RawHandler handler;
  void on_message(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    // Called by liblcm's C dispatch: nothing may escape (HandlerGuard::call is noexcept).
    const RawMessage m{channel, static_cast<const uint8_t*>(rbuf->data), rbuf->data_size, rbuf->recv_utime};
    owner->guard_.call(handler, m);
  }
};

LcmTransport::LcmTransport(const std::string& url, bool lab_network) : url_(url), lcm_(open_lcm(url, lab_network)) {}

LcmTransport::~LcmTransport() = default;

void LcmTransport::publish(const std::string& channel, const uint8_t* data, std::size_t size) {
  if (lcm_->publish(channel, data, static_cast<unsigned>(size)) != 0) {
    throw TransportError("LCM publish failed on channel '" + channel + "' (URL " + url_ + ")");
  }
}

void LcmTransport::subscribe(const std::string& channel, RawHandler handler) {
  subscriptions_.push_back(Subscription{this, std::move(handler)});
  lcm::Subscription* s = lcm_->subscribe(channel, &Subscription::on_message, &subscriptions_.back());
  if (!s) {
    subscriptions_.pop_back();
    throw TransportError("LCM subscribe failed on channel '" + channel + "' (URL " + url_ + ")");
  }
  // liblcm keeps at most 30 undispatched messages per subscription by default and drops the
  // rest silently: a process descheduled for ~30 ms at 1024 messages/s (or a flood on a shared
  // channel) loses messages. Keep up to kQueueCapacity (2 s of 1024 Hz traffic) instead.
  if (s->setQueueCapacity(kQueueCapacity) != 0) {
    throw TransportError("LCM: cannot set the queue capacity of channel '" + channel + "' (URL " + url_ + ")");
  }
}

bool LcmTransport::handle_until(TimePoint deadline) {
  auto left = deadline - SteadyClock::now();
  if (left < Duration::zero()) left = Duration::zero();
  const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(left).count();
  pollfd p{lcm_->getFileno(), POLLIN, 0};
  timespec ts{static_cast<time_t>(ns / 1000000000), static_cast<long>(ns % 1000000000)};
  const int r = ppoll(&p, 1, &ts, nullptr);
  if (r < 0) {
    if (errno == EINTR) return false;  // a signal: the caller's loop decides
    throw TransportError("LCM: poll on the file descriptor of URL " + url_ + " failed: " + std::strerror(errno));
  }
  if (r == 0 || !(p.revents & POLLIN)) return false;
  if (lcm_->handle() != 0) throw TransportError("LCM handle failed on URL " + url_);
  guard_.rethrow_pending();
  return true;
}

void run_loop(LcmInterface& lcm, LoopActor& actor) {
  while (!actor.finished()) {
    actor.advance(lcm.now());
    if (actor.finished()) break;
    lcm.handle_until(actor.next_deadline(lcm.now()));
  }
}

}  // namespace messages
