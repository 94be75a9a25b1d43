#pragma once
/// @file response_history.h
/// Time history of the building response sampled at fixed times, as produced by the CVODE
/// monolithic reference and by the in-process CR run. Units: s, in, in/s, kip.

#include "structure/shear_building.h"

#include <Eigen/Dense>

#include <vector>

namespace structure {

/// Response samples; all vectors have the same length (one entry per output time).
struct ResponseHistory {
  std::vector<double> time_s;                        ///< output times, s
  std::vector<Eigen::VectorXd> floor_disp_in;        ///< floor displacements relative to ground, in
  std::vector<Eigen::VectorXd> floor_vel_in_per_s;   ///< floor velocities relative to ground, in/s
  std::vector<Eigen::VectorXd> damper_force_kip;     ///< damper forces F (positive resisting positive drum velocity), kip

  std::size_t size() const { return time_s.size(); }
  /// Peak |interstory drift| of each story over the history, in (zeros if empty).
  Eigen::VectorXd peak_abs_drift_in(const ShearBuilding& building) const;
  /// Peak |floor displacement| of each floor over the history, in.
  Eigen::VectorXd peak_abs_floor_disp_in(const ShearBuilding& building) const;
  /// Peak |force| of each damper over the history, kip.
  Eigen::VectorXd peak_abs_damper_force_kip(const ShearBuilding& building) const;
};

}  // namespace structure
