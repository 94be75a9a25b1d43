#pragma once
/// @file energy.h
/// Energy balance of the shear building in relative coordinates (Uang & Bertero 1990):
///   E_in = −∫ ẋᵀ M ι ü_g dt = ½ẋᵀMẋ + ½xᵀKx + ∫ ẋᵀCẋ dt + ∫ Fᵀ(Γᵀẋ) dt
/// i.e. input = kinetic + strain + inherent (Rayleigh) damping + damper dissipation. Units: kip·in.
///
/// Two definitions of the discrete terms (EnergyDefinition), each named in the printed balance:
///
/// centred_difference (the hybrid run's ledger, used for every integrator). From the
/// displacements x_n alone, with ū_n = (x_{n+1} − x_{n−1})/(2Δt), w_{n+½} = (x_{n+1} − x_n)/Δt
/// and y_{n+½} = (x_{n+1} + x_n)/2:
///   input_n   = −Δt·ū_nᵀ M ι ü_g(t_n)            damping_n = Δt·ū_nᵀ C ū_n
///   damper_n  =  Δt·(Γᵀū_n)ᵀ F_n                  stored_{n+½} = ½w_{n+½}ᵀ M w_{n+½} + ½y_{n+½}ᵀ K y_{n+½}
///   algorithmic_n = −Δt·ū_nᵀ r_n,  r_n = M(x_{n+1} − 2x_n + x_{n−1})/Δt² + C ū_n
///                                        + K(x_{n+1} + 2x_n + x_{n−1})/4 + M ι ü_g(t_n) + Γ F_n
/// Multiplying r_n by ū_n gives the exact discrete identity
///   stored_{n+½} − stored_{n−½} + damping_n + damper_n + algorithmic_n = input_n,
/// so the ledger closes to round-off, and r_n is the force by which the displacement sequence
/// departs from the energy-conserving trapezoidal recurrence. CR's displacements obey that
/// recurrence exactly (cr_integrator.h: eliminating v gives M δ²x/Δt² + C ū + K x̄ = f_n), so
/// for CR algorithmic_n is zero up to round-off, nonlinear dampers included; for KR-α with
/// ρ∞ < 1 it is the numerical dissipation ρ∞ buys (plus its O(Δt²) dispersion). The first
/// sample uses x_{−1} = x_0 − Δt·ẋ_0 (CR's own start), stored energies are at half steps
/// (after N steps: t_N − Δt/2), and Δt must be uniform.
///
/// trapezoidal_state (for continuous solutions such as the CVODE reference): the given
/// velocities, stored energies at the samples, powers integrated with the trapezoidal rule;
/// the residual is the truncation error of that quadrature (second order in Δt). Fed with CR's
/// velocity (the backward difference (x₊ − x)/Δt, half a step late) it is first order
/// (≈0.6 % over El Centro at Δt = 1/1024 s): that is why the run uses centred_difference.

#include "structure/shear_building.h"
#include "structure/sparse_rows.h"

#include <Eigen/Dense>

namespace structure {

enum class EnergyDefinition { centred_difference, trapezoidal_state };

/// One line naming the definition, printed with the balance.
const char* energy_definition_text(EnergyDefinition definition);

/// Accumulates the energy terms sample by sample. Keeps a reference to the building.
/// add_step() allocates nothing.
class EnergyLedger {
 public:
  explicit EnergyLedger(const ShearBuilding& building,
                        EnergyDefinition definition = EnergyDefinition::centred_difference);

  /// Records the first sample (usually t = 0) and zeroes the integrals. A start away from rest
  /// counts the initial kinetic + strain energy as input energy, so the balance still closes.
  /// @throws std::invalid_argument on wrong vector sizes.
  void start(const Eigen::VectorXd& disp_in, const Eigen::VectorXd& vel_in_per_s,
             double ground_accel_in_per_s2, const Eigen::VectorXd& damper_force_kip);
  /// Adds the next sample, dt_s after the previous one. centred_difference books the step of
  /// the previous sample (it needs this displacement) and ignores vel_in_per_s after start().
  /// @throws std::logic_error if start() was not called; std::invalid_argument on wrong sizes
  ///         or (centred_difference) a step different from the first one.
  void add_step(double dt_s, const Eigen::VectorXd& disp_in, const Eigen::VectorXd& vel_in_per_s,
                double ground_accel_in_per_s2, const Eigen::VectorXd& damper_force_kip);

  EnergyDefinition definition() const { return definition_; }
  double input_kip_in() const { return input_; }              ///< E_in
  double kinetic_kip_in() const;                              ///< ½ẋᵀMẋ (see the definitions)
  double strain_kip_in() const;                               ///< ½xᵀKx (see the definitions)
  double inherent_damping_kip_in() const { return damping_; } ///< ∫ẋᵀCẋ dt
  double damper_kip_in() const { return damper_; }            ///< ∫Fᵀ(Γᵀẋ) dt (dissipated by the dampers)
  /// Per damper ∫F_k d(drum_k), kip·in (same definition).
  const Eigen::VectorXd& damper_kip_in_per_damper() const { return damper_each_; }
  /// Energy removed by the integrator itself (centred_difference; 0 for trapezoidal_state).
  double algorithmic_kip_in() const { return algorithmic_; }
  /// |E_in − (kinetic + strain + damping + damper + algorithmic)| / max(|E_in|, 1e-12).
  double balance_error() const;

 private:
  struct Powers {
    double input = 0.0, damping = 0.0, damper = 0.0;  // kip·in/s
  };
  void check_sizes(const Eigen::VectorXd& x, const Eigen::VectorXd& v, const Eigen::VectorXd& f) const;
  Powers powers(const Eigen::VectorXd& v, double ug, const Eigen::VectorXd& f) const;
  void add_centred(double dt, const Eigen::VectorXd& x_next, double ug_next, const Eigen::VectorXd& f_next);

  const ShearBuilding& building_;
  EnergyDefinition definition_;
  Eigen::VectorXd mass_iota_;                 // M·ι, precomputed
  // M (diagonal), K and C (tridiagonal), Γᵀ stored sparse: the products skip exact zeros.
  SparseRows mass_, stiffness_, damping_matrix_, gamma_t_;
  Tridiagonal mass_band_, stiffness_band_, damping_band_;  // the same, as diagonals (valid for a shear building)
  mutable Eigen::VectorXd work_, work2_, drum_vel_;  // scratch: add_step allocates nothing
  Eigen::VectorXd last_x_, last_v_;           // stored energies are computed on demand from these
  bool started_ = false;
  // trapezoidal_state
  Powers last_;
  Eigen::VectorXd last_damper_power_;
  // centred_difference: x_{n−1}, x_n, ü_g(t_n), F_n, the step
  Eigen::VectorXd x_prev_, x_now_, f_now_, velocity_c_;
  double ug_now_ = 0.0, dt_ = 0.0;
  long booked_ = 0;
  double input_ = 0.0, damping_ = 0.0, damper_ = 0.0, algorithmic_ = 0.0;
  Eigen::VectorXd damper_each_;
};

}  // namespace structure
