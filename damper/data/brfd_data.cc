#include "damper/data/brfd_data.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace damper {

namespace {

const std::vector<std::string> kSemiactiveColumns = {
    "time (s)", "drum displacement (in)", "friction force (kip)", "velocity",
    "actuator 1 position (in)", "actuator 2 position (in)", "actuator 1 force (lb)",
    "actuator 2 force (lb)"};
const std::vector<std::string> kPassiveColumns = {
    "time (s)", "displacement (in)", "friction force (kip)", "velocity (in/s)",
    "actuator 1 force (lb)", "actuator 2 force (lb)"};

std::string column_label(std::size_t count, std::size_t col) {
  const auto& names = brfd_column_names(count);
  return "column " + std::to_string(col) + (col < names.size() ? " (" + names[col] + ")" : "");
}

// JSON has no NaN/Infinity, but Python's json module writes them as bare tokens. Quote them so
// that the parse succeeds and the row/column check below can name where they are.
std::string quote_nonfinite_tokens(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      out += c;
      if (c == '\\' && i + 1 < text.size()) {
        out += text[++i];
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
      out += c;
      continue;
    }
    bool replaced = false;
    for (const char* tok : {"-Infinity", "Infinity", "NaN"}) {
      const std::size_t n = std::char_traits<char>::length(tok);
      if (text.compare(i, n, tok) == 0) {
        out += '"';
        out += tok;
        out += '"';
        i += n - 1;
        replaced = true;
        break;
      }
    }
    if (!replaced) out += c;
  }
  return out;
}

}  // namespace

const std::vector<std::string>& brfd_column_names(std::size_t column_count) {
  return column_count == 8 ? kSemiactiveColumns : kPassiveColumns;
}

std::string BrfdTest::name() const {
  std::string base = path.substr(path.find_last_of('/') == std::string::npos ? 0 : path.find_last_of('/') + 1);
  const std::size_t dot = base.rfind(".json");
  return dot == std::string::npos ? base : base.substr(0, dot);
}

std::vector<double> central_difference(const std::vector<double>& x, double dt_s) {
  const std::size_t n = x.size();
  std::vector<double> d(n, 0.0);
  if (n < 2) return d;
  d[0] = (x[1] - x[0]) / dt_s;
  d[n - 1] = (x[n - 1] - x[n - 2]) / dt_s;
  for (std::size_t i = 1; i + 1 < n; ++i) d[i] = (x[i + 1] - x[i - 1]) / (2.0 * dt_s);
  return d;
}

std::vector<double> centered_moving_average(const std::vector<double>& x, int half_width) {
  const long n = static_cast<long>(x.size());
  if (half_width <= 0 || n == 0) return x;
  std::vector<double> prefix(n + 1, 0.0);
  for (long i = 0; i < n; ++i) prefix[i + 1] = prefix[i] + x[i];
  std::vector<double> y(n);
  for (long i = 0; i < n; ++i) {
    // Symmetric (zero-phase) window inside the record; at the ends the window is clipped to the
    // samples it still covers. Shrinking it symmetrically to a single sample instead left the end
    // samples unsmoothed: a derived drum velocity of one displacement quantum per sample
    // (0.06 in/s) at the first and last sample of a record at rest, a fake motion that an effect
    // triggered by reversals answered with a force jump (blind set 24 t12).
    const long lo = std::max<long>(0, i - half_width), hi = std::min<long>(n - 1, i + half_width);
    y[i] = (prefix[hi + 1] - prefix[lo]) / static_cast<double>(hi - lo + 1);
  }
  return y;
}

std::vector<double> derive_velocity(const std::vector<double>& disp_in, double dt_s,
                                    int smoothing_half_width) {
  return centered_moving_average(central_difference(disp_in, dt_s), smoothing_half_width);
}

BrfdTest read_brfd_test(const std::string& path, const BrfdReadOptions& opt) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw BrfdDataError(path + ": is a folder, not a BRFD data file");
  std::ifstream in(path);
  if (!in) throw BrfdDataError(path + ": cannot open BRFD data file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw BrfdDataError(path + ": read error");
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(quote_nonfinite_tokens(buffer.str()));
  } catch (const nlohmann::json::exception& e) {  // syntax, and numbers out of range (1e999)
    throw BrfdDataError(path + ": invalid JSON: " + e.what());
  }
  if (!doc.is_object()) throw BrfdDataError(path + ": top level must be a JSON object with key \"data\"");
  if (!doc.contains("data") || !doc["data"].is_array())
    throw BrfdDataError(path + ": missing array \"data\"");
  if (!doc.contains("dt") || !doc["dt"].is_number())
    throw BrfdDataError(path + ": missing number \"dt\" (sample period, s)");
  const double dt = doc["dt"].get<double>();
  if (!(dt > 0.0) || !std::isfinite(dt)) throw BrfdDataError(path + ": \"dt\" must be > 0");
  if (doc.contains("sampling freq") && doc["sampling freq"].is_number()) {
    const double fs = doc["sampling freq"].get<double>();
    if (std::abs(fs * dt - 1.0) > 1e-6)
      throw BrfdDataError(path + ": \"sampling freq\" " + std::to_string(fs) +
                          " Hz disagrees with \"dt\" " + std::to_string(dt) + " s");
  }
  const nlohmann::json& data = doc["data"];
  if (data.size() < 3) throw BrfdDataError(path + ": \"data\" has fewer than 3 rows");
  if (!data[0].is_array()) throw BrfdDataError(path + ": row 0 is not an array");
  const std::size_t ncol = data[0].size();
  if (ncol != 6 && ncol != 8)
    throw BrfdDataError(path + ": row 0 has " + std::to_string(ncol) +
                        " columns; expected 8 (semi-active layout) or 6 (characterization layout)");

  BrfdTest t;
  t.path = path;
  t.dt_s = dt;
  t.has_actuator_positions = ncol == 8;
  const std::size_t n = data.size();
  std::vector<std::vector<double>> cols(ncol, std::vector<double>(n));
  for (std::size_t r = 0; r < n; ++r) {
    const nlohmann::json& row = data[r];
    if (!row.is_array() || row.size() != ncol)
      throw BrfdDataError(path + ": row " + std::to_string(r) + " has " +
                          std::to_string(row.is_array() ? row.size() : 0) + " columns, expected " +
                          std::to_string(ncol) + " like row 0");
    for (std::size_t c = 0; c < ncol; ++c) {
      const nlohmann::json& v = row[c];
      if (!v.is_number()) {
        const std::string what = v.is_string() ? v.get<std::string>() : v.dump();
        throw BrfdDataError(path + ": row " + std::to_string(r) + ", " + column_label(ncol, c) +
                            ": not a finite number (" + what + ")");
      }
      const double x = v.get<double>();
      if (!std::isfinite(x))
        throw BrfdDataError(path + ": row " + std::to_string(r) + ", " + column_label(ncol, c) +
                            ": not a finite number");
      if (std::abs(x) > kMaxBrfdDataMagnitude) {
        std::ostringstream o;
        o << path << ": row " << r << ", " << column_label(ncol, c) << ": " << x
          << " is beyond any measurement of the rig (|value| > " << kMaxBrfdDataMagnitude << ")";
        throw BrfdDataError(o.str());
      }
      cols[c][r] = x;
    }
  }
  for (std::size_t r = 0; r + 1 < n; ++r) {
    const double step = cols[0][r + 1] - cols[0][r];
    if (std::abs(step - dt) > opt.dt_rel_tol * dt) {
      std::ostringstream o;
      o << std::setprecision(10) << path << ": row " << r + 1 << ", " << column_label(ncol, 0)
        << ": non-uniform time step " << step << " s after row " << r << " (dt = " << dt << " s)";
      throw BrfdDataError(o.str());
    }
  }

  t.time_s = std::move(cols[0]);
  t.drum_disp_in = std::move(cols[1]);
  t.force_kip = std::move(cols[2]);
  const std::vector<double> vel_column = std::move(cols[3]);
  if (t.has_actuator_positions) {
    t.actuator1_in = std::move(cols[4]);
    t.actuator2_in = std::move(cols[5]);
    t.actuator1_force_lb = std::move(cols[6]);
    t.actuator2_force_lb = std::move(cols[7]);
  } else {
    t.actuator1_force_lb = std::move(cols[4]);
    t.actuator2_force_lb = std::move(cols[5]);
  }

  // Velocity column against the derivative of the displacement.
  const std::vector<double> derivative = central_difference(t.drum_disp_in, dt);
  const std::vector<double> deriv_s = centered_moving_average(derivative, opt.smoothing_half_width);
  double num = 0.0, den = 0.0, peak = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    num += vel_column[i] * deriv_s[i];
    den += deriv_s[i] * deriv_s[i];
    peak = std::max(peak, std::abs(deriv_s[i]));
  }
  const double ratio = den > 0.0 ? num / den : 1.0;
  t.velocity_column_ratio = ratio;
  if (den > 0.0 && ratio >= opt.quirk_ratio_min && ratio <= opt.quirk_ratio_max) {
    // Known quirk of the semi-active files: the velocity column is ~1/125 of d(disp)/dt, not in
    // in/s. The drum velocity is derived from the displacement instead.
    t.drum_vel_in_per_s = deriv_s;
    t.velocity_derived = true;
    std::ostringstream o;
    o << std::setprecision(4) << t.name() << ": velocity column is 1/" << 1.0 / ratio
      << " of d(displacement)/dt (known quirk of the semi-active files): drum velocity derived "
         "from the displacement by central differences + "
      << 2 * opt.smoothing_half_width + 1 << "-sample centred moving average (clipped to the record at its ends)";
    t.notes.push_back(o.str());
  } else {
    const std::vector<double> col_s = centered_moving_average(vel_column, opt.smoothing_half_width);
    const double tol = opt.vel_abs_tol_in_per_s + opt.vel_rel_tol * peak;
    for (std::size_t i = 0; i < n; ++i) {
      if (std::abs(col_s[i] - deriv_s[i]) > tol) {
        std::ostringstream o;
        o << std::setprecision(5) << path << ": row " << i << ", " << column_label(ncol, 3)
          << ": velocity " << vel_column[i] << " disagrees with the derivative of the displacement "
          << deriv_s[i] << " in/s (smoothed difference " << std::abs(col_s[i] - deriv_s[i])
          << " > tolerance " << tol << " in/s; column/derivative ratio over the file " << ratio
          << ")";
        throw BrfdDataError(o.str());
      }
    }
    t.drum_vel_in_per_s = vel_column;
    std::ostringstream o;
    o << std::setprecision(4) << t.name() << ": velocity column agrees with d(displacement)/dt (ratio "
      << ratio << "), used as measured";
    t.notes.push_back(o.str());
  }
  return t;
}

}  // namespace damper
