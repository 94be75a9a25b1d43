#pragma once
/// @file cr_integrator.h
/// The explicit CR algorithm (Chen & Ricles 2008, "Development of direct integration
/// algorithms for structural dynamics using discrete control theory", J. Eng. Mech. 134(8))
/// for real-time hybrid simulation of the shear building with its BRFD dampers:
///   α  = (M + Δt/2·C + Δt²/4·K)⁻¹·M
///   v₊ = v + Δt·α·a
///   x₊ = x + Δt·v + Δt²·α·a
///   M·a₊ = −M·ι·ü_g(t₊) − C·v₊ − K·x₊ − Γ·F(x₊, v₊)
/// Displacement and velocity are explicit, so the next drum command is known before the
/// damper force (measured or computed) is needed. Unconditionally stable for the linear
/// building; no numerical damping. Units: in, in/s, in/s², kip, s; all relative to the ground.
///
/// Accuracy (linear building): eliminating v shows that the displacement sequence obeys the
/// trapezoidal (average-acceleration) recurrence, so the period elongation is ≈ (ωΔt)²/12
/// and the response converges at second order. The first step, however, uses Δt²·α·a₀ where
/// the exact Taylor term is ½Δt²·a₀; when a₀ ≠ 0 (an initial displacement, or a nonzero
/// ground acceleration at t = 0) this leaves a persistent first-order error of amplitude
/// ≈ ½Δt²|a₀|/sin(ωΔt) ≈ ½Δt|a₀|/ω. Starting from rest under a record with ü_g(0) ≈ 0 (the
/// hybrid-test case) the error stays second order. tests/structure/cr_integrator_test.cc
/// measures both. Since x₊ = x + Δt·v₊, the velocity v₊ is the backward difference
/// (x₊ − x)/Δt: a second-order estimate of ẋ at mid-step, lagging ẋ(t₊) by Δt/2.

#include "structure/integrator.h"
#include "structure/shear_building.h"

#include "structure/sparse_rows.h"

#include <Eigen/Dense>

namespace structure {

/// CR integrator for one ShearBuilding. Usage per step: predict(); read next_displacement_in()
/// / next_velocity_in_per_s() and obtain the damper forces for that state; complete().
/// predict() and complete() allocate no memory (real-time safe).
class CrIntegrator final : public Integrator {
 public:
  /// Precomputes α and the Cholesky factorization of M. Keeps a reference to `building`,
  /// which must outlive the integrator.
  /// @throws std::invalid_argument if dt_s is not finite and > 0.
  CrIntegrator(const ShearBuilding& building, double dt_s);

  std::string name() const override { return "cr"; }
  std::string description() const override { return "CR (Chen & Ricles 2008)"; }

  /// Starts at rest (x = v = 0, t = 0, step 0) and solves M a₀ = −M ι ü_g(0) − Γ F₀
  /// (Integrator::initialize(ground_accel_in_per_s2, damper_force_kip)), or from a given
  /// state (e.g. free vibration) solving M a₀ = −M ι ü_g(0) − C v₀ − K x₀ − Γ F₀.
  /// @throws std::invalid_argument on wrong sizes.
  using Integrator::initialize;
  void initialize(const Eigen::VectorXd& disp_in, const Eigen::VectorXd& vel_in_per_s,
                  double ground_accel_in_per_s2, const Eigen::VectorXd& damper_force_kip) override;

  /// Computes x₊ and v₊ from the committed state. Calling it again before complete() is
  /// harmless (same result). @throws std::logic_error if not initialized.
  void predict() override;
  const Eigen::VectorXd& next_displacement_in() const override { return x_next_; }     ///< x₊, in
  const Eigen::VectorXd& next_velocity_in_per_s() const override { return v_next_; }  ///< v₊, in/s

  /// Solves M·a₊ = −M·ι·ü_g(t₊) − C·v₊ − K·x₊ − Γ·F and commits the step (t += Δt).
  /// @param ground_accel_in_per_s2 ü_g at t₊ = t + Δt, in/s²
  /// @param damper_force_kip F at (x₊, v₊), one entry per damper (kip, positive resisting
  ///        positive drum velocity)
  /// @throws std::logic_error if predict() was not called for this step;
  ///         std::invalid_argument if damper_force_kip has the wrong size.
  void complete(double ground_accel_in_per_s2, const Eigen::VectorXd& damper_force_kip) override;

  const Eigen::VectorXd& displacement_in() const override { return x_; }         ///< committed x, in
  const Eigen::VectorXd& velocity_in_per_s() const override { return v_; }       ///< committed ẋ, in/s
  const Eigen::VectorXd& acceleration_in_per_s2() const override { return a_; }  ///< committed ẍ, in/s²
  long step_index() const override { return step_; }
  double dt_s() const override { return dt_s_; }
  /// The integration parameter α = (M + Δt/2·C + Δt²/4·K)⁻¹·M (dimensionless).
  const Eigen::MatrixXd& alpha() const { return alpha_; }

 private:
  const ShearBuilding& building_;
  double dt_s_;
  Eigen::MatrixXd alpha_;
  Eigen::LLT<Eigen::MatrixXd> mass_llt_;
  // M⁻¹C, M⁻¹K, M⁻¹Γ, stored sparse: a shear building's M is diagonal and K, C are
  // tridiagonal, so these products skip the (exact) zeros of the dense matrices.
  SparseRows minv_damping_, minv_stiffness_, minv_gamma_;
  Tridiagonal minv_damping_band_, minv_stiffness_band_;  // the same, as diagonals (valid for a shear building)
  Eigen::VectorXd x_, v_, a_, x_next_, v_next_, alpha_a_;
  long step_ = 0;
  bool initialized_ = false;
  bool predicted_ = false;
};

}  // namespace structure
