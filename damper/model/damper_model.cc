#include "damper/model/damper_model.h"

#include <stdexcept>
#include <string>

namespace damper {

DamperBank::DamperBank(const DamperModel& prototype, int count) {
  if (count < 0) throw std::invalid_argument("DamperBank: negative damper count " + std::to_string(count));
  for (int k = 0; k < count; ++k) {
    models_.push_back(prototype.fresh_copy());
    DamperInput in;
    in.actuator1_in = prototype.actuator1_rest_in();
    in.actuator2_in = prototype.actuator2_rest_in();
    inputs_.push_back(in);
  }
}

void DamperBank::set_actuators(int k, double actuator1_in, double actuator2_in) {
  DamperInput& in = inputs_.at(static_cast<std::size_t>(k));
  in.actuator1_in = actuator1_in;
  in.actuator2_in = actuator2_in;
}

double DamperBank::step(int k, double drum_disp_in, double drum_vel_in_per_s, double dt_s) {
  DamperInput& in = inputs_[static_cast<std::size_t>(k)];
  in.drum_disp_in = drum_disp_in;
  in.drum_vel_in_per_s = drum_vel_in_per_s;
  return models_[static_cast<std::size_t>(k)]->step(in, dt_s);
}

void DamperBank::step(const Eigen::VectorXd& drum_disp_in, const Eigen::VectorXd& drum_vel_in_per_s, double dt_s,
                      Eigen::VectorXd& force_kip) {
  for (int k = 0; k < size(); ++k) force_kip[k] = step(k, drum_disp_in[k], drum_vel_in_per_s[k], dt_s);
}

void DamperBank::reset() {
  for (std::size_t k = 0; k < models_.size(); ++k) {
    models_[k]->reset();
    inputs_[k].actuator1_in = models_[k]->actuator1_rest_in();
    inputs_[k].actuator2_in = models_[k]->actuator2_rest_in();
  }
}

}  // namespace damper
