#pragma once
/// @file controller.h
/// Semi-active control of the BRFD inside the hybrid loop: once per step a Controller turns
/// what a real controller measures (floor absolute accelerations, interstory drifts, each
/// damper's last measured force and drum displacement; optional sensor noise and delay) into
/// electric actuator position targets (in) for every damper, through a desired kinetic friction
/// and the inverse of Eq. (4) (control/friction_inverse.h). Laws (config `control: law:`):
///  - passive_off: hold x'_1, x'_2 (the behaviour of a run without a control block);
///  - passive_on: hold the positions of the largest friction the stroke and force limits allow;
///  - lyapunov: bang-bang on the instantaneous dissipation F·v of each damper (Dupont, Kasturi &
///    Stokes 1997, J. Sound Vib. 202(2) 203-218; the structure's energy as Lyapunov function,
///    dV/dt contains -Σ F_k v_k): Fc = max when F_k v_k >= 0, else min (the band releases its
///    stored energy into the structure; least clamping shortens that phase);
///  - clipped_optimal: Dyke, Spencer, Sain & Carlson 1996 (Smart Mater. Struct. 5 565-575): a
///    discrete LQR desired force f_d = -K x̂ from a steady-state Kalman estimate x̂ of the
///    building state from the measured floor absolute accelerations and damper forces (SLICOT
///    SB02OD for both Riccati equations), clipped to what the friction damper can give: a force
///    of the sign the damper currently produces (sign of its measured force) gets
///    Fc = clamp(|f_d|) (continuous) or Fc = max if |f_d| > |F| (on_off, Dyke's Heaviside
///    form); otherwise Fc = min;
///  - modulated_homogeneous: Inaudi 1997 (Earthquake Eng. Struct. Dyn. 26 361-376): the friction
///    is proportional to the damper deformation at its last reversal, Fc = g |d(t_s)|.
/// Allocation-free per step (everything sized at construction). Units: kip, in, s, g for
/// accelerations in the config only.

#include "common/strict_yaml.h"
#include "control/friction_inverse.h"
#include "damper/model/brfd_model.h"

#include <Eigen/Dense>

#include <memory>
#include <random>
#include <string>
#include <vector>

namespace control {

enum class Law { passive_off, passive_on, lyapunov, clipped_optimal, modulated_homogeneous };
std::string to_string(Law law);
/// @throws std::invalid_argument naming the value and the choices.
Law law_from_string(const std::string& name);

/// The `control:` block of a run config.
struct ControlConfig {
  bool enabled = false;                  ///< false: no control block (today's passive run)
  Law law = Law::passive_off;
  double min_kinetic_friction_kip = 0.25;  ///< lowest friction a law asks for, kip
  // sensors
  double accel_noise_g = 0.0;    ///< std of white noise added to each floor acceleration, g
  double drift_noise_in = 0.0;   ///< std of white noise on drifts and drum displacements, in
  double force_noise_kip = 0.0;  ///< std of white noise on the measured damper forces, kip
  int delay_steps = 0;           ///< measurements reach the controller this many steps late
  unsigned seed = 1;             ///< noise generator seed
  // clipped_optimal
  double drift_weight_per_in2 = 1.0;    ///< LQR weight on Σ drift², 1/in²
  double velocity_weight = 0.0;         ///< LQR weight on floor velocities (x'Mx scale), 1/(kip in)
  double force_weight_per_kip2 = 0.05;  ///< LQR weight on Σ F², 1/kip²
  double ground_accel_g = 0.3;          ///< Kalman process noise std (ground acceleration), g
  double sensor_noise_g = 0.01;         ///< Kalman measurement noise std, g (>= accel_noise_g)
  std::string clipping = "continuous";  ///< continuous | on_off
  // modulated_homogeneous
  double gain_kip_per_in = 8.0;  ///< Fc = gain · |drum displacement at the last reversal|
};

/// Reads a `control:` block (strict). @throws common::ConfigError naming file and key.
ControlConfig control_config_from_yaml(const common::YamlSection& section);
/// The block as YAML (top-level key `control:`), "" when !enabled.
std::string control_config_to_yaml(const ControlConfig& c);

/// What the controller needs of the building (structure/shear_building.h has them):
/// M ẍ + C ẋ + K x + Γ F = -M ι ü_g, drum displacements Γᵀ x.
struct BuildingMatrices {
  Eigen::MatrixXd mass, damping, stiffness, gamma;
};

/// One step's measurements (sizes: stories n, dampers nd). Drifts and the drum displacement
/// are those of the step the targets are for; accelerations and forces those of the last
/// completed step.
struct Measurements {
  const Eigen::VectorXd* floor_abs_accel_in_per_s2 = nullptr;  ///< n
  const Eigen::VectorXd* drift_in = nullptr;                   ///< n
  const Eigen::VectorXd* force_kip = nullptr;                  ///< nd, last measured
  const Eigen::VectorXd* drum_in = nullptr;                    ///< nd
};

class Controller {
 public:
  /// @throws std::invalid_argument / std::runtime_error when the law cannot be built.
  Controller(const ControlConfig& config, const BuildingMatrices& building, const damper::BrfdParams& damper,
             double dt_s);
  /// Back to the start of a run (estimator state, filters, delay line).
  void reset();
  /// Computes the targets (nd x 2: actuator 1, 2 in) of step `step` (>= 1). Allocation-free.
  void compute(const Measurements& m, Eigen::MatrixX2d& targets_in);

  int num_dampers() const { return nd_; }
  Law law() const { return config_.law; }
  const FrictionInverse& inverse() const { return inverse_; }
  /// Desired kinetic friction of damper k at the last compute(), kip.
  double desired_friction_kip(int k) const { return desired_fc_[k]; }
  /// clipped_optimal: the desired LQR force of damper k at the last compute(), kip.
  double desired_force_kip(int k) const { return desired_force_[k]; }
  /// clipped_optimal: gains (for tests and docs).
  const Eigen::MatrixXd& lqr_gain() const { return k_lqr_; }
  const Eigen::MatrixXd& kalman_gain() const { return l_kf_; }
  /// clipped_optimal: the state estimate x̂ = [x; ẋ] after the last compute().
  const Eigen::VectorXd& state_estimate() const { return xhat_; }

 private:
  void measure(const Measurements& m);

  ControlConfig config_;
  int n_ = 0, nd_ = 0;
  double dt_ = 0.0;
  FrictionInverse inverse_;
  // delayed, noisy measurements (ring buffer of delay_steps + 1 frames)
  int ring_len_ = 1, ring_pos_ = 0;
  long frames_ = 0;
  Eigen::MatrixXd ring_accel_, ring_drift_, ring_force_, ring_drum_;
  Eigen::VectorXd accel_, drift_, force_, drum_, drum_prev_, drum_vel_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  // law state
  std::vector<double> desired_fc_, desired_force_;
  std::vector<double> reversal_disp_, last_vel_sign_;
  bool on_off_ = false;  // clipped_optimal clipping: on_off (else continuous)
  // clipped_optimal
  Eigen::MatrixXd ad_, bd_, cy_, dy_, k_lqr_, l_kf_;
  Eigen::VectorXd xhat_, xpred_, innov_, fd_;
};

}  // namespace control
