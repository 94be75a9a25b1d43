#include "structure/integrator.h"

#include "structure/cr_integrator.h"
#include "structure/kr_alpha_integrator.h"

#include <stdexcept>

namespace structure {

void Integrator::initialize(double ground_accel_in_per_s2, const Eigen::VectorXd& damper_force_kip) {
  const Eigen::VectorXd rest = Eigen::VectorXd::Zero(displacement_in().size());
  initialize(rest, rest, ground_accel_in_per_s2, damper_force_kip);
}

std::unique_ptr<Integrator> make_integrator(const ShearBuilding& building, double dt_s,
                                            const IntegratorSettings& settings) {
  if (settings.kind == "cr") return std::make_unique<CrIntegrator>(building, dt_s);
  if (settings.kind == "kr_alpha") return std::make_unique<KrAlphaIntegrator>(building, dt_s, settings.rho_inf);
  throw std::invalid_argument("unknown integrator '" + settings.kind + "' (expected cr or kr_alpha)");
}

}  // namespace structure
