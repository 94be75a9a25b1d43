#pragma once
/// @file lcm_bus.h
/// LCM plumbing shared by hybridsim, brfd-substructure and brfd-rig:
///  - the errors of the transport (DecodeError, TransportError; strict decoding itself is
///    messages::decode_message in transport.h),
///  - the network rule: udpm traffic only inside a private network namespace unless the
///    config says the URL is a lab network (see ../shared/docs/lcm-transport.md),
///  - the channel names of one run.

#include <lcm/lcm-cpp.hpp>

#include <memory>
#include <stdexcept>
#include <string>

namespace messages {

/// A message on `channel` could not be decoded (schema/hash mismatch or truncated).
class DecodeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A transport problem (URL refused, no network namespace, provider failure).
class TransportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Strict decoding and publishing live in messages/transport.h (decode_message, decode,
// subscribe_message, publish_message): one place for every process.

/// True when this process's network namespace has no device but loopback, i.e. multicast
/// cannot leave the machine.
bool in_private_network_namespace();

/// Moves this process (and the children it starts later) into a new network namespace with
/// only the loopback device up and 239.0.0.0/8 routed to it, the isolation that
/// ../shared/docs/lcm-transport.md describes. Needs root, or unprivileged user namespaces.
/// Throws TransportError saying what failed.
void enter_private_network_namespace();

/// Opens LCM on an explicit URL. Refuses an empty URL (LCM would fall back to its default
/// multicast address), and refuses udpm/mpudpm outside a private network namespace unless
/// `lab_network` is true (set by a lab in its config). Throws TransportError.
std::unique_ptr<lcm::LCM> open_lcm(const std::string& url, bool lab_network);

/// Channel names of one run: <prefix> + fixed suffix. Batch runs use distinct prefixes.
struct Channels {
  std::string prefix = "BRFD_";
  std::string drift_command() const { return prefix + "DRIFT_COMMAND"; }
  std::string force_feedback() const { return prefix + "FORCE_FEEDBACK"; }
  std::string heartbeat() const { return prefix + "HEARTBEAT"; }
  std::string run_control() const { return prefix + "RUN_CONTROL"; }
  std::string actuator_command() const { return prefix + "ACTUATOR_COMMAND"; }
  std::string sensor_frame() const { return prefix + "SENSOR_FRAME"; }
};

/// Microseconds since the Unix epoch (the utime of every message).
int64_t now_utime();

}  // namespace messages
