#pragma once
/// @file hybrid_run.h
/// One hybrid simulation: the CR step loop (structure/cr_integrator.h) exchanging drum
/// displacement and damper force with a Substructure once per step, writing results as it
/// goes so that a failure keeps every step computed so far.
///
/// Files written to the output folder:
///   time_history.csv     t, ground accel, floor displacements and absolute accelerations,
///                        interstory drifts, damper drum displacements and forces (per step)
///   summary.json         peaks, energies, status and error text
///   effective-config.yaml  every value used (re-runnable with hybridsim run --config)
///   damper-model.yaml    the damper model handed to the substructure process
///                        (server/run/substructure_session.h sets up the substructure)
///   run.lcmlog           all LCM traffic of the run (replay with lcm-logplayer)

#include "common/process.h"
#include "control/criteria.h"
#include "server/run/run_config.h"
#include "server/run/substructure.h"
#include "structure/response_history.h"

#include <Eigen/Dense>

#include <map>
#include <string>
#include <vector>

namespace server {

/// What a run produced; written to summary.json as well.
struct RunSummary {
  std::string status = "ok";          ///< "ok", "failed" or "interrupted" (SIGINT/SIGTERM)
  std::string error;                  ///< why it failed or stopped
  int signal = 0;                     ///< the signal that interrupted the run (0: none)
  /// LCM runs: messages dropped as malformed, foreign-run, forged (bad HMAC), replayed or
  /// unbound, by process ("hybridsim", "brfd-substructure") and kind ("FORCE_FEEDBACK/bad_mac").
  std::map<std::string, std::map<std::string, long>> bad_messages;
  long steps = 0;                     ///< steps completed
  double sim_time_s = 0.0;            ///< simulated time reached
  double wall_s = 0.0;                ///< wall-clock time of the run, results on disk
  double loop_wall_s = 0.0;           ///< wall-clock time of the step loop alone
  /// CPU time (CLOCK_THREAD_CPUTIME_ID) of the thread running the step loop, loop alone: what
  /// the loop costs, apart from the time a loaded machine keeps it waiting for a core.
  double loop_cpu_s = 0.0;
  /// CPU time of the whole process (CLOCK_PROCESS_CPUTIME_ID: the loop and the time-history
  /// writer thread) over the same span as wall_s.
  double cpu_s = 0.0;
  double pga_g = 0.0;                 ///< peak ground acceleration of the (scaled) record
  Eigen::VectorXd modal_periods_s;    ///< periods of the building's modes, s
  Eigen::VectorXd peak_drift_in;      ///< per story, max |interstory drift|
  Eigen::VectorXd residual_drift_in;  ///< per story, drift at the last step
  Eigen::VectorXd peak_floor_accel_g; ///< per floor, max |absolute acceleration|
  Eigen::VectorXd peak_force_kip;     ///< per damper, max |force|
  Eigen::VectorXd damper_energy_kip_in;  ///< per damper, dissipated energy ∫F·d(drum)
  double input_energy_kip_in = 0.0;
  double kinetic_energy_kip_in = 0.0;
  double strain_energy_kip_in = 0.0;
  double inherent_damping_energy_kip_in = 0.0;
  double algorithmic_energy_kip_in = 0.0;  ///< removed by the integrator (KR-α ρ∞ < 1), structure/energy.h
  double energy_balance_error = 0.0;  ///< |input − stored − dissipated| / |input|
  /// Benchmark criteria against the same building without dampers (control/criteria.h).
  control::Criteria criteria;
  double uncontrolled_peak_drift_in = 0.0, uncontrolled_peak_accel_g = 0.0, uncontrolled_peak_base_shear_kip = 0.0;
  double peak_base_shear_kip = 0.0;
  /// Semi-active control (config `control:`); empty law = no control block.
  std::string control_law;
  Eigen::VectorXd actuator_travel_in;          ///< per damper, Σ|Δx_1| + Σ|Δx_2| (actuator effort)
  Eigen::VectorXd actuator_peak_speed_in_per_s;///< per damper, max |Δx_k|/dt over both actuators
  Eigen::VectorXd actuator_min_in, actuator_max_in;  ///< per damper, extreme positions reached
  double controller_us_per_step = 0.0;        ///< mean wall time of Controller::compute
  std::string energy_definition;      ///< which ledger (structure::energy_definition_text)
  std::string integrator;             ///< e.g. "KR-alpha (Kolay & Ricles 2014), rho_inf = 0.5"
  double record_dt_s = 0.0;           ///< the record's own sample step
  ResampleDescription resampling;     ///< record step, run step, interpolation
};

/// Runs the step loop against `substructure` and writes results to config.output.dir.
/// Never throws for a substructure failure: the summary says "failed" with the reason, and
/// the time history up to the last completed step is on disk. A SIGINT/SIGTERM noticed by
/// common::interrupt_signal() stops the loop: status "interrupted", every row so far on disk.
/// Physics sanity: a non-finite state stops the run at that step, and after the loop
/// non-finite results or an energy balance error above config.max_energy_balance_error make
/// the status "failed" with the reason.
/// Throws common::ConfigError if the config does not fit the record
/// (check_run_against_record).
/// If `response` is given, every committed step (t, x, v, damper force) is also appended to
/// it: this is how validation/ judges the real loop against the CVODE reference.
RunSummary run_hybrid(const RunConfig& config, Substructure& substructure, const std::string& run_id,
                      structure::ResponseHistory* response = nullptr);

/// `hybridsim run`: sets up transport (private network namespace, LCM, spawned
/// substructure process) per the config, runs, prints the summary. Returns the exit code
/// (common::ExitCode: 0 ok, 1 run failed, 2 bad input or results folder in use, 130/143
/// interrupted by SIGINT/SIGTERM). The results folder is locked for the run
/// (common::FolderLock) and cleared of an earlier run's files (previous_run_files()).
/// duration_override_s > 0 replaces record.duration_s (`hybridsim run --duration`).
int run_command(const std::string& config_path, const std::string& output_dir_override,
                bool quiet, double duration_override_s = 0.0);

/// Files a run writes into its folder (and nothing else): an earlier run's copies are
/// removed before a new run starts, so no file of another run stands beside the new summary.
const std::vector<std::string>& previous_run_files();

/// Writes summary.json atomically (common::write_file_atomic); throws
/// common::FileWriteError naming the file (e.g. on a full disk).
void write_summary_json(const RunSummary& summary, const RunConfig& config, const std::string& path);
/// The text of summary.json (what write_summary_json writes).
std::string summary_json_text(const RunSummary& summary, const RunConfig& config);
/// Human-readable summary (the lines `hybridsim run` prints).
std::string format_summary(const RunSummary& summary);

}  // namespace server
