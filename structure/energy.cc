#include "structure/energy.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace structure {

EnergyLedger::EnergyLedger(const ShearBuilding& building)
    : building_(building),
      mass_iota_(building.mass() * building.influence()),
      work_(building.num_stories()),
      drum_vel_(building.num_dampers()),
      last_x_(Eigen::VectorXd::Zero(building.num_stories())),
      last_v_(Eigen::VectorXd::Zero(building.num_stories())) {}

double EnergyLedger::kinetic_kip_in() const {
  work_.noalias() = building_.mass() * last_v_;
  return 0.5 * last_v_.dot(work_);
}

double EnergyLedger::strain_kip_in() const {
  work_.noalias() = building_.stiffness() * last_x_;
  return 0.5 * last_x_.dot(work_);
}

EnergyLedger::Powers EnergyLedger::powers(const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                                          double ug, const Eigen::VectorXd& f) const {
  const int n = building_.num_stories();
  if (x.size() != n || v.size() != n || f.size() != building_.num_dampers()) {
    throw std::invalid_argument("EnergyLedger: expected " + std::to_string(n) +
                                " floor displacements/velocities and " +
                                std::to_string(building_.num_dampers()) + " damper forces");
  }
  Powers p;
  p.input = -v.dot(mass_iota_) * ug;
  work_.noalias() = building_.damping() * v;
  p.damping = v.dot(work_);
  drum_vel_.noalias() = building_.damper_gamma().transpose() * v;
  p.damper = f.dot(drum_vel_);
  return p;
}

void EnergyLedger::start(const Eigen::VectorXd& x, const Eigen::VectorXd& v, double ug,
                         const Eigen::VectorXd& f) {
  last_ = powers(x, v, ug, f);
  damping_ = damper_ = 0.0;
  last_x_ = x;
  last_v_ = v;
  // A start away from rest counts the initial energy as input.
  input_ = kinetic_kip_in() + strain_kip_in();
  started_ = true;
}

void EnergyLedger::add_step(double dt_s, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                            double ug, const Eigen::VectorXd& f) {
  if (!started_) throw std::logic_error("EnergyLedger::add_step called before start");
  const Powers now = powers(x, v, ug, f);
  input_ += 0.5 * dt_s * (last_.input + now.input);
  damping_ += 0.5 * dt_s * (last_.damping + now.damping);
  damper_ += 0.5 * dt_s * (last_.damper + now.damper);
  last_x_ = x;
  last_v_ = v;
  last_ = now;
}

double EnergyLedger::balance_error() const {
  const double stored_and_dissipated = kinetic_kip_in() + strain_kip_in() + damping_ + damper_;
  return std::abs(input_ - stored_and_dissipated) / std::max(std::abs(input_), 1e-12);
}

}  // namespace structure
