#include "structure/energy.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace structure {

EnergyLedger::EnergyLedger(const ShearBuilding& building) : building_(building) {}

EnergyLedger::Powers EnergyLedger::powers(const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                                          double ug, const Eigen::VectorXd& f) const {
  const int n = building_.num_stories();
  if (x.size() != n || v.size() != n || f.size() != building_.num_dampers()) {
    throw std::invalid_argument("EnergyLedger: expected " + std::to_string(n) +
                                " floor displacements/velocities and " +
                                std::to_string(building_.num_dampers()) + " damper forces");
  }
  Powers p;
  p.input = -v.dot(building_.mass() * building_.influence()) * ug;
  p.damping = v.dot(building_.damping() * v);
  p.damper = f.dot(building_.damper_gamma().transpose() * v);
  return p;
}

void EnergyLedger::start(const Eigen::VectorXd& x, const Eigen::VectorXd& v, double ug,
                         const Eigen::VectorXd& f) {
  last_ = powers(x, v, ug, f);
  input_ = damping_ = damper_ = 0.0;
  kinetic_ = 0.5 * v.dot(building_.mass() * v);
  strain_ = 0.5 * x.dot(building_.stiffness() * x);
  // A start away from rest counts the initial energy as input.
  input_ = kinetic_ + strain_;
  started_ = true;
}

void EnergyLedger::add_step(double dt_s, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                            double ug, const Eigen::VectorXd& f) {
  if (!started_) throw std::logic_error("EnergyLedger::add_step called before start");
  const Powers now = powers(x, v, ug, f);
  input_ += 0.5 * dt_s * (last_.input + now.input);
  damping_ += 0.5 * dt_s * (last_.damping + now.damping);
  damper_ += 0.5 * dt_s * (last_.damper + now.damper);
  kinetic_ = 0.5 * v.dot(building_.mass() * v);
  strain_ = 0.5 * x.dot(building_.stiffness() * x);
  last_ = now;
}

double EnergyLedger::balance_error() const {
  const double stored_and_dissipated = kinetic_ + strain_ + damping_ + damper_;
  return std::abs(input_ - stored_and_dissipated) / std::max(std::abs(input_), 1e-12);
}

}  // namespace structure
