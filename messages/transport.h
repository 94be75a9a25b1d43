#pragma once
/// @file transport.h
/// The transport seam of every process that talks LCM (hybridsim, brfd-substructure,
/// brfd-rig): an abstract LcmInterface (publish, subscribe, handle with a deadline, the clock
/// the process runs on) with
///  - LcmTransport: liblcm (udpm/udp/memq URLs, the network rule of lcm_bus.h), the wall clock;
///  - InMemoryLcm (in_memory_lcm.h): a deterministic single-process fake on a simulated clock.
/// On top of the interface, in one place, the strict message helpers: publish_message()
/// checks every return code (encoded size, encode, publish) and throws; subscribe_message()
/// decodes strictly (a hash mismatch or truncation is a DecodeError naming the channel and the
/// type, handed to the subscriber's on_error or thrown).
///
/// Exceptions and liblcm: a handler never throws through liblcm's C dispatch. Every handler is
/// called inside a try block; the first exception is kept, and rethrown by handle_until()
/// after lcm_handle() has returned (later ones in the same dispatch are counted and dropped).
///
/// LoopActor + run_loop(): a control loop written as a state machine (advance at a time point,
/// say when it next needs to run); run_loop() drives it on any LcmInterface, and the fake's
/// scheduler (InMemoryBus::run) drives several of them on one simulated clock.

#include "messages/lcm_bus.h"

#include <chrono>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace messages {

using SteadyClock = std::chrono::steady_clock;
using TimePoint = SteadyClock::time_point;
using Duration = SteadyClock::duration;

/// Seconds as a steady-clock duration.
inline Duration seconds_to_duration(double s) {
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(s));
}
/// b - a in seconds.
inline double seconds_between(TimePoint a, TimePoint b) { return std::chrono::duration<double>(b - a).count(); }

/// Encoding failed (a message whose getEncodedSize/encode reports an error).
class EncodeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Bytes of one received message; valid only during the handler call.
struct RawMessage {
  const std::string& channel;
  const uint8_t* data;
  std::size_t size;
  int64_t receive_utime;  ///< when it arrived (microseconds, this transport's clock)
};

using RawHandler = std::function<void(const RawMessage&)>;

class LcmInterface {
 public:
  virtual ~LcmInterface() = default;

  /// Publishes `size` bytes on `channel`. Throws TransportError when the transport refuses.
  virtual void publish(const std::string& channel, const uint8_t* data, std::size_t size) = 0;
  /// Calls `handler` for every message on `channel` (an exact channel name).
  virtual void subscribe(const std::string& channel, RawHandler handler) = 0;
  /// Waits until a message arrives or `deadline` passes; dispatches what arrived. Returns true
  /// when at least one message was dispatched. Throws TransportError when the transport fails,
  /// and rethrows the first exception a handler threw during this dispatch.
  virtual bool handle_until(TimePoint deadline) = 0;
  /// The clock this process runs on (steady: the wall clock, or the fake's simulated clock).
  virtual TimePoint now() const = 0;
  /// Microseconds since the Unix epoch on this transport's clock (the utime of messages).
  virtual int64_t utime() const = 0;

  /// Dispatches every message already waiting, without waiting. Returns how many handle
  /// calls dispatched something.
  int drain() {
    int n = 0;
    while (handle_until(now())) ++n;
    return n;
  }
};

/// Runs every handler call inside a try block and keeps the first exception for rethrow once
/// the transport's dispatch has returned (shared by LcmTransport and InMemoryLcm).
class HandlerGuard {
 public:
  void call(const RawHandler& handler, const RawMessage& message) noexcept;
  /// Rethrows the kept exception (and forgets it). No-op when none.
  void rethrow_pending();
  /// Exceptions dropped because one was already pending.
  long dropped() const { return dropped_; }

 private:
  std::exception_ptr pending_;
  long dropped_ = 0;
};

/// liblcm behind LcmInterface: open_lcm's URL rules, steady wall clock, now_utime().
class LcmTransport : public LcmInterface {
 public:
  /// Opens `url` as open_lcm() does (refuses an empty URL and multicast outside a private
  /// network namespace unless lab_network). Throws TransportError.
  LcmTransport(const std::string& url, bool lab_network);
  ~LcmTransport() override;
  LcmTransport(const LcmTransport&) = delete;
  LcmTransport& operator=(const LcmTransport&) = delete;

  void publish(const std::string& channel, const uint8_t* data, std::size_t size) override;
  void subscribe(const std::string& channel, RawHandler handler) override;
  bool handle_until(TimePoint deadline) override;
  TimePoint now() const override { return SteadyClock::now(); }
  int64_t utime() const override { return now_utime(); }

  const std::string& url() const { return url_; }
  /// Undispatched messages kept per subscription (liblcm's default is 30; older ones are
  /// dropped beyond it).
  static constexpr int kQueueCapacity = 2048;
  /// The liblcm object, for what the interface does not cover (log files use their own API).
  lcm::LCM& raw() { return *lcm_; }

 private:
  struct Subscription;
  std::string url_;
  std::unique_ptr<lcm::LCM> lcm_;
  std::deque<Subscription> subscriptions_;
  HandlerGuard guard_;
};

/// Encodes `msg` into `buffer` (resized, so reserve it to keep a loop allocation-free) and
/// publishes it on `channel`. Throws EncodeError or TransportError naming the channel and type.
template <class T>
void publish_message(LcmInterface& lcm, const std::string& channel, const T& msg, std::vector<uint8_t>& buffer) {
  const int size = msg.getEncodedSize();
  if (size < 0) throw EncodeError("LCM channel '" + channel + "': cannot size a " + T::getTypeName());
  buffer.resize(static_cast<std::size_t>(size));
  if (msg.encode(buffer.data(), 0, size) != size)
    throw EncodeError("LCM channel '" + channel + "': cannot encode a " + T::getTypeName());
  lcm.publish(channel, buffer.data(), buffer.size());
}

/// The same with a buffer of its own (allocates).
template <class T>
void publish_message(LcmInterface& lcm, const std::string& channel, const T& msg) {
  std::vector<uint8_t> buffer;
  publish_message(lcm, channel, msg, buffer);
}

/// Decodes `data` into `msg` (reusing its storage). Throws DecodeError naming the channel and
/// the type (hash mismatch, truncated, or trailing bytes).
template <class T>
void decode_message(const RawMessage& m, T& msg) {
  int used = -1;
  try {
    used = msg.decode(m.data, 0, static_cast<int>(m.size));
  } catch (const std::exception&) {  // lcm-gen code: a negative string length, an impossible array
    used = -1;
  }
  if (used < 0 || static_cast<std::size_t>(used) != m.size) {
    throw DecodeError("LCM channel '" + m.channel + "': cannot decode a " + T::getTypeName() + " (" +
                      std::to_string(m.size) +
                      " bytes): type hash mismatch or truncated message; are both processes built from the "
                      "same messages/*.lcm?");
  }
}

/// The same for code that holds a liblcm ReceiveBuffer (one implementation: decode_message).
template <class T>
T decode(const lcm::ReceiveBuffer& buffer, const std::string& channel) {
  T msg;
  decode_message(RawMessage{channel, static_cast<const uint8_t*>(buffer.data), buffer.data_size, buffer.recv_utime}, msg);
  return msg;
}

/// Subscribes to `channel` with strict decoding into `scratch` (which must outlive the
/// subscription; reusing it keeps the receive path allocation-free), then calls
/// `on_message(scratch, message)`. A message that does not decode goes to `on_error` with the
/// DecodeError (nullptr: the DecodeError is thrown, i.e. rethrown by handle_until).
template <class T>
void subscribe_message(LcmInterface& lcm, const std::string& channel, T& scratch,
                       std::function<void(T&, const RawMessage&)> on_message,
                       std::function<void(const DecodeError&, const RawMessage&)> on_error = nullptr) {
  lcm.subscribe(channel, [&scratch, on_message = std::move(on_message), on_error = std::move(on_error)](const RawMessage& m) {
    try {
      decode_message(m, scratch);
    } catch (const DecodeError& e) {
      if (!on_error) throw;
      on_error(e, m);
      return;
    }
    on_message(scratch, m);
  });
}

/// A control loop as a state machine: advance() does what is due at `now`; next_deadline()
/// says when it next needs to run if no message comes first; finished() ends the loop.
class LoopActor {
 public:
  virtual ~LoopActor() = default;
  virtual void advance(TimePoint now) = 0;
  virtual TimePoint next_deadline(TimePoint now) const = 0;
  virtual bool finished() const = 0;
};

/// The process loop: advance, then handle messages until the actor's next deadline, until
/// finished(). Exceptions from handlers and the transport propagate to the caller.
void run_loop(LcmInterface& lcm, LoopActor& actor);

}  // namespace messages
