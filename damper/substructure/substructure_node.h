#pragma once
/// @file substructure_node.h
/// The LCM side of `brfd-substructure`: answers each drift_command_t of its run with one
/// force_feedback_t, publishes heartbeats, follows run_control_t (start/stop/abort).
/// Virtual mode steps a BrfdModel per damper; echo mode answers at once with zero force
/// (the raw LCM round trip of `hybridsim bench`).

#include "damper/model/brfd_model.h"
#include "messages/lcm_bus.h"

#include <string>

namespace damper {

struct SubstructureNodeOptions {
  std::string url;                   ///< LCM URL (required; from the server config)
  bool lab_network = false;          ///< allow multicast outside a private network namespace
  messages::Channels channels;
  std::string run_id;                ///< answer only this run ("" = adopt the first START)
  bool echo = false;                 ///< answer with zero force, no model (benchmark)
  BrfdParams model;                  ///< virtual damper model
  double max_drum_displacement_in = 12.0;    ///< commands beyond this are refused (fault)
  double max_drum_velocity_in_per_s = 200.0; ///< commands beyond this are refused (fault)
  double command_watchdog_s = 30.0;  ///< exit with an error if a started run goes silent this long
  double heartbeat_period_s = 0.2;
};

/// Runs until STOP (returns 0), ABORT (returns 3) or a watchdog/transport error (returns 1).
/// Messages that cannot be decoded are reported on stderr naming the channel.
int run_substructure_node(const SubstructureNodeOptions& options);

}  // namespace damper
