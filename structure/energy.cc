#include "structure/energy.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace structure {

const char* energy_definition_text(EnergyDefinition definition) {
  switch (definition) {
    case EnergyDefinition::centred_difference:
      return "centred-difference ledger: velocity (x[n+1]-x[n-1])/2dt, kinetic and strain energy at half steps; "
             "exact for CR, algorithmic = energy removed by the integrator";
    case EnergyDefinition::trapezoidal_state:
      return "trapezoidal ledger: state velocities, stored energies at the samples";
  }
  return "?";
}

EnergyLedger::EnergyLedger(const ShearBuilding& building, EnergyDefinition definition)
    : building_(building),
      definition_(definition),
      mass_iota_(building.mass() * building.influence()),
      mass_(sparse_rows(building.mass())),
      stiffness_(sparse_rows(building.stiffness())),
      damping_matrix_(sparse_rows(building.damping())),
      gamma_t_(sparse_rows(building.damper_gamma().transpose())),
      mass_band_(tridiagonal(mass_)),
      stiffness_band_(tridiagonal(stiffness_)),
      damping_band_(tridiagonal(damping_matrix_)),
      work_(building.num_stories()),
      work2_(building.num_stories()),
      drum_vel_(building.num_dampers()),
      last_x_(Eigen::VectorXd::Zero(building.num_stories())),
      last_v_(Eigen::VectorXd::Zero(building.num_stories())),
      last_damper_power_(Eigen::VectorXd::Zero(building.num_dampers())),
      x_prev_(Eigen::VectorXd::Zero(building.num_stories())),
      x_now_(Eigen::VectorXd::Zero(building.num_stories())),
      f_now_(Eigen::VectorXd::Zero(building.num_dampers())),
      velocity_c_(Eigen::VectorXd::Zero(building.num_stories())),
      damper_each_(Eigen::VectorXd::Zero(building.num_dampers())) {}

double EnergyLedger::kinetic_kip_in() const {
  work_.noalias() = mass_ * last_v_;
  return 0.5 * last_v_.dot(work_);
}

double EnergyLedger::strain_kip_in() const {
  work_.noalias() = stiffness_ * last_x_;
  return 0.5 * last_x_.dot(work_);
}

void EnergyLedger::check_sizes(const Eigen::VectorXd& x, const Eigen::VectorXd& v, const Eigen::VectorXd& f) const {
  const int n = building_.num_stories();
  if (x.size() != n || v.size() != n || f.size() != building_.num_dampers()) {
    throw std::invalid_argument("EnergyLedger: expected " + std::to_string(n) +
                                " floor displacements/velocities and " +
                                std::to_string(building_.num_dampers()) + " damper forces");
  }
}

EnergyLedger::Powers EnergyLedger::powers(const Eigen::VectorXd& v, double ug, const Eigen::VectorXd& f) const {
  Powers p;
  p.input = -v.dot(mass_iota_) * ug;
  work_.noalias() = damping_matrix_ * v;
  p.damping = v.dot(work_);
  drum_vel_.noalias() = gamma_t_ * v;
  p.damper = f.dot(drum_vel_);
  return p;
}

void EnergyLedger::start(const Eigen::VectorXd& x, const Eigen::VectorXd& v, double ug, const Eigen::VectorXd& f) {
  check_sizes(x, v, f);
  damping_ = damper_ = algorithmic_ = 0.0;
  damper_each_.setZero();
  last_x_ = x;
  last_v_ = v;
  // A start away from rest counts the initial energy as input.
  input_ = kinetic_kip_in() + strain_kip_in();
  if (definition_ == EnergyDefinition::trapezoidal_state) {
    last_ = powers(v, ug, f);
    last_damper_power_ = f.cwiseProduct(drum_vel_);
  } else {
    x_now_ = x;
    f_now_ = f;
    ug_now_ = ug;
    dt_ = 0.0;
    booked_ = 0;
  }
  started_ = true;
}

void EnergyLedger::add_step(double dt_s, const Eigen::VectorXd& x, const Eigen::VectorXd& v, double ug,
                            const Eigen::VectorXd& f) {
  if (!started_) throw std::logic_error("EnergyLedger::add_step called before start");
  check_sizes(x, v, f);
  if (definition_ == EnergyDefinition::centred_difference) {
    add_centred(dt_s, x, ug, f);
    return;
  }
  const Powers now = powers(v, ug, f);
  input_ += 0.5 * dt_s * (last_.input + now.input);
  damping_ += 0.5 * dt_s * (last_.damping + now.damping);
  damper_ += 0.5 * dt_s * (last_.damper + now.damper);
  // drum_vel_ holds Γᵀv of this sample (set by powers()).
  for (int k = 0; k < f.size(); ++k) {
    const double p = f[k] * drum_vel_[k];
    damper_each_[k] += 0.5 * dt_s * (last_damper_power_[k] + p);
    last_damper_power_[k] = p;
  }
  last_x_ = x;
  last_v_ = v;
  last_ = now;
}

void EnergyLedger::add_centred(double dt, const Eigen::VectorXd& x_next, double ug_next, const Eigen::VectorXd& f_next) {
  if (booked_ == 0) {
    if (!std::isfinite(dt) || !(dt > 0.0)) throw std::invalid_argument("EnergyLedger: time step must be > 0");
    dt_ = dt;
    // Virtual sample x_{−1} = x_0 − Δt·ẋ_0; the stored energy at −½ is the input so far.
    x_prev_ = x_now_ - dt * last_v_;
    last_x_ = 0.5 * (x_now_ + x_prev_);
    input_ = kinetic_kip_in() + strain_kip_in();
  } else if (std::abs(dt - dt_) > 1e-9 * dt_) {
    throw std::invalid_argument("EnergyLedger: the centred-difference ledger needs a uniform step (" +
                                std::to_string(dt_) + " s, then " + std::to_string(dt) + " s)");
  }
  // One pass over the floors with raw pointers (the profile's hot spot: docs/step-loop-profile.md):
  //   ū_n = (x_{n+1} − x_{n−1})/(2Δt),  δ²x = (x_{n+1} − 2x_n + x_{n−1})/Δt²,
  //   x̄ = (x_{n+1} + 2x_n + x_{n−1})/4,
  // then the row sums of M δ²x, K x̄ and C ū over the nonzeros of the sparse rows.
  const int n = static_cast<int>(x_next.size());
  const double* xn = x_next.data();
  const double* x0 = x_now_.data();
  const double* xp = x_prev_.data();
  double* u = velocity_c_.data();
  double* d2 = work2_.data();
  double* mean = work_.data();
  for (int i = 0; i < n; ++i) {
    u[i] = (xn[i] - xp[i]) / (2.0 * dt);
    d2[i] = (xn[i] - 2.0 * x0[i] + xp[i]) / (dt * dt);
    mean[i] = 0.25 * (xn[i] + 2.0 * x0[i] + xp[i]);
  }
  Powers p;
  double residual_power = 0.0;
  for (int i = 0; i < n; ++i) {
    double m_d2 = 0.0, k_mean = 0.0, c_u = 0.0;
    m_d2 = mass_band_.valid ? tri_dot(mass_band_, i, d2) : row_dot(mass_, i, d2);
    k_mean = stiffness_band_.valid ? tri_dot(stiffness_band_, i, mean) : row_dot(stiffness_, i, mean);
    c_u = damping_band_.valid ? tri_dot(damping_band_, i, u) : row_dot(damping_matrix_, i, u);
    p.input -= u[i] * mass_iota_[i];
    p.damping += u[i] * c_u;
    residual_power += u[i] * (m_d2 + k_mean);
  }
  p.input *= ug_now_;
  for (int k = 0; k < gamma_t_.rows(); ++k) {
    double drum = 0.0;
    drum = row_dot(gamma_t_, k, u);
    drum_vel_[k] = drum;
    p.damper += f_now_[k] * drum;
  }
  input_ += dt * p.input;
  damping_ += dt * p.damping;
  damper_ += dt * p.damper;
  for (int k = 0; k < f_now_.size(); ++k) damper_each_[k] += dt * f_now_[k] * drum_vel_[k];
  // r_n = M(x_{n+1} − 2x_n + x_{n−1})/Δt² + C ū_n + K(x_{n+1} + 2x_n + x_{n−1})/4 + M ι ü_g + Γ F_n
  residual_power += p.damping - p.input + p.damper;
  algorithmic_ -= dt * residual_power;
  // Stored energies at n+½.
  last_v_ = (x_next - x_now_) / dt;
  last_x_ = 0.5 * (x_next + x_now_);
  x_prev_.swap(x_now_);
  x_now_ = x_next;
  f_now_ = f_next;
  ug_now_ = ug_next;
  ++booked_;
}

double EnergyLedger::balance_error() const {
  const double stored_and_dissipated = kinetic_kip_in() + strain_kip_in() + damping_ + damper_ + algorithmic_;
  return std::abs(input_ - stored_and_dissipated) / std::max(std::abs(input_), 1e-12);
}

}  // namespace structure
