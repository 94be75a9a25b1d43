#include "structure/ground_motion.h"

#include "common/resource_limits.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>

namespace structure {

double GroundMotion::duration_s() const {
  return accel_g.size() < 2 ? 0.0 : static_cast<double>(accel_g.size() - 1) * dt_s;
}

double GroundMotion::pga_g() const {
  double peak = 0.0;
  for (double a : accel_g) peak = std::max(peak, std::abs(a));
  return peak;
}

double GroundMotion::accel_in_per_s2(double t_s) const {
  if (accel_g.empty() || !(t_s >= 0.0) || !(dt_s > 0.0)) return 0.0;
  const double u = t_s / dt_s;
  const double last = static_cast<double>(accel_g.size() - 1);
  // Tolerate round-off at the last sample (t = (N−1)·dt computed as a sum of steps).
  if (u >= last) return u <= last * (1.0 + 1e-12) + 1e-9 ? accel_g.back() * kGravity_in_per_s2 : 0.0;
  const std::size_t k = static_cast<std::size_t>(u);
  const double f = u - static_cast<double>(k);
  return ((1.0 - f) * accel_g[k] + f * accel_g[k + 1]) * kGravity_in_per_s2;
}

namespace {

// A Fortran-style real: optional sign, digits with an optional point (or a leading point),
// optional exponent with E or D. Run-together values such as "-.12E-02-.36E-02" are split
// because every value must be followed by whitespace, a comma (two-column files), a sign or
// the end of the line.
const std::regex& number_regex() {
  static const std::regex re(R"([-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?)");
  return re;
}

std::string where(const std::string& path, std::size_t line_no) {
  return path + ":" + std::to_string(line_no);
}

// Splits one line into finite numbers. `allow_comma`: commas separate values (two-column).
// Throws RecordError naming file and line on anything else.
std::vector<double> parse_numbers(const std::string& line, const std::string& path,
                                  std::size_t line_no, bool allow_comma) {
  std::vector<double> out;
  const std::regex& re = number_regex();
  auto it = line.cbegin();
  const auto end = line.cend();
  auto is_sep = [allow_comma](char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f' || (allow_comma && c == ',');
  };
  while (it != end) {
    if (is_sep(*it)) {
      ++it;
      continue;
    }
    std::smatch m;
    const bool ok = std::regex_search(it, end, m, re, std::regex_constants::match_continuous);
    const auto token_end = ok ? m[0].second : it;
    const bool well_terminated =
        ok && (token_end == end || is_sep(*token_end) || *token_end == '-' || *token_end == '+');
    if (!well_terminated) {
      auto bad_end = it;
      while (bad_end != end && !is_sep(*bad_end)) ++bad_end;
      throw RecordError(where(path, line_no) + ": non-numeric token '" + std::string(it, bad_end) + "'");
    }
    std::string token(it, token_end);
    std::replace(token.begin(), token.end(), 'D', 'E');
    std::replace(token.begin(), token.end(), 'd', 'E');
    const double v = std::strtod(token.c_str(), nullptr);
    if (!std::isfinite(v)) {
      throw RecordError(where(path, line_no) + ": value '" + std::string(it, token_end) + "' is not finite");
    }
    out.push_back(v);
    it = token_end;
  }
  return out;
}

bool blank(const std::string& line) {
  return line.find_first_not_of(" \t\r\v\f") == std::string::npos;
}

void check_dt(double dt, const std::string& at) {
  if (!std::isfinite(dt) || dt < kMinRecordDt_s || dt > kMaxRecordDt_s) {
    std::ostringstream msg;
    msg << at << ": DT = " << dt << " s is outside [" << kMinRecordDt_s << ", " << kMaxRecordDt_s
        << "] s (a record's sample interval)";
    throw RecordError(msg.str());
  }
}

GroundMotion read_at2(const std::vector<std::string>& lines, const std::string& path,
                      long npts, double dt, std::size_t data_chars, const std::string& npts_text) {
  if (npts < 2) throw RecordError(where(path, 4) + ": NPTS must be >= 2, got " + std::to_string(npts));
  if (npts > kMaxRecordSamples) {
    throw RecordError(where(path, 4) + ": NPTS = " + npts_text + " exceeds the limit of " +
                      std::to_string(kMaxRecordSamples) + " samples per record");
  }
  const double bytes = 8.0 * static_cast<double>(npts);
  if (bytes > 0.5 * static_cast<double>(common::available_memory_bytes())) {
    throw RecordError(where(path, 4) + ": NPTS = " + std::to_string(npts) + " needs " + common::format_bytes(bytes) +
                      ", more than half of the available memory (" +
                      common::format_bytes(static_cast<double>(common::available_memory_bytes())) + ")");
  }
  check_dt(dt, where(path, 4));
  GroundMotion gm;
  gm.source = path;
  gm.dt_s = dt;
  // A value takes at least one character: never reserve more than the file can hold.
  gm.accel_g.reserve(std::min(static_cast<std::size_t>(npts), data_chars));
  for (std::size_t i = 4; i < lines.size(); ++i) {
    const std::vector<double> values = parse_numbers(lines[i], path, i + 1, false);
    gm.accel_g.insert(gm.accel_g.end(), values.begin(), values.end());
  }
  const long count = static_cast<long>(gm.accel_g.size());
  if (count != npts) {
    throw RecordError(path + ": header (line 4) says NPTS = " + std::to_string(npts) + " but the file holds " +
                      std::to_string(count) + " values" +
                      (count < npts ? " (truncated record)" : " (more values than NPTS)"));
  }
  return gm;
}

GroundMotion read_two_column(const std::vector<std::string>& lines, const std::string& path) {
  std::vector<double> time_s;
  std::vector<double> accel;
  std::vector<std::size_t> line_of;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::string line = lines[i];
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    if (blank(line)) continue;
    const std::vector<double> v = parse_numbers(line, path, i + 1, true);
    if (v.size() != 2) {
      throw RecordError(where(path, i + 1) + ": expected 2 columns (time s, acceleration g), got " +
                        std::to_string(v.size()));
    }
    time_s.push_back(v[0]);
    accel.push_back(v[1]);
    line_of.push_back(i + 1);
  }
  const std::size_t n = time_s.size();
  if (n < 2) throw RecordError(path + ": a two-column record needs at least 2 samples");
  // Uniform step: every increment within 1% of the median increment (robust to one jump, so
  // the error names the line where the step changes). The step used is the mean increment.
  std::vector<double> steps(n - 1);
  for (std::size_t k = 0; k + 1 < n; ++k) steps[k] = time_s[k + 1] - time_s[k];
  std::vector<double> sorted = steps;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double median = sorted[sorted.size() / 2];
  if (!(median > 0.0)) throw RecordError(path + ": time column must increase");
  for (std::size_t k = 0; k + 1 < n; ++k) {
    if (std::abs(steps[k] - median) > 0.01 * median) {
      std::ostringstream msg;
      msg << where(path, line_of[k + 1]) << ": non-uniform time step: " << time_s[k] << " s -> "
          << time_s[k + 1] << " s, while the usual step is " << median << " s";
      throw RecordError(msg.str());
    }
  }
  const double dt = (time_s.back() - time_s.front()) / static_cast<double>(n - 1);
  check_dt(dt, path + " (time column)");
  if (std::abs(time_s.front()) > 0.01 * dt) {
    std::ostringstream msg;
    msg << where(path, line_of.front()) << ": the first time must be 0 s, got " << time_s.front() << " s";
    throw RecordError(msg.str());
  }
  GroundMotion gm;
  gm.source = path;
  gm.dt_s = dt;
  gm.accel_g = std::move(accel);
  return gm;
}

}  // namespace

GroundMotion read_ground_motion(const std::string& path, double scale) {
  if (!std::isfinite(scale) || !(scale > 0.0)) {
    std::ostringstream msg;
    msg << path << ": scale factor must be finite and > 0, got " << scale;
    throw RecordError(msg.str());
  }
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw RecordError(path + ": is a folder, not a ground-motion record");
  const auto file_bytes = std::filesystem::file_size(path, ec);
  if (!ec && static_cast<double>(file_bytes) > 0.25 * static_cast<double>(common::available_memory_bytes())) {
    throw RecordError(path + ": the file (" + common::format_bytes(static_cast<double>(file_bytes)) +
                      ") is larger than a quarter of the available memory; not a usable record");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RecordError(path + ": cannot open ground-motion record");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(std::move(line));
  }
  if (in.bad()) throw RecordError(path + ": read error");

  // PEER AT2: line 4 holds NPTS and DT in one of two styles.
  static const std::regex hdr_a(R"(NPTS\s*=\s*(\d+)\s*,?\s*DT\s*=\s*([0-9.Ee+-]+))", std::regex::icase);
  static const std::regex hdr_b(R"(^\s*(\d+)\s+([0-9.Ee+-]+)\s+NPTS\s*,\s*DT)", std::regex::icase);
  static const std::regex npts_word("NPTS", std::regex::icase);
  if (lines.size() >= 4) {
    std::smatch m;
    if (std::regex_search(lines[3], m, hdr_a) || std::regex_search(lines[3], m, hdr_b)) {
      errno = 0;
      long npts = std::strtol(m[1].str().c_str(), nullptr, 10);
      if (errno == ERANGE) npts = std::numeric_limits<long>::max();
      char* dt_end = nullptr;
      const std::string dt_text = m[2].str();
      const double dt = std::strtod(dt_text.c_str(), &dt_end);
      if (dt_end != dt_text.c_str() + dt_text.size()) {
        throw RecordError(where(path, 4) + ": cannot read DT '" + dt_text + "'");
      }
      std::size_t data_chars = 0;
      for (std::size_t i = 4; i < lines.size(); ++i) data_chars += lines[i].size();
      GroundMotion gm = read_at2(lines, path, npts, dt, data_chars, m[1].str());
      gm.scale = scale;
      for (double& a : gm.accel_g) a *= scale;
      return gm;
    }
  }
  for (std::size_t i = 0; i < std::min<std::size_t>(lines.size(), 4); ++i) {
    if (std::regex_search(lines[i], npts_word)) {
      throw RecordError(where(path, 4) +
                        ": looks like a PEER AT2 file but line 4 does not hold NPTS and DT "
                        "('NPTS= 4000, DT= .0100 SEC' or '4000 0.0100 NPTS, DT')");
    }
  }

  // Two columns: the first data line must hold exactly two numbers.
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::string line = lines[i];
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    if (blank(line)) continue;
    bool two_numbers = false;
    try {
      two_numbers = parse_numbers(line, path, i + 1, true).size() == 2;
    } catch (const RecordError&) {
      two_numbers = false;
    }
    if (!two_numbers) break;
    GroundMotion gm = read_two_column(lines, path);
    gm.scale = scale;
    for (double& a : gm.accel_g) a *= scale;
    return gm;
  }
  throw RecordError(path +
                    ": unknown ground-motion format (expected a PEER AT2 file with NPTS and DT on "
                    "line 4, or two columns: time in s, acceleration in g)");
}

}  // namespace structure
