#pragma once
// The safety trips both physical system tests check, one per limit (rig.limits.<key>): the
// real-time run over LCM (system_test.cc) and the same scenario on the simulated clock
// (sim_system_test.cc). One table, so the two stay the same cases.
#include <gtest/gtest.h>

#include <string>

namespace trip_cases {

struct TripCase {
  const char* name;
  const char* limit_key;  // rig.limits.<key>
  double value;
  bool ats;
};

/// The rig's own stroke and command-rate limits (in, in/s): the case's value for its key, else
/// 2 in and 20 in/s. The rig enforces them too, so its count of out-of-limit commands received
/// is a second, independent proof.
inline double rig_stroke_in(const TripCase& tc) { return std::string(tc.limit_key) == "stroke_in" ? tc.value : 2.0; }
inline double rig_rate_in_per_s(const TripCase& tc) {
  return std::string(tc.limit_key) == "velocity_in_per_s" ? tc.value : 20.0;
}

/// Every limit once (ATS on, except for the tracking limit).
inline auto all() {
  return ::testing::Values(TripCase{"stroke", "stroke_in", 0.3, true},
                           TripCase{"command_rate", "velocity_in_per_s", 3.0, true},
                           TripCase{"actuator_force", "actuator_force_lb", 800.0, true},
                           TripCase{"drift", "drift_in", 0.3, true},
                           TripCase{"tracking", "tracking_error_in", 0.03, false});
}

inline std::string name(const ::testing::TestParamInfo<TripCase>& info) { return info.param.name; }

}  // namespace trip_cases
