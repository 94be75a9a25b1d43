#include "damper/physical/actuator_interface.h"

#include <algorithm>
#include <iostream>
#include <utility>

namespace damper::physical {

ActuatorInterface::ActuatorInterface(messages::LcmInterface& lcm, const messages::Channels& channels, const RunKey& key,
                                     SafetyLayer& safety)
    : lcm_(lcm), channels_(channels), signer_(key), frame_auth_(key), safety_(safety) {
  command_.hmac.reserve(32);
  command_.run_id.reserve(128);
  frame_.run_id.reserve(128);
  frame_.last_rejection.reserve(256);
  scratch_ = frame_;
  buffer_.reserve(512);
  lcm_.subscribe(channels_.sensor_frame(), [this](const messages::RawMessage& raw) { on_frame(raw); });
}

void ActuatorInterface::set_run_id(const std::string& run_id) { command_.run_id = run_id; }

bool ActuatorInterface::send(const ActuatorSetpoint& sp, int8_t mode, std::string& why) {
  if (!safety_.command_ok(sp, why)) return false;  // never reaches the actuators
  command_.utime = lcm_.utime();
  command_.sequence = ++sequence_;
  command_.drum_displacement_in = sp.drum_in;
  command_.actuator1_position_in = sp.actuator1_in;
  command_.actuator2_position_in = sp.actuator2_in;
  command_.mode = mode;
  signer_.sign(command_);
  try {
    messages::publish_message(lcm_, channels_.actuator_command(), command_, buffer_);
  } catch (const std::exception& e) {  // never published: the caller trips on it
    why = e.what();
    return false;
  }
  safety_.published(sp);
  ++sent_;
  return true;
}

void ActuatorInterface::on_frame(const messages::RawMessage& raw) {
  // Frames of another run are dropped (counted); so are frames without a run id (a controller
  // that has not accepted any command yet) once our controller has answered with our run id.
  std::string detail;
  bool ours_and_named = false;
  const messages::Received r = messages::check_and_decode(
      raw, frame_auth_,
      [&](const std::string& id) {
        ours_and_named = !command_.run_id.empty() && id == command_.run_id;
        return command_.run_id.empty() || ours_and_named || (id.empty() && !bound_);
      },
      scratch_, detail);
  if (r != messages::Received::ok) {  // undecodable, another run's, forged or signed with another key
    ++bad_frames_;
    bad_->report(std::string("SENSOR_FRAME/") + messages::to_string(r), detail, false);
    return;
  }
  if (ours_and_named) bound_ = true;
  if (any_frame_ && scratch_.sequence <= last_frame_sequence_) {
    ++bad_frames_;
    bad_->report("SENSOR_FRAME/replayed",
                 "frame sequence " + std::to_string(scratch_.sequence) + " <= last taken " +
                     std::to_string(last_frame_sequence_),
                 false);
    return;
  }
  any_frame_ = true;
  last_frame_sequence_ = scratch_.sequence;
  std::swap(frame_, scratch_);
  const TimePoint now = lcm_.now();
  if (frames_ > 0) max_gap_s_ = std::max(max_gap_s_, std::chrono::duration<double>(now - last_frame_time_).count());
  ++frames_;
  last_frame_time_ = now;
  if (frame_sink_ && frame_sink_->size() < frame_sink_->capacity()) {
    frame_sink_->push_back({frame_.sequence, frame_.command_sequence, frame_.drum_displacement_in});
  }
}

}  // namespace damper::physical
