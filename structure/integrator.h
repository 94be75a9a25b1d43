#pragma once
/// @file integrator.h
/// The one interface of the explicit step-by-step integrators of the shear building
///   M ẍ + C ẋ + K x + Γ F = −M ι ü_g        (shear_building.h)
/// in a hybrid simulation, and the factory that picks one from the run config:
///  - "cr":       CR algorithm, Chen & Ricles (2008)       (cr_integrator.h)
///  - "kr_alpha": KR-α method, Kolay & Ricles (2014), with ρ∞ (kr_alpha_integrator.h)
/// Both share the substructure contract: predict() makes the displacement (and velocity) of
/// step i+1 known from the committed state alone, before the damper force at i+1 is needed;
/// complete() takes that force and the ground acceleration at t_{i+1} and commits the step.
/// predict() and complete() allocate no memory. Units: in, in/s, in/s², kip, s; all relative
/// to the ground.

#include "structure/shear_building.h"

#include <Eigen/Dense>

#include <memory>
#include <string>

namespace structure {

/// Which integrator, with its parameters (the `run:` keys `integrator` and `rho_inf`).
struct IntegratorSettings {
  std::string kind = "cr";  ///< "cr" or "kr_alpha"
  /// KR-α spectral radius at infinite frequency ρ∞ ∈ [0, 1]: 1 = no numerical dissipation
  /// (KR-α then reproduces CR), 0 = asymptotic annihilation. Ignored by CR.
  double rho_inf = 0.5;
};

/// The integrator names accepted by make_integrator().
inline const char* const kIntegratorKinds[] = {"cr", "kr_alpha"};

/// Explicit integrator of one ShearBuilding. Usage per step: predict(); read
/// next_displacement_in() / next_velocity_in_per_s() and obtain the damper forces for that
/// state; complete(). Implementations keep a reference to the building (it must outlive them).
class Integrator {
 public:
  virtual ~Integrator() = default;

  /// Short name ("cr", "kr_alpha") and a human-readable description with the parameters.
  virtual std::string name() const = 0;
  virtual std::string description() const = 0;

  /// Starts from displacement, velocity (t = 0, step 0) and the equilibrium acceleration
  /// M a₀ = −M ι ü_g(0) − C v₀ − K x₀ − Γ F₀.
  /// @throws std::invalid_argument on wrong sizes.
  virtual void initialize(const Eigen::VectorXd& disp_in, const Eigen::VectorXd& vel_in_per_s,
                          double ground_accel_in_per_s2, const Eigen::VectorXd& damper_force_kip) = 0;
  /// Starts at rest (x = v = 0).
  void initialize(double ground_accel_in_per_s2, const Eigen::VectorXd& damper_force_kip);

  /// Computes x₊, v₊ from the committed state (explicit). Calling it again before complete()
  /// gives the same result. @throws std::logic_error if not initialized.
  virtual void predict() = 0;
  virtual const Eigen::VectorXd& next_displacement_in() const = 0;     ///< x₊, in
  virtual const Eigen::VectorXd& next_velocity_in_per_s() const = 0;  ///< v₊, in/s

  /// Commits the step with ü_g(t₊) (in/s²) and the damper forces F at (x₊, v₊) (kip).
  /// @throws std::logic_error without predict(); std::invalid_argument on a wrong size.
  virtual void complete(double ground_accel_in_per_s2, const Eigen::VectorXd& damper_force_kip) = 0;

  virtual const Eigen::VectorXd& displacement_in() const = 0;         ///< committed x, in
  virtual const Eigen::VectorXd& velocity_in_per_s() const = 0;       ///< committed ẋ, in/s
  virtual const Eigen::VectorXd& acceleration_in_per_s2() const = 0;  ///< committed ẍ, in/s²
  virtual long step_index() const = 0;
  virtual double dt_s() const = 0;
  double time_s() const { return static_cast<double>(step_index()) * dt_s(); }

 protected:
  // What every integrator checks and computes the same way; `who` ("CrIntegrator", ...) names
  // it in the messages.
  /// @throws std::invalid_argument unless dt_s is finite and > 0.
  static void check_time_step(const char* who, double dt_s);
  /// Cholesky factor of M. @throws std::invalid_argument if M is not positive definite.
  static Eigen::LLT<Eigen::MatrixXd> mass_factor(const char* who, const Eigen::MatrixXd& mass);
  /// @throws std::invalid_argument unless `damper_force_kip` has one entry per damper.
  static void check_damper_forces(const char* who, const char* method, const ShearBuilding& building,
                                  const Eigen::VectorXd& damper_force_kip);
  /// The start of initialize(): checks the sizes and returns the equilibrium acceleration
  /// a₀ = M⁻¹(−M ι ü_g − C v₀ − K x₀ − Γ F₀) (in/s²) with M's factor `mass_llt`.
  static Eigen::VectorXd equilibrium_acceleration(const char* who, const ShearBuilding& building,
                                                  const Eigen::LLT<Eigen::MatrixXd>& mass_llt,
                                                  const Eigen::VectorXd& disp_in, const Eigen::VectorXd& vel_in_per_s,
                                                  double ground_accel_in_per_s2, const Eigen::VectorXd& damper_force_kip);
};

/// Builds the integrator named in `settings` (matrices computed once here).
/// @throws std::invalid_argument on an unknown kind, ρ∞ outside [0, 1] or a bad dt_s.
std::unique_ptr<Integrator> make_integrator(const ShearBuilding& building, double dt_s,
                                            const IntegratorSettings& settings);

}  // namespace structure
