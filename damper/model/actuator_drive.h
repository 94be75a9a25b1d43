#pragma once
/// @file actuator_drive.h
/// The electric actuators of a DamperBank (damper/model/damper_model.h) under semi-active
/// control: per damper two ElectricActuator (damper/model/electric_actuator.h: stroke, velocity
/// limit, lag) follow the controller's position targets, and the positions they reach are set
/// on the bank as the x_1, x_2 of Eq. (4). Without targets the bank keeps its rest positions.

#include "damper/model/damper_model.h"
#include "damper/model/electric_actuator.h"

#include <vector>

namespace damper {

class ActuatorDrive {
 public:
  ActuatorDrive() = default;
  /// Two actuators per damper of `bank`, at rest at the bank's current positions.
  ActuatorDrive(const ElectricActuatorParams& params, const DamperBank& bank);
  /// Damper k's actuators move toward targets t1, t2 (in) over dt_s; the positions reached are
  /// set on the bank. Does not allocate.
  void follow(DamperBank& bank, int k, double target1_in, double target2_in, double dt_s);
  double actuator1_in(int k) const { return a1_[static_cast<std::size_t>(k)].position_in(); }
  double actuator2_in(int k) const { return a2_[static_cast<std::size_t>(k)].position_in(); }

 private:
  std::vector<ElectricActuator> a1_, a2_;
};

}  // namespace damper
