#include "structure/cr_integrator.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace structure {

CrIntegrator::CrIntegrator(const ShearBuilding& building, double dt_s)
    : building_(building), dt_s_(dt_s) {
  check_time_step("CrIntegrator", dt_s);
  const Eigen::MatrixXd& m = building.mass();
  const Eigen::MatrixXd denom = m + (0.5 * dt_s) * building.damping() + (0.25 * dt_s * dt_s) * building.stiffness();
  alpha_ = denom.partialPivLu().solve(m);
  mass_llt_ = mass_factor("CrIntegrator", m);
  // M⁻¹C, M⁻¹K, M⁻¹Γ once, so that a step is three small (sparse) matrix-vector products.
  minv_damping_ = sparse_rows(mass_llt_.solve(building.damping()));
  minv_stiffness_ = sparse_rows(mass_llt_.solve(building.stiffness()));
  minv_gamma_ = sparse_rows(mass_llt_.solve(building.damper_gamma()));
  minv_damping_band_ = tridiagonal(minv_damping_);
  minv_stiffness_band_ = tridiagonal(minv_stiffness_);
  const int n = building.num_stories();
  x_ = v_ = a_ = x_next_ = v_next_ = alpha_a_ = Eigen::VectorXd::Zero(n);
}

void CrIntegrator::initialize(const Eigen::VectorXd& disp_in, const Eigen::VectorXd& vel_in_per_s,
                              double ground_accel_in_per_s2, const Eigen::VectorXd& damper_force_kip) {
  a_ = equilibrium_acceleration("CrIntegrator", building_, mass_llt_, disp_in, vel_in_per_s, ground_accel_in_per_s2,
                                damper_force_kip);
  x_ = disp_in;
  v_ = vel_in_per_s;
  x_next_ = x_;
  v_next_ = v_;
  step_ = 0;
  initialized_ = true;
  predicted_ = false;
}

void CrIntegrator::predict() {
  if (!initialized_) throw std::logic_error("CrIntegrator::predict called before initialize");
  alpha_a_.noalias() = alpha_ * a_;
  v_next_ = v_ + dt_s_ * alpha_a_;
  x_next_ = x_ + dt_s_ * v_ + (dt_s_ * dt_s_) * alpha_a_;
  predicted_ = true;
}

void CrIntegrator::complete(double ground_accel_in_per_s2, const Eigen::VectorXd& damper_force_kip) {
  if (!predicted_) throw std::logic_error("CrIntegrator::complete called without predict for this step");
  check_damper_forces("CrIntegrator", "complete", building_, damper_force_kip);
  // a₊ = −ι·ü_g − M⁻¹C·v₊ − M⁻¹K·x₊ − M⁻¹Γ·F  (= M⁻¹ of the equation above)
  // One pass over the rows of the sparse M⁻¹C, M⁻¹K, M⁻¹Γ (ι is all ones).
  const double* v = v_next_.data();
  const double* x = x_next_.data();
  const double* f = damper_force_kip.data();
  const double* iota = building_.influence().data();
  for (int i = 0; i < a_.size(); ++i) {
    double c_v = 0.0, k_x = 0.0, g_f = 0.0;
    c_v = minv_damping_band_.valid ? tri_dot(minv_damping_band_, i, v) : row_dot(minv_damping_, i, v);
    k_x = minv_stiffness_band_.valid ? tri_dot(minv_stiffness_band_, i, x) : row_dot(minv_stiffness_, i, x);
    g_f = row_dot(minv_gamma_, i, f);
    a_[i] = ((-ground_accel_in_per_s2 * iota[i] - c_v) - k_x) - g_f;
  }
  x_ = x_next_;
  v_ = v_next_;
  ++step_;
  predicted_ = false;
}

}  // namespace structure
