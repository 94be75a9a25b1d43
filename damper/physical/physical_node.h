#pragma once
/// @file physical_node.h
/// `brfd-substructure --mode physical`: the physical BRFD substructure. Towards the server it
/// speaks the same protocol as the virtual one (run_control_t, heartbeat_t, one
/// force_feedback_t per drift_command_t): the server does not know whether a model or a rig
/// answered. Towards the lab controller (or brfd-rig) it publishes authenticated
/// actuator_command_t at the controller rate and consumes sensor_frame_t
/// (docs/physical.md).
///
/// One step: drift command k (target drum displacement) -> drift limit -> ATS compensation
/// -> excitation ramp-in -> safety layer -> signed command -> the next sensor frame ->
/// actuator force and tracking checks -> force_feedback_t with the MEASURED friction force and
/// drum displacement. The controller's frames pace the loop, so the run proceeds in real time.
///
/// Lifecycle: START -> wait for the rig's frames -> positioning ramp to the start position
/// (the rig must accept our commands) -> READY -> steps -> STOP: ramp-out to the safe state.
/// On a trip (any limit or watchdog): answer the step with STATUS_SAFETY_TRIP and the reason,
/// hold, ramp to the safe state, exit 4. On ABORT from the server: hold, ramp, exit 3.
///
/// Results (in results_dir): physical.csv (every step), tracking.json (tracking indicators,
/// ATS coefficients), safety.json (limits in force, trip reason and step).

#include "damper/model/brfd_model.h"
#include "damper/physical/physical_config.h"
#include "messages/lcm_bus.h"

#include <string>

namespace damper::physical {

struct PhysicalNodeOptions {
  std::string url;                  ///< LCM URL (the server's transport.url)
  bool lab_network = false;
  messages::Channels channels;
  std::string run_id;               ///< answer only this run ("" = adopt the first START)
  BrfdParams model;                 ///< x'_1, x'_2: electric actuator hold positions
  PhysicalSettings settings;
  std::string key_file;             ///< HMAC key (run_key.h)
  std::string results_dir;          ///< where physical.csv, tracking.json, safety.json go ("" = none)
  double heartbeat_period_s = 0.2;
  double start_watchdog_s = 120.0;  ///< exit 1 if no START arrives this long
};

/// Exit codes: 0 orderly stop, 1 watchdog before start / transport error, 2 bad input or the
/// rig refuses us, 3 aborted by the server, 4 safety trip.
int run_physical_substructure(const PhysicalNodeOptions& options);

}  // namespace damper::physical
