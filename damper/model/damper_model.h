#pragma once
/// @file damper_model.h
/// The one seam every damper model implements, and the damper bank that steps a set of them.
/// The step loop (server/run), the brfd-substructure node (damper/substructure), `damper
/// predict` and the SUNDIALS monolithic reference (validation/) all go through it, so a second
/// damper type (the band-brake model) or a controller setting actuator positions plugs in
/// without touching any of them. Units: kip, in, s.
///
/// A model has two faces:
///  - discrete: step() advances its internal state over one step of the hybrid loop with the
///    input held, and returns the force at the end of the step (what a substructure answers);
///  - continuous: num_states()/state_rate()/force_for_state() give the same physics as an
///    ODE, for CVODE in the monolithic reference (validation/monolithic_reference.h).

#include <Eigen/Dense>

#include <memory>
#include <vector>

namespace damper {

/// Inputs at one instant. Drum displacement/velocity in in and in/s; actuator positions in in.
struct DamperInput {
  double drum_disp_in = 0.0;
  double drum_vel_in_per_s = 0.0;
  double actuator1_in = 0.0;   ///< x_1, electric actuator 1 position (ignored by passive models)
  double actuator2_in = 0.0;   ///< x_2, electric actuator 2 position (ignored by passive models)
};

class DamperModel {
 public:
  virtual ~DamperModel() = default;
  /// Advances the state over dt_s with `in` held; returns the force (kip, resisting +velocity)
  /// at the end of the step. Must not allocate.
  virtual double step(const DamperInput& in, double dt_s) = 0;
  /// Back to the initial state.
  virtual void reset() = 0;
  /// Actuator positions (in) the model holds when nobody commands them: x'_1, x'_2.
  virtual double actuator1_rest_in() const = 0;
  virtual double actuator2_rest_in() const = 0;

  /// Continuous form: number of internal states (the LuGre bristle state z for BrfdModel).
  virtual int num_states() const = 0;
  /// Initial value of the states (size num_states()).
  virtual void initial_states(double* states) const = 0;
  /// d(states)/dt for `states` and input `in`.
  virtual void state_rate(const double* states, const DamperInput& in, double* rate) const = 0;
  /// Force (kip) for `states` and input `in`.
  virtual double force_for_states(const double* states, const DamperInput& in) const = 0;

  /// An independent copy with the same parameters, in its initial state.
  virtual std::unique_ptr<DamperModel> fresh_copy() const = 0;
};

/// The dampers of one run, one model each, stepped together. Actuator positions default to
/// each model's rest positions; a controller sets them with set_actuators() before step().
class DamperBank {
 public:
  DamperBank() = default;
  /// `count` copies of `prototype`, each in its initial state.
  DamperBank(const DamperModel& prototype, int count);
  DamperBank(DamperBank&&) = default;
  DamperBank& operator=(DamperBank&&) = default;

  int size() const { return static_cast<int>(models_.size()); }
  /// Commanded actuator positions of damper k (in), held until set again.
  void set_actuators(int k, double actuator1_in, double actuator2_in);
  const DamperInput& input(int k) const { return inputs_[static_cast<std::size_t>(k)]; }
  DamperModel& model(int k) { return *models_[static_cast<std::size_t>(k)]; }
  const DamperModel& model(int k) const { return *models_[static_cast<std::size_t>(k)]; }

  /// Steps damper k at drum displacement/velocity (in, in/s) over dt_s; returns its force.
  double step(int k, double drum_disp_in, double drum_vel_in_per_s, double dt_s);
  /// Steps every damper; force_kip must have size() entries. Does not allocate.
  void step(const Eigen::VectorXd& drum_disp_in, const Eigen::VectorXd& drum_vel_in_per_s, double dt_s,
            Eigen::VectorXd& force_kip);
  void reset();

 private:
  std::vector<std::unique_ptr<DamperModel>> models_;
  std::vector<DamperInput> inputs_;
};

}  // namespace damper
