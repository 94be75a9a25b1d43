#include "server/run/hybrid_run.h"

#include "common/atomic_file.h"
#include "common/run_guard.h"
#include "common/strict_yaml.h"
#include "damper/model/brfd_config.h"
#include "messages/run_key.h"
#include "server/run/hdf5_time_history.h"
#include "server/run/time_history_writer.h"
#include "server/run/substructure_session.h"
#include "common/process.h"
#include "structure/integrator.h"
#include "structure/energy.h"
#include "structure/ground_motion.h"
#include "structure/shear_building.h"
#include "structure/sparse_rows.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <memory>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace server {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> time_history_columns(int stories, int dampers, bool controlled) {
  std::vector<std::string> c{"time_s", "ground_accel_g"};
  for (int i = 1; i <= stories; ++i) c.push_back("floor" + std::to_string(i) + "_disp_in");
  for (int i = 1; i <= stories; ++i) c.push_back("floor" + std::to_string(i) + "_abs_accel_g");
  for (int i = 1; i <= stories; ++i) c.push_back("story" + std::to_string(i) + "_drift_in");
  for (int k = 1; k <= dampers; ++k) c.push_back("damper" + std::to_string(k) + "_drum_disp_in");
  for (int k = 1; k <= dampers; ++k) c.push_back("damper" + std::to_string(k) + "_force_kip");
  if (controlled) {  // semi-active control: targets sent with step i, positions reached, desired Fc
    for (int k = 1; k <= dampers; ++k) {
      const std::string d = "damper" + std::to_string(k);
      for (const char* col : {"_target1_in", "_target2_in", "_actuator1_in", "_actuator2_in", "_desired_fc_kip"})
        c.push_back(d + col);
    }
  }
  return c;
}

/// Unit of a time-history column, from its name's suffix (kip, in, s; accelerations in g).
std::string column_unit(const std::string& column) {
  const std::string suffix = column.substr(column.rfind('_') + 1);
  return suffix == "s" ? "s" : suffix == "g" ? "g" : suffix == "in" ? "in" : suffix == "kip" ? "kip" : "";
}

/// The time-history file of the run in the config's output format.
std::unique_ptr<TimeHistorySink> make_time_history_sink(const RunConfig& config, const std::vector<std::string>& columns,
                                                        long expected_rows, const std::string& record_source) {
  const fs::path dir(config.output.dir);
  if (config.output.format != "hdf5") return make_csv_time_history((dir / "time_history.csv").string(), columns);
  std::vector<std::string> units;
  for (const std::string& c : columns) units.push_back(column_unit(c));
  const std::vector<std::pair<std::string, std::string>> attributes{
      {"run", config.name},
      {"record", record_source},
      {"units_system", "kip, in, s; accelerations in g"},
      {"producer", "hybridsim (server/run/hdf5_time_history.h)"},
      {"effective_config_yaml", run_config_to_yaml(config)}};
  const std::vector<std::pair<std::string, double>> numbers{
      {"dt_s", config.dt_s},
      {"record_scale", config.record.scale},
      {"output_every_n_steps", static_cast<double>(config.output.every_n_steps)}};
  return std::make_unique<Hdf5TimeHistory>((dir / "time_history.h5").string(), columns, units, attributes, numbers,
                                           expected_rows);
}

/// CPU seconds of `clock` (CLOCK_THREAD_CPUTIME_ID or CLOCK_PROCESS_CPUTIME_ID).
double cpu_seconds(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

nlohmann::json to_json(const Eigen::VectorXd& v) {
  return nlohmann::json(std::vector<double>(v.data(), v.data() + v.size()));
}

std::string make_run_id(const std::string& name) {
  return name + "-" + std::to_string(messages::now_utime()) + "-" + std::to_string(getpid());
}

/// Physical mode: adds the substructure's tracking indicators and safety record to
/// summary.json and prints them.
void report_physical(const fs::path& out, const std::string& summary_path, bool quiet) {
  try {
    nlohmann::json summary, tracking, safety;
    std::ifstream(summary_path) >> summary;
    if (fs::exists(out / "tracking.json")) std::ifstream(out / "tracking.json") >> tracking;
    if (fs::exists(out / "safety.json")) std::ifstream(out / "safety.json") >> safety;
    summary["physical"] = {{"tracking", tracking}, {"safety", safety}};
    std::ostringstream text;
    text << std::setw(2) << summary << "\n";
    common::write_file_atomic(summary_path, text.str());
    if (!tracking.is_null() && !quiet) {
      std::cout << std::setprecision(4) << "tracking: delay " << tracking.value("delay_ms", 0.0) << " ms, NRMS error "
                << tracking.value("nrms_error_pct", 0.0) << " %, peak error " << tracking.value("peak_error_in", 0.0)
                << " in (ATS " << (tracking["ats"].value("enabled", false) ? "on" : "off") << ", a1/a0 = "
                << tracking["ats"].value("equivalent_delay_ms", 0.0) << " ms)\n";
    }
    if (!safety.is_null() && !quiet) {
      std::cout << "safety: " << safety.value("status", std::string("?"))
                << (safety.value("reason", std::string()).empty() ? "" : " (" + safety.value("reason", std::string()) + ")")
                << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "hybridsim run: warning: cannot report the physical run's tracking: " << e.what() << "\n";
  }
}

}  // namespace

RunSummary run_hybrid(const RunConfig& config, Substructure& substructure, const std::string& run_id,
                      structure::ResponseHistory* response) {
  using structure::kGravity_in_per_s2;
  const structure::ShearBuilding building(config.building);
  const structure::GroundMotion record = structure::read_ground_motion(config.record.path, config.record.scale);
  const int n = building.num_stories();
  const int nd = building.num_dampers();
  const double dt = config.dt_s;
  const long num_steps = check_run_against_record(config, record.dt_s, record.duration_s(), record.source);
  const Eigen::MatrixXd& gamma = building.damper_gamma();
  // Γᵀ as compressed rows: damper k's drum motion r_k·(x[s] − x[s−1]) from its two nonzeros
  // instead of a dense n-long dot product per damper (the same sum: the dense one only adds
  // exact zeros; docs/step-loop-profile.md).
  const structure::SparseRows gamma_t = structure::sparse_rows(gamma.transpose());

  RunSummary s;
  s.pga_g = record.pga_g();
  s.record_dt_s = record.dt_s;
  s.resampling = describe_resampling(record.dt_s, dt, config.record.resample);
  s.modal_periods_s = building.modal().period_s;
  s.peak_drift_in = Eigen::VectorXd::Zero(n);
  s.residual_drift_in = Eigen::VectorXd::Zero(n);
  s.peak_floor_accel_g = Eigen::VectorXd::Zero(n);
  s.peak_force_kip = Eigen::VectorXd::Zero(nd);
  s.damper_energy_kip_in = Eigen::VectorXd::Zero(nd);

  fs::create_directories(config.output.dir);
  const bool controlled = config.control.enabled;
  const std::vector<std::string> columns = time_history_columns(n, nd, controlled);
  const long expected_rows = num_steps / config.output.every_n_steps + 1;
  TimeHistoryWriter history(make_time_history_sink(config, columns, expected_rows, record.source), columns.size(),
                        expected_rows);

  const std::unique_ptr<structure::Integrator> integrator = structure::make_integrator(building, dt, config.integrator);
  structure::Integrator& cr = *integrator;  // CR or KR-α: same substructure contract
  s.integrator = integrator->description();
  structure::EnergyLedger energy(building);
  SubstructureReply reply{Eigen::VectorXd::Zero(nd), Eigen::VectorXd::Zero(nd), Eigen::MatrixX2d::Zero(nd, 2)};
  Eigen::VectorXd force = Eigen::VectorXd::Zero(nd);       // damper forces at the current step
  Eigen::VectorXd drum = Eigen::VectorXd::Zero(nd);
  Eigen::VectorXd drum_vel = Eigen::VectorXd::Zero(nd);
  Eigen::VectorXd drift(n);
  Eigen::VectorXd abs_accel_g(n);
  // Semi-active control: the controller sees floor absolute accelerations (in/s²) and forces of
  // the last completed step, the drifts and drum displacements of the step being computed.
  std::unique_ptr<control::Controller> controller;
  const Eigen::MatrixX2d hold = [&] {
    Eigen::MatrixX2d h(nd, 2);
    h.col(0).setConstant(config.damper_model.semiactive.actuator1_initial_in);
    h.col(1).setConstant(config.damper_model.semiactive.actuator2_initial_in);
    return h;
  }();
  Eigen::MatrixX2d targets = hold, positions = hold, positions_prev = hold;
  reply.actuator_in = hold;
  Eigen::VectorXd abs_accel_in_s2 = Eigen::VectorXd::Zero(n), drift_next(n);
  if (controlled) {
    control::BuildingMatrices bm{building.mass(), building.damping(), building.stiffness(), gamma};
    controller = std::make_unique<control::Controller>(config.control, bm, config.damper_model, dt);
    substructure.set_actuator_targets(&targets);
  }
  const control::Measurements measured{&abs_accel_in_s2, &drift_next, &force, &drum};
  s.actuator_travel_in = Eigen::VectorXd::Zero(nd);
  s.actuator_peak_speed_in_per_s = Eigen::VectorXd::Zero(nd);
  s.actuator_min_in = hold.rowwise().minCoeff();
  s.actuator_max_in = hold.rowwise().maxCoeff();
  double controller_s = 0.0;
  control::ResponseStats stats(n, building.mass().diagonal());

  auto write_row = [&](double t, double ag_in_s2) {
    history.add(t);
    history.add(ag_in_s2 / kGravity_in_per_s2);
    const Eigen::VectorXd& x = cr.displacement_in();
    for (int i = 0; i < n; ++i) history.add(x[i]);
    for (int i = 0; i < n; ++i) history.add(abs_accel_g[i]);
    for (int i = 0; i < n; ++i) history.add(drift[i]);
    for (int k = 0; k < nd; ++k) history.add(reply.measured_drum_in[k]);
    for (int k = 0; k < nd; ++k) history.add(force[k]);
    if (controlled) {
      for (int k = 0; k < nd; ++k) {
        history.add(targets(k, 0));
        history.add(targets(k, 1));
        history.add(positions(k, 0));
        history.add(positions(k, 1));
        history.add(controller->desired_friction_kip(k));
      }
    }
    history.end_row();
  };

  auto record_history = [&](double t) {
    response->time_s.push_back(t);
    response->floor_disp_in.push_back(cr.displacement_in());
    response->floor_vel_in_per_s.push_back(cr.velocity_in_per_s());
    response->damper_force_kip.push_back(force);
  };
  if (response) {
    *response = structure::ResponseHistory{};
    response->time_s.reserve(static_cast<std::size_t>(num_steps) + 1);
    response->floor_disp_in.reserve(static_cast<std::size_t>(num_steps) + 1);
    response->floor_vel_in_per_s.reserve(static_cast<std::size_t>(num_steps) + 1);
    response->damper_force_kip.reserve(static_cast<std::size_t>(num_steps) + 1);
  }

  const auto wall_start = std::chrono::steady_clock::now();
  const double thread_cpu_start = cpu_seconds(CLOCK_THREAD_CPUTIME_ID);
  const double process_cpu_start = cpu_seconds(CLOCK_PROCESS_CPUTIME_ID);
  try {
    substructure.start(run_id, nd, dt);
    double ag = record.accel_in_per_s2(0.0);
    cr.initialize(ag, force);
    energy.start(cr.displacement_in(), cr.velocity_in_per_s(), ag, force);
    drift.setZero();
    abs_accel_in_s2 = cr.acceleration_in_per_s2().array() + ag;
    abs_accel_g = abs_accel_in_s2 / kGravity_in_per_s2;
    write_row(0.0, ag);
    if (response) record_history(0.0);
    long rows_until_output = config.output.every_n_steps, steps_until_flush = config.output.flush_every_steps;
    for (long i = 0; i < num_steps; ++i) {
      common::throw_if_interrupted();  // SIGINT/SIGTERM: stop here, rows so far are kept
      const double t_next = (i + 1) * dt;
      cr.predict();  // x₊, v₊ explicit: known before the damper force is needed
      {
        const double* xn = cr.next_displacement_in().data();
        const double* vn = cr.next_velocity_in_per_s().data();
        for (int k = 0; k < nd; ++k) {
          drum[k] = structure::row_dot(gamma_t, k, xn);
          drum_vel[k] = structure::row_dot(gamma_t, k, vn);
        }
      }
      if (controlled) {
        const Eigen::VectorXd& xn = cr.next_displacement_in();
        drift_next[0] = xn[0];
        for (int j = 1; j < n; ++j) drift_next[j] = xn[j] - xn[j - 1];
        const auto c0 = std::chrono::steady_clock::now();
        controller->compute(measured, targets);
        controller_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
      }
      substructure.exchange(i + 1, t_next, drum, drum_vel, reply);
      force = reply.force_kip;
      if (controlled) {
        positions = reply.actuator_in;
        for (int k = 0; k < nd; ++k) {
          const double d1 = std::abs(positions(k, 0) - positions_prev(k, 0)), d2 = std::abs(positions(k, 1) - positions_prev(k, 1));
          s.actuator_travel_in[k] += d1 + d2;
          s.actuator_peak_speed_in_per_s[k] = std::max(s.actuator_peak_speed_in_per_s[k], std::max(d1, d2) / dt);
          s.actuator_min_in[k] = std::min(s.actuator_min_in[k], positions.row(k).minCoeff());
          s.actuator_max_in[k] = std::max(s.actuator_max_in[k], positions.row(k).maxCoeff());
        }
        positions_prev = positions;
      }
      ag = record.accel_in_per_s2(t_next);
      cr.complete(ag, force);
      const double* x = cr.displacement_in().data();
      const double* v = cr.velocity_in_per_s().data();
      bool finite = true;
      for (int j = 0; j < n; ++j) finite = finite & std::isfinite(x[j]) & std::isfinite(v[j]);
      for (int k = 0; k < nd; ++k) finite = finite & std::isfinite(force[k]);
      if (!finite) {
        std::ostringstream msg;
        msg << "physics check: non-finite " << (force.allFinite() ? "building state" : "damper force")
            << " at step " << i + 1 << " (t = " << t_next
            << " s); the run is numerically unstable (check masses, stiffnesses, dt_s and the record scale)";
        throw std::runtime_error(msg.str());
      }
      energy.add_step(dt, cr.displacement_in(), cr.velocity_in_per_s(), ag, force);

      // One pass over the floors: drifts, absolute accelerations and their peaks.
      const double* a = cr.acceleration_in_per_s2().data();
      for (int j = 0; j < n; ++j) {
        drift[j] = j == 0 ? x[0] : x[j] - x[j - 1];
        abs_accel_in_s2[j] = a[j] + ag;
        abs_accel_g[j] = abs_accel_in_s2[j] / kGravity_in_per_s2;
        s.peak_drift_in[j] = std::max(s.peak_drift_in[j], std::abs(drift[j]));
        s.peak_floor_accel_g[j] = std::max(s.peak_floor_accel_g[j], std::abs(abs_accel_g[j]));
      }
      for (int k = 0; k < nd; ++k) s.peak_force_kip[k] = std::max(s.peak_force_kip[k], std::abs(force[k]));
      stats.add(drift, abs_accel_in_s2);
      // Countdowns instead of (i + 1) % n: two 64-bit divisions per step were measurable.
      if (--rows_until_output == 0) {
        write_row(t_next, ag);
        rows_until_output = config.output.every_n_steps;
      }
      if (response) record_history(t_next);
      s.steps = i + 1;
      s.sim_time_s = t_next;
      if (--steps_until_flush == 0) {
        history.hand_over();
        steps_until_flush = config.output.flush_every_steps;
      }
    }
    substructure.stop(false, "record finished");
  } catch (const common::Interrupted& e) {
    s.status = "interrupted";
    s.signal = e.signal();
    s.error = std::string(e.what()) + " after step " + std::to_string(s.steps);
    try {
      substructure.stop(true, s.error);
    } catch (const std::exception&) {
    }
  } catch (const std::exception& e) {
    s.status = "failed";
    s.error = e.what();
    try {
      substructure.stop(true, s.error);
    } catch (const std::exception&) {
    }
  }
  s.loop_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  s.loop_cpu_s = cpu_seconds(CLOCK_THREAD_CPUTIME_ID) - thread_cpu_start;
  history.finish();
  if (s.status == "ok" && !history.error().empty()) {
    s.status = "failed";
    s.error = history.error();
  }
  s.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  s.cpu_s = cpu_seconds(CLOCK_PROCESS_CPUTIME_ID) - process_cpu_start;
  s.residual_drift_in = building.interstory_drift(cr.displacement_in());
  s.damper_energy_kip_in = energy.damper_kip_in_per_damper();
  s.algorithmic_energy_kip_in = energy.algorithmic_kip_in();
  s.energy_definition = structure::energy_definition_text(energy.definition());
  s.input_energy_kip_in = energy.input_kip_in();
  s.kinetic_energy_kip_in = energy.kinetic_kip_in();
  s.strain_energy_kip_in = energy.strain_kip_in();
  s.inherent_damping_energy_kip_in = energy.inherent_damping_kip_in();
  s.energy_balance_error = energy.balance_error();
  if (controlled) {
    s.control_law = control::to_string(config.control.law);
    s.controller_us_per_step = s.steps > 0 ? 1e6 * controller_s / static_cast<double>(s.steps) : 0.0;
  }
  // The same building without dampers under the same record and steps (same integrator,
  // F = 0): the reference of the benchmark criteria J (Ohtori et al. 2004).
  if (s.steps > 0) {
    const std::unique_ptr<structure::Integrator> bare_integrator = structure::make_integrator(building, dt, config.integrator);
    structure::Integrator& bare = *bare_integrator;
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(nd);
    control::ResponseStats ref(n, building.mass().diagonal());
    Eigen::VectorXd d(n), a(n);
    bare.initialize(record.accel_in_per_s2(0.0), zero);
    for (long i = 0; i < s.steps; ++i) {
      const double t_next = (i + 1) * dt;
      bare.predict();
      const double agn = record.accel_in_per_s2(t_next);
      bare.complete(agn, zero);
      const Eigen::VectorXd& x = bare.displacement_in();
      d[0] = x[0];
      for (int j = 1; j < n; ++j) d[j] = x[j] - x[j - 1];
      a = bare.acceleration_in_per_s2().array() + agn;
      ref.add(d, a);
    }
    s.criteria = control::evaluate_criteria(stats, ref);
    s.uncontrolled_peak_drift_in = ref.peak_drift_in();
    s.uncontrolled_peak_accel_g = ref.peak_accel_in_per_s2() / kGravity_in_per_s2;
    s.uncontrolled_peak_base_shear_kip = ref.peak_base_shear_kip();
    s.peak_base_shear_kip = stats.peak_base_shear_kip();
  }
  if (s.status == "ok") {
    // Physics sanity: every reported figure finite, the energy balance closed.
    const bool finite = s.peak_drift_in.allFinite() && s.residual_drift_in.allFinite() &&
                        s.peak_floor_accel_g.allFinite() && s.peak_force_kip.allFinite() &&
                        s.damper_energy_kip_in.allFinite() && std::isfinite(s.input_energy_kip_in) &&
                        std::isfinite(s.kinetic_energy_kip_in) && std::isfinite(s.strain_energy_kip_in) &&
                        std::isfinite(s.inherent_damping_energy_kip_in) && std::isfinite(s.energy_balance_error);
    std::ostringstream msg;
    msg << std::setprecision(4);
    if (!finite) {
      s.status = "failed";
      s.error = "physics check: non-finite results (peaks or energies); the run is numerically unstable";
    } else if (s.energy_balance_error > config.max_energy_balance_error) {
      msg << "physics check: energy balance error " << 100.0 * s.energy_balance_error
          << " % exceeds run.max_energy_balance_error " << 100.0 * config.max_energy_balance_error
          << " % (input " << s.input_energy_kip_in << " kip-in; implausible damper forces or dt_s too large)";
      s.status = "failed";
      s.error = msg.str();
    }
  }
  return s;
}

void write_summary_json(const RunSummary& s, const RunConfig& config, const std::string& path) {
  common::write_file_atomic(path, summary_json_text(s, config));
}

std::string summary_json_text(const RunSummary& s, const RunConfig& config) {
  nlohmann::json j;
  j["run"] = config.name;
  j["config"] = config.source_file;
  j["record"] = config.record.path;
  j["scale"] = config.record.scale;
  j["status"] = s.status;
  j["error"] = s.error;
  if (s.signal != 0) j["signal"] = common::signal_name(s.signal);
  if (config.transport.kind == "lcm") {
    // Every LCM run says what it dropped (all zero: an empty object per process).
    nlohmann::json bad = nlohmann::json::object();
    long total = 0;
    for (const auto& [who, kinds] : s.bad_messages) {
      bad[who] = nlohmann::json::object();
      for (const auto& [kind, n] : kinds) {
        bad[who][kind] = n;
        total += n;
      }
    }
    j["bad_messages"] = bad;
    j["bad_messages_total"] = total;
    j["on_bad_message"] = config.transport.on_bad_message;
  }
  j["steps"] = s.steps;
  j["dt_s"] = config.dt_s;
  j["output_every_n_steps"] = config.output.every_n_steps;
  j["time_history_file"] = config.output.format == "hdf5" ? "time_history.h5" : "time_history.csv";
  j["sim_time_s"] = s.sim_time_s;
  j["wall_s"] = s.wall_s;
  j["step_loop_wall_s"] = s.loop_wall_s;
  j["cpu_s"] = s.cpu_s;
  j["step_loop_cpu_s"] = s.loop_cpu_s;
  j["pga_g"] = s.pga_g;
  j["modal_periods_s"] = to_json(s.modal_periods_s);
  j["peak_drift_in"] = to_json(s.peak_drift_in);
  j["residual_drift_in"] = to_json(s.residual_drift_in);
  j["peak_floor_accel_g"] = to_json(s.peak_floor_accel_g);
  j["peak_damper_force_kip"] = to_json(s.peak_force_kip);
  j["damper_energy_kip_in"] = to_json(s.damper_energy_kip_in);
  j["energy_kip_in"] = {{"input", s.input_energy_kip_in},
                        {"kinetic", s.kinetic_energy_kip_in},
                        {"strain", s.strain_energy_kip_in},
                        {"inherent_damping", s.inherent_damping_energy_kip_in},
                        {"damper", s.damper_energy_kip_in.sum()},
                        {"algorithmic", s.algorithmic_energy_kip_in},
                        {"balance_error", s.energy_balance_error},
                        {"definition", s.energy_definition}};
  j["integrator"] = {{"kind", config.integrator.kind}, {"description", s.integrator}};
  if (config.integrator.kind == "kr_alpha") j["integrator"]["rho_inf"] = config.integrator.rho_inf;
  j["record_dt_s"] = s.record_dt_s;
  j["resampling"] = {{"mode", config.record.resample},
                     {"record_dt_s", s.resampling.record_dt_s},
                     {"run_dt_s", s.resampling.run_dt_s},
                     {"steps_per_record_sample", s.resampling.steps_per_sample},
                     {"interpolation", s.resampling.text}};
  // Benchmark criteria relative to the building without dampers (Ohtori et al. 2004).
  const control::Criteria& c = s.criteria;
  j["criteria"] = {{"J1_peak_drift_ratio", c.j1},
                   {"J2_peak_floor_accel", c.j2},
                   {"J3_peak_base_shear", c.j3},
                   {"J1_rms_drift_ratio", c.j1_rms},
                   {"J2_rms_floor_accel", c.j2_rms},
                   {"J3_rms_base_shear", c.j3_rms},
                   {"peak_base_shear_kip", s.peak_base_shear_kip},
                   {"uncontrolled", {{"peak_drift_in", s.uncontrolled_peak_drift_in},
                                     {"peak_floor_accel_g", s.uncontrolled_peak_accel_g},
                                     {"peak_base_shear_kip", s.uncontrolled_peak_base_shear_kip}}}};
  if (!s.control_law.empty()) {
    j["control"] = {{"law", s.control_law},
                    {"actuator_travel_in", to_json(s.actuator_travel_in)},
                    {"actuator_peak_speed_in_per_s", to_json(s.actuator_peak_speed_in_per_s)},
                    {"actuator_min_in", to_json(s.actuator_min_in)},
                    {"actuator_max_in", to_json(s.actuator_max_in)},
                    {"controller_us_per_step", s.controller_us_per_step}};
  }
  std::ostringstream text;
  text << std::setw(2) << j << "\n";
  return text.str();
}

std::string format_summary(const RunSummary& s) {
  std::ostringstream o;
  o << std::setprecision(4);
  o << "status: " << s.status << (s.error.empty() ? "" : " (" + s.error + ")") << "\n";
  o << "steps: " << s.steps << "  simulated: " << s.sim_time_s << " s  wall: " << s.wall_s << " s\n";
  if (!s.integrator.empty()) o << "integrator: " << s.integrator << "\n";
  for (const auto& [who, kinds] : s.bad_messages) {
    long n = 0;
    for (const auto& kv : kinds) n += kv.second;
    if (n == 0) continue;
    o << "bad messages dropped by " << who << ": " << n << " (";
    const char* sep = "";
    for (const auto& [kind, k] : kinds) {
      o << sep << kind << " " << k;
      sep = ", ";
    }
    o << ")\n";
  }
  if (!s.resampling.text.empty()) o << "record: " << s.resampling.text << "\n";
  o << "PGA: " << s.pga_g << " g   modal periods (s):";
  for (int i = 0; i < s.modal_periods_s.size(); ++i) o << " " << s.modal_periods_s[i];
  o << "\n";
  for (int i = 0; i < s.peak_drift_in.size(); ++i)
    o << "story " << i + 1 << ": peak drift " << s.peak_drift_in[i] << " in, residual "
      << s.residual_drift_in[i] << " in, floor peak abs accel " << s.peak_floor_accel_g[i] << " g\n";
  for (int k = 0; k < s.peak_force_kip.size(); ++k)
    o << "damper " << k + 1 << ": peak force " << s.peak_force_kip[k] << " kip, energy dissipated "
      << s.damper_energy_kip_in[k] << " kip-in\n";
  o << "energy (kip-in): input " << s.input_energy_kip_in << " = kinetic " << s.kinetic_energy_kip_in
    << " + strain " << s.strain_energy_kip_in << " + inherent damping "
    << s.inherent_damping_energy_kip_in << " + damper " << s.damper_energy_kip_in.sum();
  if (std::abs(s.algorithmic_energy_kip_in) > 1e-9 * std::abs(s.input_energy_kip_in))
    o << " + algorithmic " << s.algorithmic_energy_kip_in;
  o << "  (balance error " << std::setprecision(2) << s.energy_balance_error << std::setprecision(4) << ")\n";
  if (!s.energy_definition.empty()) o << "  [" << s.energy_definition << "]\n";
  const control::Criteria& c = s.criteria;
  o << "criteria vs. no damper: J1 drift " << c.j1 << "  J2 accel " << c.j2 << "  J3 base shear " << c.j3
    << "  (RMS: " << c.j1_rms << " " << c.j2_rms << " " << c.j3_rms << ")\n";
  if (!s.control_law.empty()) {
    o << "control: " << s.control_law << ", controller " << s.controller_us_per_step << " us/step";
    for (int k = 0; k < s.actuator_travel_in.size(); ++k)
      o << "; damper " << k + 1 << " actuator travel " << s.actuator_travel_in[k] << " in, peak speed "
        << s.actuator_peak_speed_in_per_s[k] << " in/s, range [" << s.actuator_min_in[k] << ", " << s.actuator_max_in[k] << "] in";
    o << "\n";
  }
  return o.str();
}

const std::vector<std::string>& previous_run_files() {
  static const std::vector<std::string> files{
      "summary.json",   "time_history.csv", "effective-config.yaml", "damper-model.yaml", "run.lcmlog",
      "substructure.log", "physical.yaml",  "physical.csv",          "tracking.json",     "safety.json",
      "run.key",        "rig.log",          "rig-samples.csv", "time_history.h5",
      "substructure-messages.json"};
  return files;
}

namespace {

/// Removes an earlier run's files from `out` (only the names a run writes; anything else in
/// the folder is left alone). `keep` is a file the config points at (rig.key_file).
void clear_previous_run(const fs::path& out, const std::string& keep) {
  std::error_code ec;
  for (const std::string& name : previous_run_files()) {
    const fs::path p = out / name;
    if (!keep.empty() && fs::equivalent(p, keep, ec)) continue;
    fs::remove(p, ec);
    if (ec) throw std::runtime_error("cannot remove " + p.string() + " of an earlier run: " + ec.message());
  }
}

}  // namespace

int run_command(const std::string& config_path, const std::string& output_dir_override, bool quiet,
                double duration_override_s) {
  RunConfig config;
  try {
    config = load_run_config(config_path);
    if (!output_dir_override.empty()) config.output.dir = output_dir_override;
    if (duration_override_s > 0.0) config.record.duration_s = duration_override_s;
    // Fail early on a bad record, and on a run that does not fit the record or the disk.
    const structure::GroundMotion record = structure::read_ground_motion(config.record.path, config.record.scale);
    check_run_against_record(config, record.dt_s, record.duration_s(), record.source);
    check_resampling(config, record.dt_s);
    config.resampling_note = describe_resampling(record.dt_s, config.dt_s, config.record.resample).text;
    structure::ShearBuilding check(config.building);
  } catch (const std::exception& e) {
    std::cerr << "hybridsim run: " << e.what() << "\n";
    return common::kExitBadInput;
  }
  const fs::path out(config.output.dir);
  // One run per folder: the lock is held until this process exits (also on a crash).
  common::FolderLock lock;
  try {
    lock = common::FolderLock(config.output.dir);
    clear_previous_run(out, config.rig.rig.key_file);
  } catch (const std::exception& e) {
    std::cerr << "hybridsim run: " << e.what() << "\n";
    return common::kExitBadInput;
  }
  common::install_interrupt_handlers();
  try {
    common::write_file_atomic((out / "effective-config.yaml").string(), run_config_to_yaml(config));
  } catch (const std::exception& e) {
    std::cerr << "hybridsim run: " << e.what() << "\n";
    return common::kExitRunFailed;
  }
  const std::string run_id = make_run_id(config.name);
  const bool physical = config.damper.mode == "physical";
  const bool local_rig = launches_local_rig(config);
  if (local_rig) {
    // Check the emulator's config before anything runs, and give the run its own HMAC key.
    const std::string check_log = (out / "rig.log").string();
    fs::remove(check_log);
    try {
      ChildProcess check(sibling_executable(config.rig.rig.executable),
                         {"--config", config.rig.rig.config, "--check-config"}, check_log);
      if (check.wait_or_kill(10.0) != 0) {
        std::ifstream f(check_log);
        std::cerr << "hybridsim run: rig emulator config " << config.rig.rig.config << " is not usable:\n" << f.rdbuf();
        return common::kExitBadInput;
      }
    } catch (const std::exception& e) {
      std::cerr << "hybridsim run: rig emulator: " << e.what() << "\n";
      return common::kExitBadInput;
    }
    fs::remove(check_log);
  }

  RunSummary summary;
  try {
    SubstructureSession session(config, out.string(), run_id);
    summary = run_hybrid(config, session.substructure(), run_id);
    for (const std::string& note : session.finish(summary.status == "ok")) std::cerr << "hybridsim run: " << note << "\n";
    summary.bad_messages = session.bad_messages();
  } catch (const common::Interrupted& e) {
    summary.status = "interrupted";
    summary.signal = e.signal();
    summary.error = e.what();
  } catch (const std::exception& e) {
    summary.status = "failed";
    summary.error = e.what();
  }
  if (summary.status == "ok" && common::interrupt_signal() != 0) {
    // The signal came after the last step: the results are complete, but say so.
    summary.signal = common::interrupt_signal();
  }
  try {
    write_summary_json(summary, config, (out / "summary.json").string());
  } catch (const std::exception& e) {
    std::cerr << "hybridsim run: " << e.what() << "\n";
    if (summary.status == "ok") {
      summary.status = "failed";
      summary.error = e.what();
    }
  }
  if (!quiet) std::cout << format_summary(summary);
  if (physical) report_physical(out, (out / "summary.json").string(), quiet);
  std::cout << "results: " << fs::weakly_canonical(fs::absolute(out)).string() << "\n";
  if (summary.status == "interrupted") {
    std::cerr << "hybridsim run: " << summary.error << "; rows up to step " << summary.steps << " are in "
              << (out / "time_history.csv").string() << "\n";
    return common::exit_code_for_signal(summary.signal);
  }
  if (summary.status != "ok") {
    std::cerr << "hybridsim run: run failed: " << summary.error << "\n";
    return common::kExitRunFailed;
  }
  return common::kExitOk;
}

}  // namespace server
