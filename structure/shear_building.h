#pragma once
/// @file shear_building.h
/// Linear shear-building model of the numerical substructure: lumped floor masses, story
/// springs, Rayleigh damping, and the placement of the BRFD dampers between floors.
/// Units: kip, in, s (mass in kip·s²/in). Floor 1 is the lowest floor; story i joins
/// floor i−1 (floor 0 = ground) and floor i. Displacements are relative to the ground.

#include "common/strict_yaml.h"

#include <Eigen/Dense>

#include <array>
#include <string>
#include <vector>

namespace structure {

/// One BRFD between two floors.
struct DamperPlacement {
  int story = 1;                ///< 1-based story carrying the BRFD (between floors story−1 and story)
  double drum_per_drift = 1.0;  ///< drum displacement (in) per in of interstory drift; nonzero
};

/// Plain parameters of a ShearBuilding, with defaults where a default makes sense.
struct BuildingParams {
  std::vector<double> story_mass_kip_s2_per_in;    ///< floor masses, bottom floor first; each > 0
  std::vector<double> story_stiffness_kip_per_in;  ///< story stiffnesses, bottom story first; each > 0
  /// Rayleigh damping C = αM + βK: the two 1-based modes given the ratios below. The modes may
  /// be equal (e.g. [1, 1] for a single story) if the two ratios are equal; then α = ζω, β = ζ/ω.
  std::array<int, 2> damping_modes{{1, 2}};
  std::array<double, 2> damping_ratios{{0.02, 0.02}};  ///< critical-damping ratios, in [0, 1)
  std::vector<DamperPlacement> dampers;                ///< may be empty
};

/// Reads a building block (strict: unknown keys are errors). Keys:
///   story_mass_kip_s2_per_in: [..]      required, each > 0
///   story_stiffness_kip_per_in: [..]    required, same length, each > 0
///   damping: {modes: [1, 2], ratios: [0.02, 0.02]}   optional (these are the defaults)
///   dampers: [{story: 1, drum_per_drift: 1.0}, ...]  optional (default: none);
///            story in 1..N, drum_per_drift nonzero (default 1.0)
/// @throws common::ConfigError naming file, line and key path on any error.
BuildingParams building_params_from_yaml(const common::YamlSection& section);

/// Writes the params as a YAML block readable by building_params_from_yaml() (for the
/// effective config written next to results). Numbers are written with 17 significant digits.
std::string building_params_to_yaml(const BuildingParams& params);

/// Checks params for a ShearBuilding. @throws std::invalid_argument saying what is wrong.
void validate_building_params(const BuildingParams& params);

/// Undamped modes of the building, sorted by increasing frequency.
struct ModalProperties {
  Eigen::VectorXd omega_rad_per_s;  ///< natural circular frequencies ω_j, rad/s
  Eigen::VectorXd period_s;         ///< natural periods T_j = 2π/ω_j, s
  /// Mode shapes as columns, mass-normalized (φᵀMφ = I), sign chosen so the roof entry is ≥ 0.
  Eigen::MatrixXd mode_shapes;
};

/// The linear shear building: M, K, C (Rayleigh), ι and the damper matrix Γ.
/// Equation of motion in relative floor displacements x (in):
///   M ẍ + C ẋ + K x + Γ F = −M ι ü_g,
/// with F the damper forces (kip) and ü_g the ground acceleration (in/s²).
class ShearBuilding {
 public:
  /// Assembles the matrices and solves the eigenproblem.
  /// @throws std::invalid_argument on bad params (see validate_building_params()).
  explicit ShearBuilding(const BuildingParams& params);

  int num_stories() const { return static_cast<int>(params_.story_mass_kip_s2_per_in.size()); }
  int num_dampers() const { return static_cast<int>(params_.dampers.size()); }

  const Eigen::MatrixXd& mass() const { return mass_; }            ///< M, kip·s²/in (diagonal)
  const Eigen::MatrixXd& stiffness() const { return stiffness_; }  ///< K, kip/in (tridiagonal)
  const Eigen::MatrixXd& damping() const { return damping_; }      ///< C = αM + βK, kip·s/in
  const Eigen::VectorXd& influence() const { return influence_; }  ///< ι (all ones)

  /// Γ: num_stories × num_dampers. Drum displacement of the dampers = Γᵀ·x (x floor
  /// displacements relative to ground); the damper forces F (kip, force the damper exerts on
  /// its actuator, positive resisting positive drum velocity) act on the floors as −Γ·F.
  const Eigen::MatrixXd& damper_gamma() const { return gamma_; }

  /// Interstory drifts d_i = x_i − x_{i−1} (x_0 = 0), in.
  /// @throws std::invalid_argument if the size is not num_stories().
  Eigen::VectorXd interstory_drift(const Eigen::VectorXd& floor_disp_in) const;

  /// Modes of K φ = ω² M φ (Eigen::GeneralizedSelfAdjointEigenSolver).
  const ModalProperties& modal() const { return modal_; }
  double rayleigh_alpha() const { return alpha_; }  ///< α of C = αM + βK, 1/s
  double rayleigh_beta() const { return beta_; }    ///< β of C = αM + βK, s
  const BuildingParams& params() const { return params_; }

 private:
  BuildingParams params_;
  Eigen::MatrixXd mass_, stiffness_, damping_, gamma_;
  Eigen::VectorXd influence_;
  ModalProperties modal_;
  double alpha_ = 0.0;
  double beta_ = 0.0;
};

}  // namespace structure
