#include "structure/ground_motion.h"

#include "common/resource_limits.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <cctype>
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
// optional exponent with E or D — the grammar [-+]?(\d+\.?\d*|\.\d+)([EeDd][-+]?\d+)?, matched
// greedily from the start (an exponent without digits is not part of the number). Run-together
// values such as "-.12E-02-.36E-02" are split because every value must be followed by
// whitespace, a comma (two-column files), a sign or the end of the line.
// Scanned by hand: std::regex cost about 25 ms per record (60 M instructions for El Centro),
// the largest fixed cost of a short batch or IDA run (docs/step-loop-profile.md).
// Returns the end of the number starting at `p`, or `p` if none starts there.
const char* scan_number(const char* p, const char* end) {
  auto digit = [](char c) { return c >= '0' && c <= '9'; };
  const char* q = p;
  if (q != end && (*q == '-' || *q == '+')) ++q;
  if (q != end && digit(*q)) {
    while (q != end && digit(*q)) ++q;
    if (q != end && *q == '.') ++q;
    while (q != end && digit(*q)) ++q;
  } else if (q != end && *q == '.' && q + 1 != end && digit(q[1])) {
    q += 2;
    while (q != end && digit(*q)) ++q;
  } else {
    return p;
  }
  if (q != end && (*q == 'E' || *q == 'e' || *q == 'D' || *q == 'd')) {
    const char* e = q + 1;
    if (e != end && (*e == '-' || *e == '+')) ++e;
    if (e != end && digit(*e)) {
      while (e != end && digit(*e)) ++e;
      q = e;
    }
  }
  return q;
}

std::string where(const std::string& path, std::size_t line_no) {
  return path + ":" + std::to_string(line_no);
}

// Appends the finite numbers of one line to `out`. `allow_comma`: commas separate values
// (two-column). Throws RecordError naming file and line on anything else.
void parse_numbers(const std::string& line, const std::string& path, std::size_t line_no, bool allow_comma,
                   std::vector<double>& out) {
  const char* it = line.data();
  const char* const end = it + line.size();
  auto is_sep = [allow_comma](char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f' || (allow_comma && c == ',');
  };
  char token[128];
  while (it != end) {
    if (is_sep(*it)) {
      ++it;
      continue;
    }
    const char* const token_end = scan_number(it, end);
    const bool well_terminated =
        token_end != it && (token_end == end || is_sep(*token_end) || *token_end == '-' || *token_end == '+');
    if (!well_terminated) {
      const char* bad_end = it;
      while (bad_end != end && !is_sep(*bad_end)) ++bad_end;
      throw RecordError(where(path, line_no) + ": non-numeric token '" + std::string(it, bad_end) + "'");
    }
    // strtod of the token (a Fortran D exponent written as E), as before: the same doubles.
    const std::size_t length = static_cast<std::size_t>(token_end - it);
    std::string long_token;
    char* text = token;
    if (length >= sizeof token) {
      long_token.assign(it, token_end);
      text = long_token.data();
    } else {
      std::copy(it, token_end, token);
      token[length] = '\0';
    }
    for (char* c = text; *c; ++c)
      if (*c == 'D' || *c == 'd') *c = 'E';
    const double v = std::strtod(text, nullptr);
    if (!std::isfinite(v)) {
      throw RecordError(where(path, line_no) + ": value '" + std::string(it, token_end) + "' is not finite");
    }
    out.push_back(v);
    it = token_end;
  }
}

std::vector<double> parse_numbers(const std::string& line, const std::string& path, std::size_t line_no,
                                  bool allow_comma) {
  std::vector<double> out;
  parse_numbers(line, path, line_no, allow_comma, out);
  return out;
}

// Line 4 of a PEER AT2 file, matched by hand (the grammars below, case-insensitive, as the
// std::regex patterns they replace; \s is ASCII white space):
//   style a (searched anywhere): NPTS\s*=\s*(\d+)\s*,?\s*DT\s*=\s*([0-9.Ee+-]+)
//   style b (from the start):    ^\s*(\d+)\s+([0-9.Ee+-]+)\s+NPTS\s*,\s*DT
struct AT2Header {
  std::string npts, dt;  // the two captured texts
};

bool space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool dt_char(char c) { return is_digit(c) || c == '.' || c == 'E' || c == 'e' || c == '+' || c == '-'; }

/// Whether `word` (upper case) is at `i` of `s`, ignoring case.
bool word_at(const std::string& s, std::size_t i, const char* word) {
  for (; *word; ++word, ++i)
    if (i >= s.size() || std::toupper(static_cast<unsigned char>(s[i])) != *word) return false;
  return true;
}

/// First position >= `from` of `word` (upper case) in `s`, ignoring case; npos if none.
std::size_t find_word(const std::string& s, std::size_t from, const char* word) {
  for (std::size_t i = from; i < s.size(); ++i)
    if (word_at(s, i, word)) return i;
  return std::string::npos;
}

std::size_t skip(const std::string& s, std::size_t i, bool (*in)(char)) {
  while (i < s.size() && in(s[i])) ++i;
  return i;
}

bool match_header_a(const std::string& s, AT2Header& h) {
  for (std::size_t at = find_word(s, 0, "NPTS"); at != std::string::npos; at = find_word(s, at + 1, "NPTS")) {
    std::size_t i = skip(s, at + 4, space);
    if (i >= s.size() || s[i] != '=') continue;
    i = skip(s, i + 1, space);
    const std::size_t npts_begin = i;
    i = skip(s, i, is_digit);
    if (i == npts_begin) continue;
    const std::size_t npts_end = i;
    i = skip(s, i, space);
    if (i < s.size() && s[i] == ',') ++i;
    i = skip(s, i, space);
    if (!word_at(s, i, "DT")) continue;
    i = skip(s, i + 2, space);
    if (i >= s.size() || s[i] != '=') continue;
    i = skip(s, i + 1, space);
    const std::size_t dt_begin = i;
    i = skip(s, i, dt_char);
    if (i == dt_begin) continue;
    h.npts = s.substr(npts_begin, npts_end - npts_begin);
    h.dt = s.substr(dt_begin, i - dt_begin);
    return true;
  }
  return false;
}

bool match_header_b(const std::string& s, AT2Header& h) {
  std::size_t i = skip(s, 0, space);
  const std::size_t npts_begin = i;
  i = skip(s, i, is_digit);
  if (i == npts_begin) return false;
  const std::size_t npts_end = i;
  if (skip(s, i, space) == i) return false;
  i = skip(s, i, space);
  const std::size_t dt_begin = i;
  i = skip(s, i, dt_char);
  if (i == dt_begin) return false;
  const std::size_t dt_end = i;
  if (skip(s, i, space) == i) return false;
  i = skip(s, i, space);
  if (!word_at(s, i, "NPTS")) return false;
  i = skip(s, i + 4, space);
  if (i >= s.size() || s[i] != ',') return false;
  i = skip(s, i + 1, space);
  if (!word_at(s, i, "DT")) return false;
  h.npts = s.substr(npts_begin, npts_end - npts_begin);
  h.dt = s.substr(dt_begin, dt_end - dt_begin);
  return true;
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
  for (std::size_t i = 4; i < lines.size(); ++i) parse_numbers(lines[i], path, i + 1, false, gm.accel_g);
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
  AT2Header header;
  if (lines.size() >= 4 && (match_header_a(lines[3], header) || match_header_b(lines[3], header))) {
    errno = 0;
    long npts = std::strtol(header.npts.c_str(), nullptr, 10);
    if (errno == ERANGE) npts = std::numeric_limits<long>::max();
    char* dt_end = nullptr;
    const std::string& dt_text = header.dt;
    const double dt = std::strtod(dt_text.c_str(), &dt_end);
    if (dt_end != dt_text.c_str() + dt_text.size()) {
      throw RecordError(where(path, 4) + ": cannot read DT '" + dt_text + "'");
    }
    std::size_t data_chars = 0;
    for (std::size_t i = 4; i < lines.size(); ++i) data_chars += lines[i].size();
    GroundMotion gm = read_at2(lines, path, npts, dt, data_chars, header.npts);
    gm.scale = scale;
    for (double& a : gm.accel_g) a *= scale;
    return gm;
  }
  for (std::size_t i = 0; i < std::min<std::size_t>(lines.size(), 4); ++i) {
    if (find_word(lines[i], 0, "NPTS") != std::string::npos) {
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
