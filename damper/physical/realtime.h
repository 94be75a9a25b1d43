#pragma once
/// @file realtime.h
/// Helpers of the 1024 Hz loops of brfd-substructure (physical mode) and brfd-rig.

#include <poll.h>
#include <sched.h>
#include <sys/mman.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <iostream>
#include <string>

namespace damper::physical {

/// Switches the calling process to SCHED_FIFO at `priority` (1..99) and locks its memory, so
/// compile jobs or other load on the machine do not delay the control loop by milliseconds.
/// 0 does nothing. Without the privilege it says so on stderr and carries on.
inline void enter_realtime(int priority, const std::string& who) {
  if (priority <= 0) return;
  sched_param sp{};
  sp.sched_priority = priority;
  if (sched_setscheduler(0, SCHED_FIFO, &sp) != 0) {
    std::cerr << who << ": note: cannot use SCHED_FIFO priority " << priority << " (" << std::strerror(errno)
              << "); running at normal priority, expect more timing jitter\n";
    return;
  }
  mlockall(MCL_CURRENT | MCL_FUTURE);
}

/// Waits until `fd` is readable or `timeout` passes (sub-millisecond resolution). Returns
/// true when readable.
inline bool wait_readable(int fd, std::chrono::nanoseconds timeout) {
  if (timeout.count() < 0) timeout = std::chrono::nanoseconds(0);
  pollfd p{fd, POLLIN, 0};
  timespec ts{static_cast<time_t>(timeout.count() / 1000000000), static_cast<long>(timeout.count() % 1000000000)};
  const int r = ppoll(&p, 1, &ts, nullptr);
  return r > 0 && (p.revents & POLLIN);
}

}  // namespace damper::physical
