#include "structure/kr_alpha_integrator.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace structure {

KrAlphaParameters KrAlphaParameters::from_rho_inf(double rho_inf) {
  if (!(rho_inf >= 0.0 && rho_inf <= 1.0)) {
    std::ostringstream msg;
    msg << "KR-alpha: rho_inf must be in [0, 1], got " << rho_inf;
    throw std::invalid_argument(msg.str());
  }
  KrAlphaParameters p;
  p.rho_inf = rho_inf;
  p.alpha_m = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0);
  p.alpha_f = rho_inf / (rho_inf + 1.0);
  p.gamma = 0.5 - p.alpha_m + p.alpha_f;
  p.beta = 0.25 * std::pow(1.0 - p.alpha_m + p.alpha_f, 2);
  return p;
}

KrAlphaIntegrator::KrAlphaIntegrator(const ShearBuilding& building, double dt_s, double rho_inf)
    : building_(building), dt_s_(dt_s), p_(KrAlphaParameters::from_rho_inf(rho_inf)) {
  check_time_step("KrAlphaIntegrator", dt_s);
  const Eigen::MatrixXd& m = building.mass();
  const Eigen::MatrixXd& c = building.damping();
  const Eigen::MatrixXd& k = building.stiffness();
  const double g = p_.gamma * dt_s, b = p_.beta * dt_s * dt_s;
  const Eigen::PartialPivLU<Eigen::MatrixXd> lhs((m + g * c + b * k).eval());
  alpha1_ = lhs.solve(m);
  alpha2_ = (0.5 + p_.gamma) * alpha1_;
  alpha3_ = lhs.solve(p_.alpha_m * m + p_.alpha_f * g * c + p_.alpha_f * b * k);
  mass_llt_ = mass_factor("KrAlphaIntegrator", m);
  const int n = building.num_stories();
  // M(I − α₃) = M·(M + γΔtC + βΔt²K)⁻¹·((1 − α_m)M + (1 − α_f)(γΔtC + βΔt²K)): regular for ρ∞ ∈ [0, 1].
  const Eigen::MatrixXd mass_hat = m * (Eigen::MatrixXd::Identity(n, n) - alpha3_);
  const Eigen::PartialPivLU<Eigen::MatrixXd> hat(mass_hat);
  p_damping_ = hat.solve(c);
  p_stiffness_ = hat.solve(k);
  p_gamma_ = hat.solve(building.damper_gamma());
  p_accel_ = hat.solve(m * alpha3_);
  p_iota_ = hat.solve(m * building.influence());
  x_ = v_ = a_ = x_next_ = v_next_ = delta_a_ = x_w_ = v_w_ = a_next_ = Eigen::VectorXd::Zero(n);
  f_w_ = force_prev_ = Eigen::VectorXd::Zero(building.num_dampers());
}

std::string KrAlphaIntegrator::description() const {
  std::ostringstream o;
  o << "KR-alpha (Kolay & Ricles 2014), rho_inf = " << p_.rho_inf;
  return o.str();
}

void KrAlphaIntegrator::initialize(const Eigen::VectorXd& disp_in, const Eigen::VectorXd& vel_in_per_s,
                                   double ground_accel_in_per_s2, const Eigen::VectorXd& damper_force_kip) {
  a_ = equilibrium_acceleration("KrAlphaIntegrator", building_, mass_llt_, disp_in, vel_in_per_s,
                                ground_accel_in_per_s2, damper_force_kip);
  x_ = disp_in;
  v_ = vel_in_per_s;
  x_next_ = x_;
  v_next_ = v_;
  force_prev_ = damper_force_kip;
  ground_prev_ = ground_accel_in_per_s2;
  step_ = 0;
  initialized_ = true;
  predicted_ = false;
}

void KrAlphaIntegrator::predict() {
  if (!initialized_) throw std::logic_error("KrAlphaIntegrator::predict called before initialize");
  delta_a_.noalias() = alpha1_ * a_;  // α₁·ẍ_n; α₂·ẍ_n = (½ + γ)·α₁·ẍ_n
  v_next_ = v_ + dt_s_ * delta_a_;
  x_next_ = x_ + dt_s_ * v_ + ((0.5 + p_.gamma) * dt_s_ * dt_s_) * delta_a_;
  predicted_ = true;
}

void KrAlphaIntegrator::complete(double ground_accel_in_per_s2, const Eigen::VectorXd& damper_force_kip) {
  if (!predicted_) throw std::logic_error("KrAlphaIntegrator::complete called without predict for this step");
  check_damper_forces("KrAlphaIntegrator", "complete", building_, damper_force_kip);
  const double wn = 1.0 - p_.alpha_f, wo = p_.alpha_f;  // weights of step n+1 and step n
  x_w_ = wn * x_next_ + wo * x_;
  v_w_ = wn * v_next_ + wo * v_;
  f_w_ = wn * damper_force_kip + wo * force_prev_;
  const double ground_w = wn * ground_accel_in_per_s2 + wo * ground_prev_;
  // ẍ_{n+1} = (M(I − α₃))⁻¹·(f_{n+1−α_f} − C·ẋ_{n+1−α_f} − K·x_{n+1−α_f} − M·α₃·ẍ_n)
  a_next_ = -ground_w * p_iota_;
  a_next_.noalias() -= p_damping_ * v_w_;
  a_next_.noalias() -= p_stiffness_ * x_w_;
  a_next_.noalias() -= p_gamma_ * f_w_;
  a_next_.noalias() -= p_accel_ * a_;
  a_.swap(a_next_);
  x_ = x_next_;
  v_ = v_next_;
  force_prev_ = damper_force_kip;
  ground_prev_ = ground_accel_in_per_s2;
  ++step_;
  predicted_ = false;
}

}  // namespace structure
