#include "damper/diagnose/diagnose_data.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace damper {

namespace {

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) {
    while (!cell.empty() && (cell.back() == '\r' || cell.back() == ' ')) cell.pop_back();
    while (!cell.empty() && cell.front() == ' ') cell.erase(cell.begin());
    out.push_back(cell);
  }
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

int find_column(const std::vector<std::string>& header, std::initializer_list<const char*> names) {
  for (const char* n : names) {
    const auto it = std::find(header.begin(), header.end(), n);
    if (it != header.end()) return static_cast<int>(it - header.begin());
  }
  return -1;
}

BrfdTest read_run_csv(const std::string& path, const BrfdReadOptions& opt) {
  std::ifstream in(path);
  if (!in) throw BrfdDataError(path + ": cannot open");
  std::string line;
  if (!std::getline(in, line)) throw BrfdDataError(path + ": empty file (no header line)");
  const std::vector<std::string> header = split_csv_line(line);
  const int c_t = find_column(header, {"sim_time_s", "time_s"});
  const int c_d = find_column(header, {"measured_in", "drum_disp_in"});
  const int c_f = find_column(header, {"force_kip", "measured_force_kip"});
  const int c_x1 = find_column(header, {"actuator1_in"});
  const int c_x2 = find_column(header, {"actuator2_in"});
  const int c_f1 = find_column(header, {"actuator1_force_lb"});
  const int c_f2 = find_column(header, {"actuator2_force_lb"});
  if (c_t < 0 || c_d < 0 || c_f < 0) {
    throw BrfdDataError(path + ": header needs a time column (sim_time_s or time_s), a drum displacement "
                        "column (measured_in or drum_disp_in) and a force column (force_kip or measured_force_kip)");
  }
  if ((c_x1 < 0) != (c_x2 < 0)) throw BrfdDataError(path + ": give both actuator1_in and actuator2_in or neither");
  BrfdTest t;
  t.path = path;
  t.has_actuator_positions = c_x1 >= 0;
  std::size_t row = 0;
  while (std::getline(in, line)) {
    ++row;
    if (line.empty() || line == "\r") continue;
    const std::vector<std::string> cells = split_csv_line(line);
    if (cells.size() != header.size()) {
      throw BrfdDataError(path + ": row " + std::to_string(row) + ": " + std::to_string(cells.size()) +
                          " values, the header has " + std::to_string(header.size()));
    }
    auto value = [&](int c) {
      std::size_t used = 0;
      double v = NAN;
      try {
        v = std::stod(cells[static_cast<std::size_t>(c)], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != cells[static_cast<std::size_t>(c)].size() || !std::isfinite(v)) {
        throw BrfdDataError(path + ": row " + std::to_string(row) + ", column " + std::to_string(c) + " (" +
                            header[static_cast<std::size_t>(c)] + "): not a finite number: '" +
                            cells[static_cast<std::size_t>(c)] + "'");
      }
      return v;
    };
    t.time_s.push_back(value(c_t));
    t.drum_disp_in.push_back(value(c_d));
    t.force_kip.push_back(value(c_f));
    if (t.has_actuator_positions) {
      t.actuator1_in.push_back(value(c_x1));
      t.actuator2_in.push_back(value(c_x2));
    }
    t.actuator1_force_lb.push_back(c_f1 >= 0 ? value(c_f1) : 0.0);
    t.actuator2_force_lb.push_back(c_f2 >= 0 ? value(c_f2) : 0.0);
  }
  if (t.size() < 100) throw BrfdDataError(path + ": " + std::to_string(t.size()) + " rows (need at least 100)");
  t.dt_s = (t.time_s.back() - t.time_s.front()) / static_cast<double>(t.size() - 1);
  if (!(t.dt_s > 0.0)) throw BrfdDataError(path + ": time does not increase");
  for (std::size_t i = 1; i < t.size(); ++i) {
    const double d = t.time_s[i] - t.time_s[i - 1];
    if (std::abs(d - t.dt_s) > 1e-3 * t.dt_s + opt.dt_rel_tol * t.dt_s) {
      throw BrfdDataError(path + ": row " + std::to_string(i + 1) + ", column " + std::to_string(c_t) + " (" +
                          header[static_cast<std::size_t>(c_t)] + "): time step " + std::to_string(d) +
                          " s differs from the mean step " + std::to_string(t.dt_s) + " s (need uniform sampling)");
    }
  }
  t.drum_vel_in_per_s = derive_velocity(t.drum_disp_in, t.dt_s, opt.smoothing_half_width);
  t.velocity_derived = true;
  t.notes.push_back(t.name() + ": recorded run (CSV): drum velocity derived from " +
                    header[static_cast<std::size_t>(c_d)] + " by central differences + " +
                    std::to_string(2 * opt.smoothing_half_width + 1) + "-sample centred moving average (clipped to the record at its ends)");
  return t;
}

double percentile_abs(const std::vector<double>& x, double q) {
  std::vector<double> a(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) a[i] = std::abs(x[i]);
  if (a.empty()) return 0.0;
  const std::size_t k = std::min(a.size() - 1, static_cast<std::size_t>(q * static_cast<double>(a.size())));
  std::nth_element(a.begin(), a.begin() + static_cast<long>(k), a.end());
  return a[k];
}

int half_width_samples(double window_s, double dt_s) {
  return std::max(1, static_cast<int>(std::lround(0.5 * window_s / dt_s)));
}

}  // namespace

BrfdTest read_measured_record(const std::string& path, const BrfdReadOptions& options) {
  if (fs::is_directory(path)) {
    const fs::path csv = fs::path(path) / "physical.csv";
    if (!fs::exists(csv)) throw BrfdDataError(path + ": folder without physical.csv");
    return read_run_csv(csv.string(), options);
  }
  const std::string ext = fs::path(path).extension().string();
  if (ext == ".csv") return read_run_csv(path, options);
  return read_brfd_test(path, options);
}

std::vector<std::string> expand_measured_paths(const std::vector<std::string>& args) {
  std::vector<std::string> out;
  for (const std::string& a : args) {
    if (!fs::exists(a)) throw BrfdDataError(a + ": no such file or folder");
    if (!fs::is_directory(a) || fs::exists(fs::path(a) / "physical.csv")) {
      out.push_back(a);
      continue;
    }
    std::vector<std::string> found;
    for (const auto& e : fs::directory_iterator(a))
      if (e.is_regular_file() && e.path().extension() == ".json") found.push_back(e.path().string());
    std::sort(found.begin(), found.end());
    if (found.empty()) throw BrfdDataError(a + ": folder holds no *.json test and no physical.csv");
    out.insert(out.end(), found.begin(), found.end());
  }
  if (out.empty()) throw BrfdDataError("no measured data given");
  return out;
}

std::string to_string(Regime r) {
  switch (r) {
    case Regime::sliding: return "sliding";
    case Regime::reversal: return "reversal";
    case Regime::sticking: return "sticking";
    case Regime::actuators: return "actuators";
    case Regime::after_stop: return "after_stop";
    case Regime::chatter: return "chatter";
  }
  return "?";
}

std::string describe(Regime r) {
  switch (r) {
    case Regime::sliding: return "steady sliding";
    case Regime::reversal: return "right after a velocity reversal";
    case Regime::sticking: return "sticking at low speed";
    case Regime::actuators: return "while the electric actuators move";
    case Regime::after_stop: return "at rest after the drum stops";
    case Regime::chatter: return "high-frequency chatter";
  }
  return "?";
}

Segmentation segment_record(const BrfdTest& t, const SegmentationOptions& o) {
  const std::size_t n = t.size();
  Segmentation s;
  s.train.assign(n, 1);
  s.regime.assign(n, Regime::sliding);
  s.drum_regime.assign(n, Regime::sliding);
  if (n == 0) return s;
  const std::vector<double>& d = t.drum_disp_in;
  const std::vector<double>& v = t.drum_vel_in_per_s;

  // Rest after the excitation: the drum stays within rest_band_in of its final position.
  std::size_t rest = n;
  while (rest > 0 && std::abs(d[rest - 1] - d[n - 1]) <= o.rest_band_in) --rest;
  if (static_cast<double>(n - rest) * t.dt_s < o.min_rest_s || rest == 0) rest = n;
  s.rest_begin = rest;

  // Reversals: velocity sign changes with hysteresis, placed at the displacement extremum.
  const double v95 = percentile_abs(std::vector<double>(v.begin(), v.begin() + static_cast<long>(rest)), 0.95);
  const double vh = std::max(0.01, o.reversal_hysteresis * v95);
  int dir = 0;
  std::size_t extremum = 0;
  std::vector<std::size_t> minima;  // backward-to-forward reversals: the drum cycle boundaries
  for (std::size_t i = 0; i < rest; ++i) {
    if (dir > 0 && d[i] > d[extremum]) extremum = i;
    if (dir < 0 && d[i] < d[extremum]) extremum = i;
    if (v[i] > vh && dir <= 0) {
      if (dir < 0) {
        s.reversals.push_back(extremum);
        minima.push_back(extremum);
      }
      dir = 1;
      extremum = i;
    } else if (v[i] < -vh && dir >= 0) {
      if (dir > 0) s.reversals.push_back(extremum);
      dir = -1;
      extremum = i;
    }
  }

  // Passive window: until the first actuator motion; records whose actuators never move use the
  // first passive_fraction of the motion, extended to the next backward-to-forward reversal.
  std::size_t first_motion = n;
  if (t.has_actuator_positions) {
    for (std::size_t i = 0; i < n; ++i) {
      if (std::abs(t.actuator1_in[i] - t.actuator1_in[0]) > o.actuator_motion_threshold_in ||
          std::abs(t.actuator2_in[i] - t.actuator2_in[0]) > o.actuator_motion_threshold_in) {
        first_motion = i;
        break;
      }
    }
  }
  s.actuated = first_motion < n;
  // Cycle boundaries: reversals from backward to forward motion (displacement minima).
  const std::vector<std::size_t>& bounds = minima;
  if (s.actuated) {
    s.passive_end = first_motion;
  } else {
    const std::size_t target = static_cast<std::size_t>(o.passive_fraction * static_cast<double>(rest));
    s.passive_end = rest;
    for (std::size_t b : bounds)
      if (b >= target) {
        s.passive_end = b;
        break;
      }
    if (s.passive_end >= rest) s.passive_end = std::min(rest, std::max<std::size_t>(target, 1));
  }

  // Spans: passive window (train), then cycles alternating train / held-out (a piece shorter
  // than a third of a cycle is merged into the next one), then the rest split in halves.
  s.spans.push_back({0, s.passive_end, true});
  std::vector<std::size_t> cuts;
  for (std::size_t b : bounds)
    if (b > s.passive_end && b < rest) cuts.push_back(b);
  cuts.push_back(rest);
  double cycle = 0.0;
  for (std::size_t k = 1; k < bounds.size(); ++k) cycle += static_cast<double>(bounds[k] - bounds[k - 1]);
  cycle = bounds.size() > 1 ? cycle / static_cast<double>(bounds.size() - 1) : static_cast<double>(n);
  std::size_t begin = s.passive_end;
  bool label = true;
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    const std::size_t end = cuts[k];
    if (end <= begin) continue;
    const bool last = k + 1 == cuts.size();
    if (!last && static_cast<double>(end - begin) < cycle / 3.0) continue;  // merge into the next
    s.spans.push_back({begin, end, label});
    label = !label;
    begin = end;
  }
  if (rest < n) {
    const std::size_t mid = rest + (n - rest) / 2;
    s.spans.push_back({rest, mid, true});
    s.spans.push_back({mid, n, false});
  }
  for (const Segmentation::Span& sp : s.spans)
    for (std::size_t i = sp.begin; i < sp.end; ++i) s.train[i] = sp.train ? 1 : 0;

  // Regimes (exclusive, by priority).
  const double v_stick = std::max(0.01, o.sticking_speed_fraction * v95);
  // Actuators "move" while displaced from x' (dilated by actuator_hold_s: the harmonic motions
  // cross x' mid-way).
  std::vector<std::uint8_t> moving(n, 0);
  if (t.has_actuator_positions) {
    const long hold = static_cast<long>(std::lround(o.actuator_hold_s / t.dt_s));
    long last = -1;
    for (std::size_t i = 0; i < n; ++i) {
      if (std::abs(t.actuator1_in[i] - t.actuator1_in[0]) > o.actuator_motion_threshold_in ||
          std::abs(t.actuator2_in[i] - t.actuator2_in[0]) > o.actuator_motion_threshold_in) {
        if (last >= 0 && static_cast<long>(i) - last <= 2 * hold)
          for (long j = last; j < static_cast<long>(i); ++j) moving[static_cast<std::size_t>(j)] = 1;
        moving[i] = 1;
        last = static_cast<long>(i);
      }
    }
  }
  s.actuators_moving = moving;
  // Band re-loading after the force changes sign: the measured force (centred 0.02 s average)
  // changes sign with a hysteresis of 10 % of its 95th-percentile magnitude; the crossing is the
  // last sample of the old sign before the flip.
  s.band_reloading.assign(n, 0);
  if (!t.force_kip.empty()) {
    const long half = std::max(1L, static_cast<long>(std::lround(0.01 / t.dt_s)));
    std::vector<double> f(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const long a = std::max(0L, static_cast<long>(i) - half), b = std::min(static_cast<long>(n) - 1, static_cast<long>(i) + half);
      double sum = 0.0;
      for (long j = a; j <= b; ++j) sum += t.force_kip[static_cast<std::size_t>(j)];
      f[i] = sum / static_cast<double>(b - a + 1);
    }
    const double h = 0.1 * percentile_abs(std::vector<double>(f.begin(), f.begin() + static_cast<long>(rest)), 0.95);
    int sign = 0;
    for (std::size_t i = 0; i < rest; ++i) {
      const int now = f[i] > h ? 1 : f[i] < -h ? -1 : 0;
      if (now == 0 || now == sign) continue;
      if (sign != 0) {
        std::size_t j = i;
        while (j > 0 && f[j - 1] * sign <= 0.0) --j;  // back to the zero crossing
        for (std::size_t k = j; k < rest && std::abs(d[k] - d[j]) < o.reversal_travel_in; ++k) s.band_reloading[k] = 1;
      }
      sign = now;
    }
  }
  // Rests between strokes: the drum stays within rest_band_in of where it stopped for at least
  // min_rest_s (blind sets 20 and 21: relaxations at the stops between strokes were counted as
  // "right after a reversal", so residual_static's gain there was not its own).
  // A stop holds only samples where the drum is still (|v| <= rest_speed_in_per_s): the creep into
  // the stop and the first hundredth of an inch of the next stroke, inside rest_band_in, are motion
  // (blind set 22 t21: a grip lost at each reversal and taken up with travel changed the force in the
  // first 0.01 in of the stroke after a stop, and counted as the force changing at rest).
  const std::size_t min_rest = static_cast<std::size_t>(std::ceil(o.min_rest_s / t.dt_s));
  for (std::size_t i = 0; i < rest;) {
    std::size_t j = i + 1;
    while (j < rest && std::abs(d[j] - d[i]) <= o.rest_band_in) ++j;
    if (j - i >= min_rest) {
      std::size_t b = i, e = j;
      while (b < e && std::abs(v[b]) > o.rest_speed_in_per_s) ++b;
      while (e > b && std::abs(v[e - 1]) > o.rest_speed_in_per_s) --e;
      if (e - b >= min_rest) s.rests.push_back({b, e});
      i = j;
    } else {
      ++i;
    }
  }
  // The final rest likewise holds only samples where the drum is still: the excitation may end in a
  // slow creep into the stop, which is motion (twenty-third session: set 33 t15's record B "rested"
  // from 0.22 in/s on, and an Iwan bank's different approach to the stop there counted as the force
  // changing at rest, 39 % of its gain).
  if (rest < n) {
    std::size_t b = rest;
    while (b < n && std::abs(v[b]) > o.rest_speed_in_per_s) ++b;
    if (b < n) s.rests.push_back({b, n});
  }
  std::vector<std::uint8_t> resting(n, 0);
  for (const Segmentation::Rest& r : s.rests)
    for (std::size_t i = r.begin; i < r.end; ++i) resting[i] = 1;
  std::size_t rev_k = 0;
  double rev_disp = d[0];  // the motion start counts as a reversal
  for (std::size_t i = 0; i < n; ++i) {
    while (rev_k < s.reversals.size() && s.reversals[rev_k] <= i) rev_disp = d[s.reversals[rev_k++]];
    Regime drum = Regime::sliding;
    if (resting[i]) drum = Regime::after_stop;
    else if (std::abs(d[i] - rev_disp) < o.reversal_travel_in) drum = Regime::reversal;
    else if (std::abs(v[i]) < v_stick) drum = Regime::sticking;
    s.drum_regime[i] = drum;
    // Exclusive regime: the actuators' motion ranks between reversal and sticking.
    s.regime[i] = moving[i] != 0 && (drum == Regime::sliding || drum == Regime::sticking) ? Regime::actuators : drum;
  }
  return s;
}

double RegimeEnergy::total() const {
  double s = 0.0;
  for (double e : energy) s += e;
  return s;
}

RegimeEnergy& RegimeEnergy::operator+=(const RegimeEnergy& o) {
  for (int k = 0; k < kRegimeCount; ++k) {
    energy[k] += o.energy[k];
    samples[k] += o.samples[k];
  }
  return *this;
}

std::vector<double> low_frequency_part(const std::vector<double>& r, double dt_s, const SegmentationOptions& o) {
  return centered_moving_average(r, half_width_samples(o.chatter_window_s, dt_s));
}

RegimeEnergy localize(const std::vector<double>& r, const Segmentation& seg, double dt_s,
                      const SegmentationOptions& o, const std::vector<std::uint8_t>* mask) {
  const std::vector<double> low = low_frequency_part(r, dt_s, o);
  RegimeEnergy e;
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (mask && !(*mask)[i]) continue;
    const int k = static_cast<int>(seg.regime[i]);
    e.energy[k] += low[i] * low[i];
    ++e.samples[k];
    const double h = r[i] - low[i];
    e.energy[static_cast<int>(Regime::chatter)] += h * h;
    ++e.samples[static_cast<int>(Regime::chatter)];
  }
  return e;
}

std::vector<ResidualWindow> residual_windows(const std::string& name, const std::vector<double>& time_s,
                                             const std::vector<double>& r, const Segmentation& seg,
                                             double dt_s, const SegmentationOptions& o) {
  const std::vector<double> low = low_frequency_part(r, dt_s, o);
  std::vector<ResidualWindow> w;
  const std::size_t n = r.size();
  std::size_t b = 0;
  for (std::size_t i = 1; i <= n; ++i) {
    if (i < n && seg.regime[i] == seg.regime[b]) continue;
    ResidualWindow x;
    x.test = name;
    x.t0_s = time_s[b];
    x.t1_s = time_s[i - 1] + dt_s;
    x.regime = seg.regime[b];
    for (std::size_t j = b; j < i; ++j) x.energy += low[j] * low[j];
    w.push_back(x);
    b = i;
  }
  const std::size_t chunk = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(0.5 / dt_s)));
  for (std::size_t s0 = 0; s0 < n; s0 += chunk) {
    ResidualWindow x;
    x.test = name;
    x.regime = Regime::chatter;
    const std::size_t s1 = std::min(n, s0 + chunk);
    x.t0_s = time_s[s0];
    x.t1_s = time_s[s1 - 1] + dt_s;
    for (std::size_t j = s0; j < s1; ++j) x.energy += (r[j] - low[j]) * (r[j] - low[j]);
    w.push_back(x);
  }
  return w;
}

}  // namespace damper
