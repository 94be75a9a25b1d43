#pragma once
/// @file relationships.h
/// Re-derives from the measured data the relationships behind Eq. (4) of the BRFD paper:
///  - scaling factors C1..C4 (paper Figs. 6-7, Table 2): slope of the friction force against
///    an electric actuator's force during kinetic friction, per drum rotation direction.
///    Forward rotation (v >= 0): actuator 2 taut, actuator 1 slack; backward: the reverse.
///    C1 = fwd/actuator 1 (slack), C2 = fwd/actuator 2 (taut), C3 = bwd/actuator 1 (taut),
///    C4 = bwd/actuator 2 (slack), matching the rows m_1j..m_4j of Table 1;
///  - force amplification factors (Figs. 9-10): damping force over slack-actuator force during
///    kinetic friction, per direction;
///  - from the semi-active tests, the average increase of the amplification factor on drum
///    strokes where the electric actuators move vs strokes where they hold (paper: ~33%).
/// Forces are compared in the same unit (kip): actuator load cells (lb) are divided by 1000.

#include "damper/data/brfd_data.h"

#include <array>
#include <string>
#include <vector>

namespace damper {

/// Options of the relationship analysis.
struct RelationshipsOptions {
  /// Kinetic friction samples: |v| >= this fraction of the test's peak |v| and the force in the
  /// direction of motion (excludes the stick/backlash phase after each reversal).
  double kinetic_speed_fraction = 0.5;
  /// Semi-active strokes count only if their peak |v| reaches this fraction of the test's peak
  /// (drops the ramp-up/down strokes).
  double full_stroke_fraction = 0.8;
  double actuator_motion_threshold_in = 0.002;
  /// Characterization files whose name contains one of these are listed but left out of the
  /// means (the data's authors: some 0 lb tests measured band tension incorrectly).
  std::vector<std::string> exclude_from_mean = {"Hz0lbtension"};
};

/// Straight line fitted to (actuator force kip, |friction force| kip).
struct LineFit {
  double slope = 0.0;          ///< ordinary least squares slope (the scaling factor)
  double intercept_kip = 0.0;
  double slope_origin = 0.0;   ///< least squares slope through the origin (= force ratio)
  double r2 = 0.0;
  std::size_t samples = 0;
};

/// Fits |y| against x by OLS and through the origin.
LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y);

/// One passive test (a characterization test, or the unactuated samples of a semi-active test).
struct CharacterizationRelations {
  std::string name;
  bool in_mean = true;
  std::array<LineFit, 4> scaling;         ///< C1..C4 (see file comment)
  double amplification_fwd = 0.0;         ///< mean |F| / mean slack-actuator force, forward
  double amplification_bwd = 0.0;
  double slack_force_fwd_lb = 0.0;        ///< mean slack-actuator force during kinetic friction
  double slack_force_bwd_lb = 0.0;
  double taut_force_fwd_lb = 0.0;
  double taut_force_bwd_lb = 0.0;
};

/// One drum stroke (between reversals) of a semi-active test, kinetic friction samples only.
struct StrokeAmplification {
  double t_start_s = 0.0, t_end_s = 0.0;
  bool forward = true;
  bool actuated = false;          ///< an actuator is off x' during the stroke's kinetic friction
  double mean_force_kip = 0.0;    ///< mean |F|
  double peak_force_kip = 0.0;    ///< max of |F| smoothed over 15 samples
  double mean_slack_lb = 0.0;     ///< mean slack-actuator force
  double af_mean = 0.0;           ///< amplification factor: mean |F| / mean slack force
  double af_peak = 0.0;           ///< amplification factor: peak |F| / mean slack force
};

/// Relative increase of a quantity on actuated strokes vs unactuated full strokes of the same
/// direction (mean over strokes of each kind; NaN if either kind is missing).
struct Increase {
  double unactuated = 0.0, actuated = 0.0, increase = 0.0;
};

/// One semi-active test: its strokes and the amplification increase of actuated strokes.
struct SemiactiveAmplification {
  std::string name;
  std::vector<StrokeAmplification> strokes;
  bool forward_actuated = true;   ///< direction of the actuated strokes
  Increase af_mean;               ///< of StrokeAmplification::af_mean
  Increase af_peak;               ///< of StrokeAmplification::af_peak
  Increase peak_force;            ///< of the peak damping force itself
  CharacterizationRelations passive;  ///< scaling factors on the unactuated samples
};

/// Whole analysis.
struct RelationshipsReport {
  std::vector<CharacterizationRelations> characterization;
  std::array<double, 4> mean_slope{};        ///< mean OLS slope over tests in the mean
  std::array<double, 4> mean_slope_origin{};  ///< mean through-origin slope
  std::array<double, 4> table2{{119.68, 2.10, 1.94, 123.31}};
  std::vector<SemiactiveAmplification> semiactive;
  std::array<double, 4> semiactive_mean_slope_origin{};  ///< C1..C4 from unactuated samples
  std::array<double, 4> semiactive_mean_slope{};
  /// Averages over the semi-active tests of Increase::increase (paper: about 33%).
  double mean_increase_af_mean = 0.0, mean_increase_af_peak = 0.0, mean_increase_peak_force = 0.0;
  std::vector<std::string> notes;
};

/// Scaling and amplification factors of a passive test. For a semi-active file only the
/// samples with both actuators at x'_1, x'_2 (within the motion threshold) are used.
CharacterizationRelations characterization_relations(const BrfdTest& test,
                                                     const RelationshipsOptions& options);
/// Analyses one semi-active test (8 columns).
SemiactiveAmplification semiactive_amplification(const BrfdTest& test,
                                                 const RelationshipsOptions& options);
/// Reads DIR/characterization/*.json and DIR/semiactive/*.json (either may be absent, not both).
/// Throws BrfdDataError / std::invalid_argument.
RelationshipsReport derive_relationships(const std::string& data_dir,
                                         const RelationshipsOptions& options);
/// The printed tables (per test, means beside Table 2, amplification increase).
std::string format_relationships(const RelationshipsReport& report);

}  // namespace damper
