#pragma once
/// @file monolithic_reference.h
/// Reference solutions of the building with its BRFD dampers, without any substructuring:
///  - simulate_monolithic(): SUNDIALS CVODE (BDF, dense direct linear solver) integrates the
///    building state [x, ẋ] and every damper model's internal states z (the LuGre bristle
///    state for BrfdModel) as ONE stiff ODE,
///      ẋ = v,  M v̇ = −M ι ü_g(t) − C v − K x − Γ F(z, Γᵀx, Γᵀv),
///      ż_j = DamperModel::state_rate(z_j, ·)       (Eq. 1 of the BRFD paper for BrfdModel),
///      F_j = DamperModel::force_for_states(z_j, ·)  (Eq. 3),
///    with the semi-active actuators held at their rest positions x'_1, x'_2.
/// It judges the real step loop (server::run_hybrid with an in-process substructure): see
/// tests/validation.
/// Ground acceleration is the record linearly interpolated (GroundMotion::accel_in_per_s2).
/// Units: s, in, in/s, kip.

#include "damper/model/brfd_model.h"
#include "structure/ground_motion.h"
#include "structure/response_history.h"
#include "structure/shear_building.h"

#include <Eigen/Dense>

#include <stdexcept>
#include <vector>

namespace structure {

/// Options of the CVODE reference.
struct ReferenceOptions {
  double output_dt_s = 1.0 / 1024;  ///< output interval, s (> 0)
  double duration_s = -1;           ///< simulated time, s; <= 0: the whole record
  double rtol = 1e-8;               ///< CVODE relative tolerance
  double atol = 1e-10;              ///< CVODE absolute tolerance (in, in/s and in for z)
  long max_num_steps = 10'000'000;  ///< CVodeSetMaxNumSteps: internal steps per output interval
  Eigen::VectorXd initial_floor_disp_in;       ///< x(0), in; empty: at rest
  Eigen::VectorXd initial_floor_vel_in_per_s;  ///< ẋ(0), in/s; empty: at rest
};

/// A SUNDIALS call that failed. The message names the SUNDIALS function and its return flag.
class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Integrates the building + bristle states with CVODE from rest (or the initial state in
/// `options`), the bristle states starting at z = 0. Outputs every options.output_dt_s from
/// t = 0 to the duration. Record sample times are CVODE stop times, so the solver never steps
/// across a kink of the piecewise-linear ground acceleration.
/// @param damper_per_placement one BrfdParams per building.params().dampers entry (empty for
///        a building without dampers)
/// @throws std::invalid_argument on a damper-count mismatch or bad options;
///         SolverError naming the SUNDIALS function if any SUNDIALS call fails.
ResponseHistory simulate_monolithic(const ShearBuilding& building, const GroundMotion& motion,
                                    const std::vector<damper::BrfdParams>& damper_per_placement,
                                    const ReferenceOptions& options);

}  // namespace structure
