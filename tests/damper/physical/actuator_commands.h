#pragma once
// An actuator command of a running test (MODE_RUN, the actuators at x'_1 = 0.655 in and
// x'_2 = 0.8559 in of the damper model), the one the authentication tests sign, forge and
// replay (auth_test.cc, system_test.cc and its simulated-clock twin sim_system_test.cc).
#include "hybrid_lcm/actuator_command_t.hpp"

#include <cstdint>
#include <string>

namespace actuator_commands {

inline hybrid_lcm::actuator_command_t run_command(const std::string& run_id, int64_t sequence, int64_t utime,
                                                  double drum_displacement_in) {
  hybrid_lcm::actuator_command_t c;
  c.utime = utime;
  c.run_id = run_id;
  c.sequence = sequence;
  c.drum_displacement_in = drum_displacement_in;
  c.actuator1_position_in = 0.655;
  c.actuator2_position_in = 0.8559;
  c.mode = hybrid_lcm::actuator_command_t::MODE_RUN;
  return c;
}

}  // namespace actuator_commands
