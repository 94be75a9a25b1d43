#pragma once
/// @file ground_motion.h
/// Earthquake ground-acceleration records: reading PEER NGA "AT2" files and two-column
/// (time, acceleration) text files, and evaluating the acceleration at any time.
/// Records hold acceleration in g; the structure sees in/s² (× kGravity_in_per_s2).

#include <stdexcept>
#include <string>
#include <vector>

namespace structure {

/// Standard gravity in in/s² (9.80665 m/s² / 0.0254 m/in = 386.0886 in/s²).
constexpr double kGravity_in_per_s2 = 386.09;

/// Sample intervals a record may have: 10 µs (100 kHz) to 1 s. Outside this a DT is a typo or
/// a unit error (ms for s), not an earthquake record.
constexpr double kMinRecordDt_s = 1e-5;
constexpr double kMaxRecordDt_s = 1.0;
/// Most samples a record may hold: 5·10^7 (400 MB of doubles, 69 h at 200 Hz). NPTS above
/// this, or above what the file's size or the machine's available memory can hold, is refused
/// before anything is allocated.
constexpr long kMaxRecordSamples = 50'000'000;

/// A uniformly sampled ground-acceleration record: sample k is at t = k·dt_s.
struct GroundMotion {
  std::string source;           ///< file it was read from (or a description)
  double dt_s = 0.0;            ///< sample interval, s (> 0)
  std::vector<double> accel_g;  ///< ground acceleration in g, already multiplied by `scale`
  double scale = 1.0;           ///< scale factor that was applied to the file's values

  /// (N − 1)·dt, s; 0 for fewer than two samples.
  double duration_s() const;
  /// Peak ground acceleration max|a|, g (scaled).
  double pga_g() const;
  /// Ground acceleration at t (in/s²): linear interpolation between samples, 0 before t = 0
  /// and after the last sample. Allocates nothing (usable in the real-time loop).
  double accel_in_per_s2(double t_s) const;
};

/// A record file that cannot be used. The message names the file (and the line where
/// relevant), e.g. "records/x.AT2:17: non-numeric token 'abc'".
class RecordError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Reads a ground-motion record and multiplies it by `scale`. The format is detected:
///  - PEER NGA AT2: 4 header lines, line 4 `NPTS= 4000, DT= .0100 SEC` (any spacing, trailing
///    text allowed) or `4000 0.0100 NPTS, DT`; then values in g in Fortran E format, any
///    number per line, possibly run together (`-.1234E-02-.3616E-02`); LF or CRLF.
///    The number of values must equal NPTS.
///  - Two columns: time (s) and acceleration (g) per line, separated by whitespace or a comma;
///    blank lines and `#` comments allowed; the time step must be uniform and start at t = 0.
/// Non-numeric tokens, NaN and infinite values are rejected. DT must lie in
/// [kMinRecordDt_s, kMaxRecordDt_s]; NPTS at most kMaxRecordSamples and what fits in memory.
/// @param scale multiplies every value; must be finite and > 0.
/// @throws RecordError naming the file (and line) if the file is missing, of unknown format,
///         truncated (NPTS mismatch: expected and actual counts), has a non-numeric token, a
///         non-finite value, a non-uniform time step, or if `scale` is invalid.
GroundMotion read_ground_motion(const std::string& path, double scale = 1.0);

}  // namespace structure
