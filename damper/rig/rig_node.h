#pragma once
/// @file rig_node.h
/// brfd-rig: plays the lab controller of the BRFD over LCM (docs/physical.md, "Lab-side
/// protocol"). At rate_hz it publishes one sensor_frame_t (from RigSimulator, or from a
/// measured test file in replay mode) and takes the newest accepted actuator_command_t as its
/// target. Every command received is checked (HMAC, run, sequence, age: CommandGate; then
/// the rig's own hardware limits) and logged, accepted or not, to rig-commands.csv; rejections
/// are counted in each frame (rejected_commands, last_rejection). On exit (a MODE_END
/// command, no command for idle_exit_s, SIGTERM) it writes rig-summary.json.

#include "damper/physical/command_auth.h"
#include "messages/run_key.h"
#include "damper/rig/rig_config.h"
#include "damper/rig/rig_simulator.h"
#include "hybrid_lcm/actuator_command_t.hpp"
#include "hybrid_lcm/sensor_frame_t.hpp"
#include "messages/lcm_bus.h"
#include "messages/transport.h"

#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace damper {
struct BrfdTest;
}

namespace damper::rig {

struct RigNodeOptions {
  std::string url;
  bool lab_network = false;
  messages::Channels channels;
  std::string run_id;          ///< accept only this run's commands ("" = the first authentic one's)
  std::string key_file;        ///< HMAC key (messages/run_key.h)
  std::string log_dir;         ///< rig-commands.csv, rig-summary.json, rig-config.yaml ("" = none)
  RigConfig config;
};

/// The controller loop as a messages::LoopActor on any messages::LcmInterface: run_rig()
/// drives it on liblcm at rate_hz of wall-clock time; tests drive it on the in-memory fake
/// (messages/in_memory_lcm.h), where a period is simulated time.
class RigNode : public messages::LoopActor {
 public:
  using TimePoint = messages::TimePoint;
  /// Reads the key file and the replay file (throws naming them), opens the log.
  RigNode(messages::LcmInterface& lcm, const RigNodeOptions& options);
  RigNode(messages::LcmInterface& lcm, const RigNodeOptions& options, const physical::RunKey& key);
  ~RigNode() override;
  RigNode(const RigNode&) = delete;
  RigNode& operator=(const RigNode&) = delete;

  void advance(TimePoint now) override;
  TimePoint next_deadline(TimePoint) const override { return next_tick_; }
  bool finished() const override;

  /// Ends the loop as SIGTERM does (exit 0, reason "signal").
  void request_stop() { stop_requested_ = true; }
  /// The transport failed: end the loop with exit 1.
  void transport_failed(const std::string& why);
  /// Writes rig-summary.json, prints the exit line, returns the exit code.
  int finish();

  const RigSimulator& simulator() const { return sim_; }
  const hybrid_lcm::sensor_frame_t& last_frame() const { return frame_; }
  long frames() const { return frames_; }
  long commands_received() const { return received_; }
  long commands_accepted() const { return accepted_; }
  long commands_rejected() const { return rejected_; }
  long out_of_limit_received() const { return out_of_limit_received_; }
  const std::map<std::string, long>& rejected_by_kind() const { return by_kind_; }

 private:
  void on_command(const hybrid_lcm::actuator_command_t& cmd, int64_t rx_utime);
  void on_undecodable(const std::string& what, int64_t rx_utime);
  void on_forged(std::size_t bytes, int64_t rx_utime);
  bool within_limits(const hybrid_lcm::actuator_command_t& c, std::string& why) const;
  void reject(const std::string& why);
  void log_row(int64_t rx, const hybrid_lcm::actuator_command_t* c, const char* verdict, int within);
  void tick();
  void write_summary();

  messages::LcmInterface& lcm_;
  RigNodeOptions o_;
  RigConfig c_;
  double period_;
  physical::CommandGate gate_;
  messages::MessageAuth frame_auth_;  ///< signs the sensor frames (messages/message_auth.h)
  RigSimulator sim_;
  std::unique_ptr<damper::BrfdTest> replay_;
  std::size_t replay_index_ = 0;
  RigCommand target_;
  hybrid_lcm::actuator_command_t cmd_;
  hybrid_lcm::sensor_frame_t frame_;
  std::vector<uint8_t> buffer_;
  std::FILE* log_ = nullptr;
  std::string why_;
  std::string exit_reason_ = "?";
  bool end_requested_ = false, stop_requested_ = false, done_ = false;
  int code_ = 0;
  TimePoint started_{}, next_tick_{}, last_accepted_{};
  long received_ = 0, accepted_ = 0, rejected_ = 0, out_of_limit_received_ = 0, frames_ = 0, overruns_ = 0;
  int64_t last_sequence_ = 0;
  double max_lateness_s_ = 0.0;
  long max_lateness_frame_ = 0;
  double max_abs_drum_received_ = 0.0, max_abs_drum_accepted_ = 0.0, max_rate_accepted_ = 0.0;
  std::map<std::string, long> by_kind_;
};

/// Runs until a MODE_END command, idle_exit_s without commands, or SIGTERM/SIGINT (exit 0),
/// or start_timeout_s without any command (exit 1).
int run_rig(const RigNodeOptions& options);

}  // namespace damper::rig
