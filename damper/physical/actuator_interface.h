#pragma once
/// @file actuator_interface.h
/// The physical substructure's link to the lab controller (or brfd-rig): actuator commands
/// out on <prefix>ACTUATOR_COMMAND, sensor frames in on <prefix>SENSOR_FRAME
/// (docs/physical.md, "Lab-side protocol").
///
/// send() is the only way a command leaves this process, and it runs the safety layer
/// first: a setpoint that fails a limit is never encoded, signed or published. Times (frame
/// arrival, command utime) come from the transport's clock, so it runs on the in-memory fake
/// (messages/in_memory_lcm.h) exactly as on liblcm.

#include "damper/physical/command_auth.h"
#include "messages/bad_message_log.h"
#include "messages/message_auth.h"
#include "damper/physical/safety.h"
#include "damper/physical/tracking.h"
#include "hybrid_lcm/actuator_command_t.hpp"
#include "hybrid_lcm/sensor_frame_t.hpp"
#include "messages/lcm_bus.h"
#include "messages/transport.h"

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace damper::physical {

class ActuatorInterface {
 public:
  using TimePoint = messages::TimePoint;

  /// Subscribes to the sensor frames of `channels` on `lcm`; a frame is taken only when its
  /// HMAC verifies under `key` and its sequence is above the last taken one.
  ActuatorInterface(messages::LcmInterface& lcm, const messages::Channels& channels, const RunKey& key, SafetyLayer& safety);
  ActuatorInterface(const ActuatorInterface&) = delete;
  ActuatorInterface& operator=(const ActuatorInterface&) = delete;

  /// Commands carry this run id; frames of other runs are ignored. Frames with an empty run
  /// id (a controller that has accepted no command yet) are taken until the first frame with
  /// our run id arrives.
  void set_run_id(const std::string& run_id);

  /// Safety check, then sign and publish with the next sequence number. Returns false (and
  /// publishes nothing) when the safety layer refuses the setpoint; `why` says which limit.
  bool send(const ActuatorSetpoint& sp, int8_t mode, std::string& why);

  int64_t last_sequence() const { return sequence_; }
  long commands_sent() const { return sent_; }

  /// Sensor frames received so far, the newest one and when it arrived.
  long frames_received() const { return frames_; }
  const hybrid_lcm::sensor_frame_t& latest_frame() const { return frame_; }
  TimePoint last_frame_time() const { return last_frame_time_; }
  /// Longest time between two consecutive frames since reset_frame_gap() (s).
  double max_frame_gap_s() const { return max_gap_s_; }
  void reset_frame_gap() { max_gap_s_ = 0.0; }
  /// Frames dropped: undecodable, foreign run, bad HMAC or replayed (sequence not above the
  /// last accepted frame's), each counted by kind in bad_messages() ("SENSOR_FRAME/bad_mac").
  long bad_frames() const { return bad_frames_; }
  /// Where dropped frames are counted (the node's log; default: one of its own).
  void count_bad_frames_in(messages::BadMessageLog* log) { bad_ = log ? log : &own_bad_; }
  const messages::BadMessageLog& bad_messages() const { return *bad_; }

  /// From now on every frame taken is appended to `sink` (period number, command in force,
  /// measured drum displacement) while it has capacity: the loop never allocates, so reserve
  /// first. nullptr stops recording. This is the controller-clock record of tracking.h.
  void record_frames(std::vector<FrameSample>* sink) { frame_sink_ = sink; }

 private:
  void on_frame(const messages::RawMessage& raw);

  messages::LcmInterface& lcm_;
  messages::Channels channels_;
  CommandSigner signer_;
  messages::MessageAuth frame_auth_;
  messages::BadMessageLog own_bad_{"brfd-substructure"};
  messages::BadMessageLog* bad_ = &own_bad_;
  int64_t last_frame_sequence_ = 0;
  bool any_frame_ = false;
  SafetyLayer& safety_;
  hybrid_lcm::actuator_command_t command_;
  std::vector<uint8_t> buffer_;
  int64_t sequence_ = 0;
  long sent_ = 0;
  hybrid_lcm::sensor_frame_t frame_, scratch_;
  long frames_ = 0;
  long bad_frames_ = 0;
  double max_gap_s_ = 0.0;
  bool bound_ = false;
  std::vector<FrameSample>* frame_sink_ = nullptr;
  TimePoint last_frame_time_{};
};

}  // namespace damper::physical
