#pragma once
/// @file diagnose_bench.h
/// `hybridsim diagnose bench` (docs/diagnose.md, "Benchmark"): the hidden-effect benchmark of the
/// discrepancy workflow, with its own generator. Each trial makes two synthetic "measured"
/// semi-active records (0.5 Hz ramped drum sinusoids of 1 in and 0.8 in, electric actuator moves
/// on different strokes, 2 s at rest, white force noise), from a base model plus ONE hidden
/// effect, and runs diagnose on them from the base model (--base model) or, for the 'none/identify'
/// cases, from the base identified on the passive windows (the default path of a new user).
/// Hidden effects: every effect of the library (effects.h) at two strengths, and shapes that are
/// NOT library formulas (bench_own_shapes(): a weight-law backlash, a pure actuator delay, friction
/// growing with d², a hyperbolic force relaxation at rest), and the 'none' cases (the exact base).
/// A trial is correct when diagnose names exactly the hidden effect's family (none for none) and
/// the gap to the noise-free truth (NRMSE) at least halves.

#include "damper/data/brfd_data.h"
#include "damper/model/brfd_model.h"

#include <functional>
#include <optional>
#include <utility>
#include <string>
#include <vector>

namespace damper {

/// One hidden-effect case of the benchmark.
struct BenchCase {
  std::string name;    ///< e.g. "backlash/strong", "own:actuator_delay/weak", "none/model"
  std::string family;  ///< the library effect that should be named, or "none"
  bool identify = false;  ///< diagnose with --base identify (else --base model)
  /// Noise-free "measured" force for the inputs of `test` (time, drum, actuators filled in).
  std::function<std::vector<double>(const BrfdTest& test, const BrfdParams& base)> truth;
  /// Alternative generator (damper/synthetic shapes): the noisy records and their noise-free force
  /// for (seed, noise); when set, `truth` and the bench drives are not used and `base` is the model
  /// diagnose starts from.
  std::function<std::vector<std::pair<BrfdTest, std::vector<double>>>(unsigned seed, double noise_kip)> records;
  std::optional<BrfdParams> base;
};

/// Options of run_diagnose_bench().
struct BenchOptions {
  bool quick = false;              ///< the CI subset (one seed, one noise level, strong effects)
  int seeds = 3;
  std::vector<double> noise_kip = {0.02, 0.06};
  std::vector<std::string> only;   ///< case-name prefixes to run (empty: all)
  std::string out_dir;             ///< bench.csv (empty: none)
  std::function<void(const std::string&)> log;
  bool verbose = false;            ///< also log each diagnose report
  int effect_evals = 60;           ///< diagnose's LN_BOBYQA evaluations per start of an effect fit
  int threads = 0;                 ///< diagnose's fit threads (0: the hardware threads)
  /// diagnose's fit rate, Hz: 0 = diagnose's default, the records' own rate (no decimation; a
  /// 256 Hz fit rate leaves a discretization residual that a second effect then explained in 26 of
  /// 156 trials at noise 0.02, docs/diagnose.md).
  double fit_rate_hz = 0.0;
  /// Extra cases, appended to the matrix.
  std::vector<BenchCase> extra;
  /// Also run the shapes of damper/synthetic (written blind by another author; see
  /// hidden_shape_cases()), or only those.
  bool hidden_shapes = false, only_hidden_shapes = false;
  /// Drum motion of those records: "harmonic" (the paper's tests 1 and 4) or "earthquake" (two
  /// broadband records, EarthquakeProfile of damper/synthetic, phases from the trial's seed).
  std::string hidden_motion = "harmonic";
  /// "model": diagnose from the exact base (--base model; the none/identify cases excepted), the
  /// bench's default; "identify": every case as a user runs diagnose, each record's base LuGre
  /// identified on its passive window (the effect present there is then partly absorbed).
  std::string base = "model";
};

/// One trial's outcome.
struct BenchTrial {
  std::string case_name, family, named;  ///< named: comma-separated, or "none"
  unsigned seed = 0;
  double noise_kip = 0.0;
  double gap_before = 0.0, gap_after = 0.0;  ///< NRMSE vs the noise-free truth, mean over records
  bool correct = false, false_positive = false;
  double seconds = 0.0;
};

/// Result: trials, and the summary counts of the last line.
struct BenchResult {
  std::vector<BenchTrial> trials;
  int correct = 0, wrong = 0, false_positive = 0;
};

/// The base model of the benchmark (LuGre values close to those identified on the real tests,
/// Tables 1-2 of the paper for Eq. 4).
BrfdParams bench_base_model();
/// The library cases (every effect x weak/strong), the own non-library shapes and 'none'.
std::vector<BenchCase> bench_cases(bool quick);
/// The shapes of damper/synthetic/hidden_shapes.h (three-stage backlash, 2nd-order actuator,
/// actuator delay, displacement friction |x|^p, rate-and-state velocity friction, relaxing residual
/// force, viscous power law, asymmetry, none) at strength 0.5 and 1, on the paper's harmonic tests
/// 1 and 4 (1024 Hz, 15 s), from configs/brfd-semiactive.yaml's model. Their family labels map to
/// the library: displacement_friction -> self_energizing, velocity_friction and viscous -> velocity.
std::vector<BenchCase> hidden_shape_cases(bool quick, bool earthquake = false);
/// A one-second electric actuator move of a drive, x = x' - a sin(2π (t - t0)) for t0 <= t <
/// t0 + 1 s (retract, then extend), on actuator 1, 2 or both.
struct ActuatorPulse {
  double t0_s = 0.0, amplitude_in = 0.0;
  bool actuator1 = false, actuator2 = false;
};
/// A drive of the synthetic semi-active tests (the bench's and the diagnose tests'): the drum a
/// 0.5 Hz sinusoid of `amplitude_in` with 2 s raised-cosine ramps up and down over the motion,
/// then at rest; the actuators at x'_1, x'_2 of the model plus the pulses.
struct BenchDrive {
  double amplitude_in = 1.0;
  std::vector<ActuatorPulse> pulses;
};
/// The two drives of a trial: 1 in (actuator 1 at 3.5 s, actuator 2 at 6.5 s, both at 7.5 s) and
/// 0.8 in (actuator 2 at 4.5 s, actuator 1 at 8.5 s, both at 9.5 s).
const std::vector<BenchDrive>& bench_drive_set();
/// The input of `drive` at time t (s), drum motion over [0, motion_s), actuators from `base`.
DamperInput bench_drive_input(double t_s, const BenchDrive& drive, const BrfdParams& base, double motion_s = 12.0);
/// `drive` sampled at rate_hz over motion_s + rest_s (inputs only; force empty).
BrfdTest bench_drive(const BenchDrive& drive, const BrfdParams& base, double rate_hz, double motion_s = 12.0,
                     double rest_s = 2.0);
/// The two drives of a trial (bench_drive_set(); inputs only; force empty), at rate_hz.
std::vector<BrfdTest> bench_drives(const BrfdParams& base, double rate_hz);

/// Runs the matrix; logs one line per trial, the confusion matrix and, last,
/// "trials=<n> correct=<n> wrong=<n> false_positive=<n>".
BenchResult run_diagnose_bench(const BenchOptions& options);
std::string bench_final_line(const BenchResult& result);

}  // namespace damper
