#pragma once
/// @file brfd_data.h
/// Strict reader of the measured BRFD data files (/work/shared/data/brfd, JSON:
/// `{"data": [[...], ...], "dt": 0.0009765625, "sampling freq": 1024, ...}`).
///
/// Two layouts exist:
///  - 8 columns (semiactive/): time s, drum displacement in, friction force kip, velocity (see
///    below), actuator 1 position in, actuator 2 position in, actuator 1 force lb,
///    actuator 2 force lb;
///  - 6 columns (characterization/, earthquake-profiles/): time s, displacement in, friction
///    force kip, velocity in/s, actuator 1 force lb, actuator 2 force lb.
///
/// Velocity quirk of the semi-active files: their velocity column is about 1/125 of the time
/// derivative of the displacement column (not in in/s). The reader detects this (least-squares
/// ratio of the column to the derivative within `quirk_ratio_min..max`) and then DERIVES the drum
/// velocity from the displacement: central differences followed by a light zero-phase
/// (centred) moving average. It says so in BrfdTest::notes. For every other file the velocity
/// column must agree with the derivative of the displacement, otherwise it is an error.
///
/// Errors are BrfdDataError with a message naming the file, and the row and column where
/// relevant (rows and columns are counted from 0 as in the JSON array, columns also named).

#include <stdexcept>
#include <string>
#include <vector>

namespace damper {

/// Largest magnitude a value of a data file may have (s, in, kip, lb alike): 10^9. Larger
/// values are no measurement and overflow the error sums (a 1e300 kip force gave nrmse=inf).
constexpr double kMaxBrfdDataMagnitude = 1e9;

/// A user-input error in a BRFD data file.
class BrfdDataError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One measured test, in the project's units (kip, in, s; actuator forces in lb as measured).
struct BrfdTest {
  std::string path;
  double dt_s = 0.0;
  std::vector<double> time_s;
  std::vector<double> drum_disp_in;
  std::vector<double> drum_vel_in_per_s;   ///< checked column, or derived (semi-active quirk)
  std::vector<double> force_kip;           ///< measured friction (damping) force
  std::vector<double> actuator1_in;        ///< empty unless has_actuator_positions
  std::vector<double> actuator2_in;        ///< empty unless has_actuator_positions
  std::vector<double> actuator1_force_lb;
  std::vector<double> actuator2_force_lb;
  bool has_actuator_positions = false;     ///< true for the 8-column semi-active layout
  bool velocity_derived = false;           ///< true when velocity was derived from displacement
  double velocity_column_ratio = 1.0;      ///< LS ratio of the velocity column to d(disp)/dt
  std::vector<std::string> notes;          ///< what the reader did (for logs)

  std::size_t size() const { return time_s.size(); }
  /// File name without directory and extension ("harmonic0.015forward").
  std::string name() const;
};

/// Options of read_brfd_test().
struct BrfdReadOptions {
  double dt_rel_tol = 1e-6;             ///< allowed |t[i+1]-t[i]-dt| / dt
  /// Half-width (samples) of the zero-phase moving average applied to the central-difference
  /// velocity (derived velocity) and to both signals in the agreement check. 7 → 15 samples
  /// (15 ms at 1024 Hz): no visible lag or amplitude loss at the 0.5-2 Hz of the tests.
  int smoothing_half_width = 7;
  /// Agreement check: |smoothed column - smoothed derivative| must stay below
  /// vel_abs_tol + vel_rel_tol * max|derivative| at every row.
  double vel_abs_tol_in_per_s = 0.15;
  double vel_rel_tol = 0.05;
  /// Column/derivative ratio range recognised as the semi-active quirk (1/125 ≈ 0.008).
  double quirk_ratio_min = 1.0 / 160.0;
  double quirk_ratio_max = 1.0 / 100.0;
};

/// Reads and checks one data file. Throws BrfdDataError (file, row, column in the message).
BrfdTest read_brfd_test(const std::string& path, const BrfdReadOptions& options = {});

/// Central differences (one-sided at the ends) of `x` sampled every dt_s.
std::vector<double> central_difference(const std::vector<double>& x, double dt_s);
/// Centred moving average of width 2*half_width+1, zero-phase inside the record; at the ends the
/// window is clipped to the samples it covers (the average of those).
std::vector<double> centered_moving_average(const std::vector<double>& x, int half_width);
/// Drum velocity (in/s) derived from displacement: central differences + moving average.
std::vector<double> derive_velocity(const std::vector<double>& disp_in, double dt_s,
                                    int smoothing_half_width);

/// Column names of the two layouts (for messages).
const std::vector<std::string>& brfd_column_names(std::size_t column_count);

}  // namespace damper
