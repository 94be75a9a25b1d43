#pragma once
/// @file kr_alpha_integrator.h
/// The KR-α method (Kolay & Ricles 2014, "Development of a family of unconditionally stable
/// explicit direct integration algorithms with controllable numerical energy dissipation",
/// Earthquake Engng Struct. Dyn. 43(9):1361–1380, doi:10.1002/eqe.2401): explicit, model-based
/// integration parameter matrices, unconditionally stable for linear and softening systems,
/// with numerical dissipation set by ρ∞ (the spectral radius as ωΔt → ∞), as in
/// OpenSees/OpenFresco `KRAlphaExplicit` and Lehigh's RTMD.
///
/// Parameters from ρ∞ ∈ [0, 1] (those of the generalized-α method of Chung & Hulbert 1993):
///   α_m = (2ρ∞ − 1)/(ρ∞ + 1),  α_f = ρ∞/(ρ∞ + 1),  γ = ½ − α_m + α_f,  β = ¼(1 − α_m + α_f)²
/// Integration parameter matrices (computed once, from M, C, K and Δt):
///   α₁ = (M + γΔt·C + βΔt²·K)⁻¹·M
///   α₂ = (½ + γ)·α₁
///   α₃ = (M + γΔt·C + βΔt²·K)⁻¹·(α_m·M + α_f·γΔt·C + α_f·βΔt²·K)
/// Step (explicit displacement and velocity, so the damper command of step n+1 is known
/// before its force is needed, as in CR):
///   ẋ_{n+1} = ẋ_n + Δt·α₁·ẍ_n
///   x_{n+1} = x_n + Δt·ẋ_n + Δt²·α₂·ẍ_n
///   M·[(I − α₃)·ẍ_{n+1} + α₃·ẍ_n] + C·ẋ_{n+1−α_f} + K·x_{n+1−α_f} = f_{n+1−α_f}
/// with (·)_{n+1−α_f} = (1 − α_f)·(·)_{n+1} + α_f·(·)_n and f = −M·ι·ü_g − Γ·F, the damper
/// force F at the same weighted point (the restoring force of the substructure, measured at
/// x_{n+1}). ρ∞ = 1 gives α₃ = ½I, α₂ = α₁ = CR's α, and the weighted equation then keeps the
/// equilibrium of step n+1 exactly: KR-α(ρ∞ = 1) reproduces CR to round-off.
/// Units: in, in/s, in/s², kip, s; all relative to the ground.

#include "structure/integrator.h"
#include "structure/shear_building.h"

#include <Eigen/Dense>

namespace structure {

/// The scalar parameters of KR-α for a given ρ∞ (formulas above).
struct KrAlphaParameters {
  double rho_inf, alpha_m, alpha_f, gamma, beta;
  /// @throws std::invalid_argument if ρ∞ is not in [0, 1].
  static KrAlphaParameters from_rho_inf(double rho_inf);
};

/// KR-α integrator for one ShearBuilding (keeps a reference; it must outlive the integrator).
/// predict() and complete() allocate no memory.
class KrAlphaIntegrator final : public Integrator {
 public:
  /// Computes α₁, α₂, α₃ and the factorization of M·(I − α₃) once.
  /// @throws std::invalid_argument if dt_s is not finite and > 0 or ρ∞ is not in [0, 1].
  KrAlphaIntegrator(const ShearBuilding& building, double dt_s, double rho_inf);

  std::string name() const override { return "kr_alpha"; }
  std::string description() const override;

  using Integrator::initialize;
  void initialize(const Eigen::VectorXd& disp_in, const Eigen::VectorXd& vel_in_per_s,
                  double ground_accel_in_per_s2, const Eigen::VectorXd& damper_force_kip) override;
  void predict() override;
  const Eigen::VectorXd& next_displacement_in() const override { return x_next_; }
  const Eigen::VectorXd& next_velocity_in_per_s() const override { return v_next_; }
  void complete(double ground_accel_in_per_s2, const Eigen::VectorXd& damper_force_kip) override;

  const Eigen::VectorXd& displacement_in() const override { return x_; }
  const Eigen::VectorXd& velocity_in_per_s() const override { return v_; }
  const Eigen::VectorXd& acceleration_in_per_s2() const override { return a_; }
  long step_index() const override { return step_; }
  double dt_s() const override { return dt_s_; }

  const KrAlphaParameters& parameters() const { return p_; }
  const Eigen::MatrixXd& alpha1() const { return alpha1_; }  ///< α₁ (dimensionless)
  const Eigen::MatrixXd& alpha2() const { return alpha2_; }  ///< α₂ = (½ + γ)·α₁
  const Eigen::MatrixXd& alpha3() const { return alpha3_; }  ///< α₃ (dimensionless)

 private:
  const ShearBuilding& building_;
  double dt_s_;
  KrAlphaParameters p_;
  Eigen::MatrixXd alpha1_, alpha2_, alpha3_;
  Eigen::LLT<Eigen::MatrixXd> mass_llt_;
  // (M(I − α₃))⁻¹ applied to C, K, Γ, M·ι and M·α₃: a step is a few matrix-vector products.
  Eigen::MatrixXd p_damping_, p_stiffness_, p_gamma_, p_accel_;
  Eigen::VectorXd p_iota_;
  Eigen::VectorXd x_, v_, a_, x_next_, v_next_, delta_a_, x_w_, v_w_, f_w_, a_next_;
  Eigen::VectorXd force_prev_;  // F_n
  double ground_prev_ = 0.0;    // ü_g(t_n)
  long step_ = 0;
  bool initialized_ = false;
  bool predicted_ = false;
};

}  // namespace structure
