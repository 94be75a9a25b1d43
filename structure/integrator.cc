#include "structure/integrator.h"

#include "structure/cr_integrator.h"
#include "structure/kr_alpha_integrator.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace structure {

void Integrator::initialize(double ground_accel_in_per_s2, const Eigen::VectorXd& damper_force_kip) {
  const Eigen::VectorXd rest = Eigen::VectorXd::Zero(displacement_in().size());
  initialize(rest, rest, ground_accel_in_per_s2, damper_force_kip);
}

void Integrator::check_time_step(const char* who, double dt_s) {
  if (!std::isfinite(dt_s) || !(dt_s > 0.0))
    throw std::invalid_argument(std::string(who) + ": time step must be finite and > 0, got " + std::to_string(dt_s));
}

Eigen::LLT<Eigen::MatrixXd> Integrator::mass_factor(const char* who, const Eigen::MatrixXd& mass) {
  Eigen::LLT<Eigen::MatrixXd> llt(mass);
  if (llt.info() != Eigen::Success) throw std::invalid_argument(std::string(who) + ": mass matrix is not positive definite");
  return llt;
}

void Integrator::check_damper_forces(const char* who, const char* method, const ShearBuilding& building,
                                     const Eigen::VectorXd& damper_force_kip) {
  if (damper_force_kip.size() != building.num_dampers()) {
    throw std::invalid_argument(std::string(who) + "::" + method + ": expected " +
                                std::to_string(building.num_dampers()) + " damper forces, got " +
                                std::to_string(damper_force_kip.size()));
  }
}

Eigen::VectorXd Integrator::equilibrium_acceleration(const char* who, const ShearBuilding& building,
                                                     const Eigen::LLT<Eigen::MatrixXd>& mass_llt,
                                                     const Eigen::VectorXd& disp_in, const Eigen::VectorXd& vel_in_per_s,
                                                     double ground_accel_in_per_s2,
                                                     const Eigen::VectorXd& damper_force_kip) {
  const int n = building.num_stories();
  if (disp_in.size() != n || vel_in_per_s.size() != n) {
    throw std::invalid_argument(std::string(who) + "::initialize: expected " + std::to_string(n) +
                                " floor displacements and velocities");
  }
  check_damper_forces(who, "initialize", building, damper_force_kip);
  Eigen::VectorXd rhs(n);
  rhs.noalias() = -ground_accel_in_per_s2 * (building.mass() * building.influence());
  rhs.noalias() -= building.damping() * vel_in_per_s;
  rhs.noalias() -= building.stiffness() * disp_in;
  rhs.noalias() -= building.damper_gamma() * damper_force_kip;
  return mass_llt.solve(rhs);
}

std::unique_ptr<Integrator> make_integrator(const ShearBuilding& building, double dt_s,
                                            const IntegratorSettings& settings) {
  if (settings.kind == "cr") return std::make_unique<CrIntegrator>(building, dt_s);
  if (settings.kind == "kr_alpha") return std::make_unique<KrAlphaIntegrator>(building, dt_s, settings.rho_inf);
  throw std::invalid_argument("unknown integrator '" + settings.kind + "' (expected cr or kr_alpha)");
}

}  // namespace structure
