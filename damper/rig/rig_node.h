#pragma once
/// @file rig_node.h
/// brfd-rig: plays the lab controller of the BRFD over LCM (docs/physical.md, "Lab-side
/// protocol"). At rate_hz it publishes one sensor_frame_t (from RigSimulator, or from a
/// measured test file in replay mode) and takes the newest accepted actuator_command_t as its
/// target. Every command received is checked (HMAC, run, sequence, age: CommandGate; then
/// the rig's own hardware limits) and logged, accepted or not, to rig-commands.csv; rejections
/// are counted in each frame (rejected_commands, last_rejection). On exit (a MODE_END
/// command, no command for idle_exit_s, SIGTERM) it writes rig-summary.json.

#include "damper/rig/rig_config.h"
#include "messages/lcm_bus.h"

#include <string>

namespace damper::rig {

struct RigNodeOptions {
  std::string url;
  bool lab_network = false;
  messages::Channels channels;
  std::string run_id;          ///< accept only this run's commands ("" = the first authentic one's)
  std::string key_file;        ///< HMAC key (damper/physical/run_key.h)
  std::string log_dir;         ///< rig-commands.csv, rig-summary.json, rig-config.yaml ("" = none)
  RigConfig config;
};

/// Runs until a MODE_END command, idle_exit_s without commands, or SIGTERM/SIGINT (exit 0),
/// or start_timeout_s without any command (exit 1).
int run_rig(const RigNodeOptions& options);

}  // namespace damper::rig
