#pragma once
/// @file diagnose_data.h
/// Data side of `hybridsim diagnose` (docs/diagnose.md): reading measured records (the JSON
/// test files of /work/shared/data/brfd, or a run recorded from the physical substructure,
/// physical.csv), the train/held-out split, the regimes of the motion and the localization of
/// the residual force (model − measured) in those regimes and in time windows.

#include "damper/data/brfd_data.h"
#include "damper/model/brfd_model.h"

#include <cstdint>
#include <string>
#include <vector>

namespace damper {

/// Reads one measured record. `path` is a JSON test file (read_brfd_test), a CSV recorded by
/// the physical substructure (header with `sim_time_s` or `time_s`, `measured_in` or
/// `drum_disp_in`, `force_kip` or `measured_force_kip`, optional `actuator1_in`, `actuator2_in`),
/// or a run folder holding physical.csv. The CSV's drum velocity is derived from the
/// displacement (central differences + zero-phase moving average, as for the semi-active
/// files). Throws BrfdDataError naming the file (and row, column) on bad data.
BrfdTest read_measured_record(const std::string& path, const BrfdReadOptions& options = {});

/// Expands the --measured arguments: files as given; a folder with physical.csv is one record;
/// any other folder gives its *.json files (sorted). Throws BrfdDataError if nothing is found.
std::vector<std::string> expand_measured_paths(const std::vector<std::string>& args);

/// The regimes a sample can belong to. Time-domain regimes are exclusive, in this priority:
/// after_stop, reversal, actuators, sticking, sliding. Chatter is the high-frequency part of the
/// residual at any time (see localize()).
enum class Regime : std::uint8_t { sliding = 0, reversal, sticking, actuators, after_stop, chatter };
constexpr int kRegimeCount = 6;
std::string to_string(Regime r);
/// One-line meaning of a regime, for reports.
std::string describe(Regime r);

/// Options of the split and of the regime classification.
struct SegmentationOptions {
  /// An actuator "moves" when it departs from its t = 0 position by more than this, in (the
  /// same threshold as `damper predict`).
  double actuator_motion_threshold_in = 0.002;
  /// Gaps shorter than twice this between actuator displacements count as motion, s.
  double actuator_hold_s = 0.1;
  /// Reversal detection: velocity hysteresis, as a fraction of the 95th percentile of |v|
  /// (at least 0.01 in/s).
  double reversal_hysteresis = 0.03;
  /// "Right after a velocity reversal": drum travel since the reversal below this, in.
  double reversal_travel_in = 0.25;
  /// "Sticking at low speed": |v| below this fraction of the 95th percentile of |v|.
  double sticking_speed_fraction = 0.15;
  /// "At rest": the drum stays within this of the position where it stopped (for the final rest:
  /// of its final position), in.
  double rest_band_in = 0.01;
  /// A stop between strokes holds only samples with |v| at most this, in/s (the creep into the stop
  /// and the start of the next stroke are motion).
  double rest_speed_in_per_s = 0.05;
  /// Minimum duration of a rest (between strokes or final) to count as one, s.
  double min_rest_s = 0.2;
  /// Passive records (actuators never move): fraction of the record used as the passive
  /// (base identification) window, extended to the next drum cycle boundary.
  double passive_fraction = 0.4;
  /// Chatter: the residual minus its centred moving average over this window, s (first null
  /// of the average at 1/window Hz).
  double chatter_window_s = 0.1;
};

/// How one record is cut: the passive window (base identification, training), drum cycles
/// alternating training / held-out after it, the final rest split in halves.
struct Segmentation {
  std::size_t passive_end = 0;           ///< samples [0, passive_end) are the passive window
  bool actuated = false;                 ///< the actuators move in this record
  std::vector<std::size_t> reversals;    ///< sample indices of drum reversals (displacement extrema)
  std::size_t rest_begin = 0;            ///< first sample after the excitation stops (= size if none)
  /// Every rest of the drum, [begin, end): the drum stays within rest_band_in of where it stopped
  /// for at least min_rest_s — the stops between strokes as well as the final rest (the last one,
  /// ending at the record's end, when there is a final rest). Their samples are the after_stop
  /// regime: a held force settles there whether or not the excitation resumes later.
  struct Rest {
    std::size_t begin, end;
  };
  std::vector<Rest> rests;
  std::vector<std::uint8_t> train;       ///< per sample: 1 training, 0 held-out
  std::vector<Regime> regime;            ///< per sample, time-domain regime
  std::vector<std::uint8_t> actuators_moving;  ///< per sample: the actuators move (whatever the regime)
  /// Per sample, the state of the drum alone (after_stop, reversal, sticking or sliding: the
  /// regime with the actuators left out). The drum and the actuators are two independent axes:
  /// an effect of the drum motion acts whether or not the actuators are displaced.
  std::vector<Regime> drum_regime;
  /// Per sample: 1 while the band re-loads after its force has changed sign, i.e. from the zero
  /// crossing of the measured force (with hysteresis) until the drum has travelled
  /// reversal_travel_in beyond it. A slack band lets go where its force passes through zero, which
  /// on this device comes Fc/σ0 ≈ 0.2-0.5 in of drum travel after the velocity reversal — beyond the
  /// `reversal` regime; backlash's signature is counted here too.
  std::vector<std::uint8_t> band_reloading;
  /// Contiguous spans [begin, end) with their split label, in order (for reports/figures).
  struct Span {
    std::size_t begin, end;
    bool train;
  };
  std::vector<Span> spans;
};

/// Cuts a record (see Segmentation). x'_k are the actuator positions at t = 0.
Segmentation segment_record(const BrfdTest& test, const SegmentationOptions& options = {});

/// Residual energy (sum of squared residual, kip²) per regime over a set of samples.
struct RegimeEnergy {
  double energy[kRegimeCount] = {0, 0, 0, 0, 0, 0};
  std::size_t samples[kRegimeCount] = {0, 0, 0, 0, 0, 0};  ///< chatter: all samples
  double total() const;  ///< sum over regimes (chatter included)
  RegimeEnergy& operator+=(const RegimeEnergy& o);
};

/// A time window where the residual concentrates.
struct ResidualWindow {
  std::string test;
  double t0_s = 0.0, t1_s = 0.0;
  Regime regime = Regime::sliding;
  double energy = 0.0;  ///< kip²
};

/// Splits the residual r = predicted − measured into a low-frequency part (centred moving average
/// over chatter_window_s) attributed to the sample's time-domain regime and a high-frequency part
/// attributed to chatter; sums squares per regime. `mask` (optional, same size) selects samples.
RegimeEnergy localize(const std::vector<double>& residual, const Segmentation& seg, double dt_s,
                      const SegmentationOptions& options, const std::vector<std::uint8_t>* mask = nullptr);

/// Contiguous regime runs (and 0.5 s chatter windows) of one record with their residual energy.
std::vector<ResidualWindow> residual_windows(const std::string& test_name, const std::vector<double>& time_s,
                                             const std::vector<double>& residual, const Segmentation& seg,
                                             double dt_s, const SegmentationOptions& options);

/// Low-frequency part of the residual (centred moving average), same length.
std::vector<double> low_frequency_part(const std::vector<double>& residual, double dt_s,
                                       const SegmentationOptions& options);

}  // namespace damper
