#include "damper/physical/actuator_interface.h"

#include <algorithm>
#include <iostream>
#include <utility>

namespace damper::physical {

ActuatorInterface::ActuatorInterface(lcm::LCM& lcm, const messages::Channels& channels, const RunKey& key,
                                     SafetyLayer& safety)
    : lcm_(lcm), channels_(channels), signer_(key), safety_(safety) {
  command_.hmac.reserve(32);
  command_.run_id.reserve(128);
  frame_.run_id.reserve(128);
  frame_.last_rejection.reserve(256);
  scratch_ = frame_;
  buffer_.reserve(512);
  lcm_.subscribe(channels_.sensor_frame(), &ActuatorInterface::on_frame, this);
}

void ActuatorInterface::set_run_id(const std::string& run_id) { command_.run_id = run_id; }

bool ActuatorInterface::send(const ActuatorSetpoint& sp, int8_t mode, std::string& why) {
  if (!safety_.command_ok(sp, why)) return false;  // never reaches the actuators
  command_.utime = messages::now_utime();
  command_.sequence = ++sequence_;
  command_.drum_displacement_in = sp.drum_in;
  command_.actuator1_position_in = sp.actuator1_in;
  command_.actuator2_position_in = sp.actuator2_in;
  command_.mode = mode;
  signer_.sign(command_);
  const int size = command_.getEncodedSize();
  buffer_.resize(static_cast<std::size_t>(size));
  command_.encode(buffer_.data(), 0, size);
  if (lcm_.publish(channels_.actuator_command(), buffer_.data(), static_cast<unsigned>(size)) != 0) {
    why = "LCM publish failed on channel '" + channels_.actuator_command() + "'";
    return false;
  }
  safety_.published(sp);
  ++sent_;
  return true;
}

void ActuatorInterface::on_frame(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
  if (scratch_.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) < 0) {
    if (bad_frames_++ < 5) {
      std::cerr << "brfd-substructure: LCM channel '" << channel << "': cannot decode a "
                << hybrid_lcm::sensor_frame_t::getTypeName()
                << ": type hash mismatch or truncated message; is the lab bridge built from the same "
                   "messages/sensor_frame_t.lcm?\n";
    }
    return;
  }
  // Frames of another run are ignored; so are frames without a run id (a controller that has
  // not accepted any command yet) once our controller has answered with our run id.
  if (!command_.run_id.empty()) {
    if (scratch_.run_id == command_.run_id) bound_ = true;
    else if (!scratch_.run_id.empty() || bound_) return;
  }
  std::swap(frame_, scratch_);
  const Clock::time_point now = Clock::now();
  if (frames_ > 0) max_gap_s_ = std::max(max_gap_s_, std::chrono::duration<double>(now - last_frame_time_).count());
  ++frames_;
  last_frame_time_ = now;
  if (frame_sink_ && frame_sink_->size() < frame_sink_->capacity()) {
    frame_sink_->push_back({frame_.sequence, frame_.command_sequence, frame_.drum_displacement_in});
  }
}

}  // namespace damper::physical
