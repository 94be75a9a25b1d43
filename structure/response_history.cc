#include "structure/response_history.h"

namespace structure {

Eigen::VectorXd ResponseHistory::peak_abs_drift_in(const ShearBuilding& building) const {
  Eigen::VectorXd peak = Eigen::VectorXd::Zero(building.num_stories());
  for (const Eigen::VectorXd& x : floor_disp_in) {
    peak = peak.cwiseMax(building.interstory_drift(x).cwiseAbs());
  }
  return peak;
}

Eigen::VectorXd ResponseHistory::peak_abs_floor_disp_in(const ShearBuilding& building) const {
  Eigen::VectorXd peak = Eigen::VectorXd::Zero(building.num_stories());
  for (const Eigen::VectorXd& x : floor_disp_in) peak = peak.cwiseMax(x.cwiseAbs());
  return peak;
}

Eigen::VectorXd ResponseHistory::peak_abs_damper_force_kip(const ShearBuilding& building) const {
  Eigen::VectorXd peak = Eigen::VectorXd::Zero(building.num_dampers());
  for (const Eigen::VectorXd& f : damper_force_kip) peak = peak.cwiseMax(f.cwiseAbs());
  return peak;
}

}  // namespace structure
