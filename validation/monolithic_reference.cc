#include "validation/monolithic_reference.h"

#include "structure/cr_integrator.h"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>

namespace structure {
namespace {

// ---- RAII around the SUNDIALS C handles (movable, not copyable; freed in reverse order). ----

[[noreturn]] void throw_flag(const char* function, int flag, const std::string& detail = "") {
  std::string name = "unknown flag";
  if (char* text = CVodeGetReturnFlagName(flag)) {
    name = text;
    std::free(text);
  }
  throw SolverError(std::string("SUNDIALS ") + function + " failed with flag " +
                    std::to_string(flag) + " (" + name + ")" + (detail.empty() ? "" : ": " + detail));
}

void check(int flag, const char* function) {
  if (flag < 0) throw_flag(function, flag);
}

template <typename T>
T check_ptr(T ptr, const char* function) {
  if (ptr == nullptr) throw SolverError(std::string("SUNDIALS ") + function + " returned NULL");
  return ptr;
}

struct ContextFree {
  void operator()(SUNContext c) const { SUNContext_Free(&c); }
};
struct VectorFree {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct MatrixFree {
  void operator()(SUNMatrix m) const { SUNMatDestroy(m); }
};
struct SolverFree {
  void operator()(SUNLinearSolver s) const { SUNLinSolFree(s); }
};
struct CvodeFree {
  void operator()(void* mem) const { CVodeFree(&mem); }
};

using Context = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextFree>;
using Vector = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorFree>;
using DenseMatrix = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixFree>;
using LinearSolver = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, SolverFree>;
using CvodeMemory = std::unique_ptr<void, CvodeFree>;

Context make_context() {
  SUNContext ctx = nullptr;
  check(SUNContext_Create(nullptr, &ctx), "SUNContext_Create");
  return Context(check_ptr(ctx, "SUNContext_Create"));
}

// ---- The ODE: state y = [x (n), v (n), z (nd)]. ----

// The dampers of the reference: one DamperModel each (damper/model/damper_model.h) in its
// continuous form; damper j's states sit at offset[j] in the damper part of the ODE state.
struct DamperInputs {
  const ShearBuilding* building = nullptr;
  std::vector<std::unique_ptr<damper::DamperModel>> models;
  std::vector<damper::DamperInput> inputs;  // actuator positions preset; drum filled per call
  std::vector<int> offset;                  // first state of damper j
  int num_states = 0;                       // all damper states

  void set_drum(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& v) {
    const Eigen::MatrixXd& gamma = building->damper_gamma();
    for (std::size_t j = 0; j < models.size(); ++j) {
      inputs[j].drum_disp_in = gamma.col(static_cast<Eigen::Index>(j)).dot(x);
      inputs[j].drum_vel_in_per_s = gamma.col(static_cast<Eigen::Index>(j)).dot(v);
    }
  }
};

DamperInputs make_dampers(const ShearBuilding& building, const std::vector<damper::BrfdParams>& params,
                          const char* who) {
  if (static_cast<int>(params.size()) != building.num_dampers()) {
    throw std::invalid_argument(std::string(who) + ": the building places " +
                                std::to_string(building.num_dampers()) + " dampers but " +
                                std::to_string(params.size()) + " damper parameter sets were given");
  }
  DamperInputs d;
  d.building = &building;
  for (const damper::BrfdParams& p : params) {
    d.models.push_back(damper::make_damper_model(p));
    damper::DamperInput in;
    in.actuator1_in = d.models.back()->actuator1_rest_in();
    in.actuator2_in = d.models.back()->actuator2_rest_in();
    d.inputs.push_back(in);
    d.offset.push_back(d.num_states);
    d.num_states += d.models.back()->num_states();
  }
  return d;
}

struct OdeData {
  const ShearBuilding* building = nullptr;
  const GroundMotion* motion = nullptr;
  DamperInputs dampers;
  Eigen::MatrixXd mass_inverse;
  Eigen::VectorXd mass_iota;  // M·ι
  Eigen::VectorXd force;  // scratch, kip
  Eigen::VectorXd rhs;    // scratch
  std::string error;      // exception text caught inside the C callback
  std::string solver_message;  // last message from CVODE's error handler
};

// Keeps CVODE's error text for the exception instead of printing it to stderr.
void error_handler(int /*error_code*/, const char* module, const char* function, char* msg, void* user_data) {
  static_cast<OdeData*>(user_data)->solver_message =
      std::string(module ? module : "") + "::" + (function ? function : "") + ": " + (msg ? msg : "");
}

int ode_rhs(realtype t, N_Vector y, N_Vector ydot, void* user_data) {
  auto* d = static_cast<OdeData*>(user_data);
  try {
    const Eigen::Index n = d->building->num_stories();
    const Eigen::Index nd = d->building->num_dampers();
    const Eigen::Index ns = d->dampers.num_states;
    Eigen::Map<const Eigen::VectorXd> state(N_VGetArrayPointer(y), 2 * n + ns);
    Eigen::Map<Eigen::VectorXd> rate(N_VGetArrayPointer(ydot), 2 * n + ns);
    const auto x = state.segment(0, n);
    const auto v = state.segment(n, n);
    d->dampers.set_drum(x, v);
    for (Eigen::Index j = 0; j < nd; ++j) {
      const Eigen::Index at = 2 * n + d->dampers.offset[static_cast<std::size_t>(j)];
      const damper::DamperInput& in = d->dampers.inputs[static_cast<std::size_t>(j)];
      const damper::DamperModel& model = *d->dampers.models[static_cast<std::size_t>(j)];
      model.state_rate(state.data() + at, in, rate.data() + at);
      d->force(j) = model.force_for_states(state.data() + at, in);
    }
    const double ug = d->motion->accel_in_per_s2(t);
    d->rhs.noalias() = -ug * d->mass_iota;
    d->rhs.noalias() -= d->building->damping() * v;
    d->rhs.noalias() -= d->building->stiffness() * x;
    d->rhs.noalias() -= d->building->damper_gamma() * d->force;
    rate.segment(0, n) = v;
    rate.segment(n, n).noalias() = d->mass_inverse * d->rhs;
    return std::isfinite(rate.sum()) ? 0 : 1;  // > 0: recoverable, CVODE retries a smaller step
  } catch (const std::exception& e) {
    d->error = e.what();
    return -1;
  }
}

void record_sample(ResponseHistory& h, double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                   const Eigen::VectorXd& f) {
  h.time_s.push_back(t);
  h.floor_disp_in.push_back(x);
  h.floor_vel_in_per_s.push_back(v);
  h.damper_force_kip.push_back(f);
}

}  // namespace

ResponseHistory simulate_monolithic(const ShearBuilding& building, const GroundMotion& motion,
                                    const std::vector<damper::BrfdParams>& damper_per_placement,
                                    const ReferenceOptions& options) {
  const int n = building.num_stories();
  const int nd = building.num_dampers();
  if (!(options.output_dt_s > 0.0) || !std::isfinite(options.output_dt_s)) {
    throw std::invalid_argument("simulate_monolithic: output_dt_s must be finite and > 0");
  }
  if (!(options.rtol > 0.0) || !(options.atol > 0.0)) {
    throw std::invalid_argument("simulate_monolithic: rtol and atol must be > 0");
  }
  if (!(motion.dt_s > 0.0) || motion.accel_g.size() < 2) {
    throw std::invalid_argument("simulate_monolithic: ground motion '" + motion.source +
                                "' needs dt > 0 and at least 2 samples");
  }
  const auto check_initial = [n](const Eigen::VectorXd& v, const char* what) {
    if (v.size() != 0 && v.size() != n) {
      throw std::invalid_argument(std::string("simulate_monolithic: ") + what + " must have " +
                                  std::to_string(n) + " entries (or be empty)");
    }
  };
  check_initial(options.initial_floor_disp_in, "initial_floor_disp_in");
  check_initial(options.initial_floor_vel_in_per_s, "initial_floor_vel_in_per_s");

  OdeData data;
  data.building = &building;
  data.motion = &motion;
  data.dampers = make_dampers(building, damper_per_placement, "simulate_monolithic");
  data.mass_inverse = building.mass().inverse();
  data.mass_iota = building.mass() * building.influence();
  data.force = Eigen::VectorXd::Zero(nd);
  data.rhs = Eigen::VectorXd::Zero(n);

  const double duration = options.duration_s > 0.0 ? options.duration_s : motion.duration_s();
  const long num_outputs = static_cast<long>(std::floor(duration / options.output_dt_s + 1e-9));
  const long last_sample = static_cast<long>(motion.accel_g.size()) - 1;
  const sunindextype size = 2 * n + data.dampers.num_states;

  // Declared in creation order, so they are freed in reverse (context last).
  Context ctx = make_context();
  Vector y(check_ptr(N_VNew_Serial(size, ctx.get()), "N_VNew_Serial"));
  Eigen::Map<Eigen::VectorXd> state(N_VGetArrayPointer(y.get()), size);
  state.setZero();
  if (options.initial_floor_disp_in.size() == n) state.segment(0, n) = options.initial_floor_disp_in;
  if (options.initial_floor_vel_in_per_s.size() == n) state.segment(n, n) = options.initial_floor_vel_in_per_s;
  for (int j = 0; j < nd; ++j)
    data.dampers.models[static_cast<std::size_t>(j)]->initial_states(state.data() + 2 * n +
                                                                      data.dampers.offset[static_cast<std::size_t>(j)]);
  DenseMatrix jac(check_ptr(SUNDenseMatrix(size, size, ctx.get()), "SUNDenseMatrix"));
  LinearSolver solver(check_ptr(SUNLinSol_Dense(y.get(), jac.get(), ctx.get()), "SUNLinSol_Dense"));
  CvodeMemory cvode(check_ptr(CVodeCreate(CV_BDF, ctx.get()), "CVodeCreate"));
  void* mem = cvode.get();
  check(CVodeSetErrHandlerFn(mem, error_handler, &data), "CVodeSetErrHandlerFn");
  check(CVodeInit(mem, ode_rhs, 0.0, y.get()), "CVodeInit");
  check(CVodeSetUserData(mem, &data), "CVodeSetUserData");
  check(CVodeSStolerances(mem, options.rtol, options.atol), "CVodeSStolerances");
  check(CVodeSetLinearSolver(mem, solver.get(), jac.get()), "CVodeSetLinearSolver");
  check(CVodeSetMaxNumSteps(mem, options.max_num_steps), "CVodeSetMaxNumSteps");

  ResponseHistory history;
  history.time_s.reserve(num_outputs + 1);
  history.floor_disp_in.reserve(num_outputs + 1);
  history.floor_vel_in_per_s.reserve(num_outputs + 1);
  history.damper_force_kip.reserve(num_outputs + 1);
  auto record = [&](double t) {
    const Eigen::VectorXd x = state.segment(0, n);
    const Eigen::VectorXd v = state.segment(n, n);
    data.dampers.set_drum(x, v);
    Eigen::VectorXd f(nd);
    for (int j = 0; j < nd; ++j) {
      const auto jj = static_cast<std::size_t>(j);
      f(j) = data.dampers.models[jj]->force_for_states(state.data() + 2 * n + data.dampers.offset[jj], data.dampers.inputs[jj]);
    }
    record_sample(history, t, x, v, f);
  };
  record(0.0);

  // Merge output times k·output_dt with record sample times j·dt (the kinks of ü_g, and the
  // drop to zero after the last sample); each record sample time is a CVODE stop time.
  long k = 1;
  long j = 1;
  const double tol = 1e-9 * std::min(options.output_dt_s, motion.dt_s);
  auto break_time = [&](long jj) { return jj <= last_sample ? jj * motion.dt_s : std::numeric_limits<double>::infinity(); };
  const auto set_stop_time = [&](double t_stop) {
    const int flag = CVodeSetStopTime(mem, t_stop);
    if (flag < 0) throw_flag("CVodeSetStopTime", flag, data.solver_message);
  };
  set_stop_time(std::min(break_time(j), duration + options.output_dt_s));
  while (k <= num_outputs) {
    const double t_out = k * options.output_dt_s;
    const double t_break = break_time(j);
    const bool at_break = t_break <= t_out + tol;
    const double target = at_break ? t_break : t_out;
    realtype t_reached = 0.0;
    const int flag = CVode(mem, target, y.get(), &t_reached, CV_NORMAL);
    if (flag < 0) {
      if (!data.error.empty()) throw SolverError("SUNDIALS CVode: right-hand side failed: " + data.error);
      throw_flag("CVode", flag, data.solver_message);
    }
    if (std::abs(t_out - target) <= tol) {
      record(t_out);
      ++k;
    }
    if (at_break) {
      ++j;
      set_stop_time(std::min(break_time(j), duration + options.output_dt_s));
    }
  }
  return history;
}

}  // namespace structure
