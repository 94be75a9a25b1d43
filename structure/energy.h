#pragma once
/// @file energy.h
/// Energy balance of the shear building in relative coordinates (Uang & Bertero 1990):
///   E_in = −∫ ẋᵀ M ι ü_g dt = ½ẋᵀMẋ + ½xᵀKx + ∫ ẋᵀCẋ dt + ∫ Fᵀ(Γᵀẋ) dt
/// i.e. input = kinetic + strain + inherent (Rayleigh) damping + damper dissipation.
/// Integrals are accumulated with the trapezoidal rule over each step. Units: kip·in.
/// Fed with CrIntegrator output, the velocity is CR's backward difference (x₊ − x)/Δt, which
/// lags ẋ(t) by half a step: the balance error is then first order in Δt (≈0.5% over El Centro
/// at Δt = 1/1024 s). Feeding the centred velocity (v_n + v_{n+1})/2 closes it to round-off.

#include "structure/shear_building.h"

#include <Eigen/Dense>

namespace structure {

/// Accumulates the energy terms sample by sample. Keeps a reference to the building.
class EnergyLedger {
 public:
  explicit EnergyLedger(const ShearBuilding& building);

  /// Records the first sample (usually t = 0) and zeroes the integrals. A start away from rest
  /// counts the initial kinetic + strain energy as input energy, so the balance still closes.
  /// @throws std::invalid_argument on wrong vector sizes.
  void start(const Eigen::VectorXd& disp_in, const Eigen::VectorXd& vel_in_per_s,
             double ground_accel_in_per_s2, const Eigen::VectorXd& damper_force_kip);
  /// Adds the step from the previous sample to this one, dt_s later (trapezoidal rule).
  /// @throws std::logic_error if start() was not called; std::invalid_argument on wrong sizes.
  void add_step(double dt_s, const Eigen::VectorXd& disp_in, const Eigen::VectorXd& vel_in_per_s,
                double ground_accel_in_per_s2, const Eigen::VectorXd& damper_force_kip);

  double input_kip_in() const { return input_; }             ///< E_in = −∫ẋᵀMιü_g dt
  double kinetic_kip_in() const;                             ///< ½ẋᵀMẋ at the last sample
  double strain_kip_in() const;                              ///< ½xᵀKx at the last sample
  double inherent_damping_kip_in() const { return damping_; }///< ∫ẋᵀCẋ dt
  double damper_kip_in() const { return damper_; }           ///< ∫Fᵀ(Γᵀẋ) dt (dissipated by the dampers)
  /// |E_in − (kinetic + strain + damping + damper)| / max(|E_in|, 1e-12).
  double balance_error() const;

 private:
  struct Powers {
    double input = 0.0, damping = 0.0, damper = 0.0;  // kip·in/s
  };
  Powers powers(const Eigen::VectorXd& x, const Eigen::VectorXd& v, double ug,
                const Eigen::VectorXd& f) const;

  const ShearBuilding& building_;
  Eigen::VectorXd mass_iota_;          // M·ι, precomputed
  mutable Eigen::VectorXd work_, drum_vel_;  // scratch: add_step allocates nothing
  Eigen::VectorXd last_x_, last_v_;          // last sample: stored energies are computed on demand
  bool started_ = false;
  Powers last_;
  double input_ = 0.0, damping_ = 0.0, damper_ = 0.0;
};

}  // namespace structure
