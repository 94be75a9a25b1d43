#include "damper/model/actuator_drive.h"

namespace damper {

ActuatorDrive::ActuatorDrive(const ElectricActuatorParams& params, const DamperBank& bank) {
  for (int k = 0; k < bank.size(); ++k) {
    a1_.emplace_back(params);
    a2_.emplace_back(params);
    a1_.back().reset(bank.input(k).actuator1_in);
    a2_.back().reset(bank.input(k).actuator2_in);
  }
}

void ActuatorDrive::follow(DamperBank& bank, int k, double t1, double t2, double dt) {
  const auto i = static_cast<std::size_t>(k);
  bank.set_actuators(k, a1_[i].step(t1, dt), a2_[i].step(t2, dt));
}

}  // namespace damper
