#include "server/batch/batch.h"

#include "messages/lcm_bus.h"
#include "server/run/hybrid_run.h"
#include "common/process.h"
#include "server/run/run_config.h"
#include "structure/ground_motion.h"
#include "structure/shear_building.h"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

namespace server {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using nlohmann::json;

namespace {

// ---------------------------------------------------------------------------------------
// small helpers

/// Shortest text that reads back as exactly `v`.
std::string fmt(double v) {
  if (!std::isfinite(v)) return std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf");
  char buf[64];
  for (int p = 15; p <= 17; ++p) {
    std::snprintf(buf, sizeof buf, "%.*g", p, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

std::string fixed(double v, int digits) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(digits) << v;
  return o.str();
}

std::string read_file(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

/// Writes `text` to `path` atomically (temp file in the same folder, fsync, rename).
void write_file_atomic(const fs::path& path, const std::string& text) {
  const fs::path tmp = path.string() + ".tmp." + std::to_string(getpid());
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw std::runtime_error("cannot write " + tmp.string());
    f << text;
    f.flush();
    if (!f) throw std::runtime_error("cannot write " + tmp.string() + " (disk full?)");
  }
  const int fd = ::open(tmp.c_str(), O_RDONLY);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
  fs::rename(tmp, path);
}

void fsync_path(const fs::path& p) {
  const int fd = ::open(p.c_str(), O_RDONLY);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool valid_label(const std::string& s) {
  if (s.empty() || s[0] == '.' || s.size() > 200) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-')) return false;
  if (s.size() >= 8 && s.compare(s.size() - 8, 8, ".partial") == 0) return false;
  return s.find(".failed-") == std::string::npos;
}

std::string sanitize_label(const std::string& s) {
  std::string out;
  for (char c : s) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-') ? c : '_';
  while (!out.empty() && out[0] == '.') out.erase(0, 1);
  return out.empty() ? "record" : out;
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

std::string self_exe() { return fs::read_symlink("/proc/self/exe").string(); }

std::string last_lines(const fs::path& p, int n) {
  std::ifstream f(p);
  std::vector<std::string> lines;
  for (std::string l; std::getline(f, l);)
    if (!l.empty()) lines.push_back(l);
  std::string out;
  for (std::size_t i = lines.size() > static_cast<std::size_t>(n) ? lines.size() - n : 0; i < lines.size(); ++i)
    out += (out.empty() ? "" : " | ") + lines[i];
  return out;
}

// ---------------------------------------------------------------------------------------
// the local (one-rank) communicator

class LocalComm : public BatchComm {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  bool all(bool ok) override { return ok; }
  std::vector<std::string> gather(const std::string& text) override { return {text}; }
};

}  // namespace

// ---------------------------------------------------------------------------------------
// record set

std::vector<BatchRecord> load_record_set(const std::string& spec) {
  std::vector<BatchRecord> set;
  std::error_code ec;
  if (spec.empty()) throw BatchInputError("--records is required: a record list file or a folder of records");
  if (!fs::exists(spec, ec)) throw BatchInputError("records '" + spec + "': no such file or folder");
  if (fs::is_directory(spec, ec)) {
    std::vector<fs::path> files;
    for (const fs::directory_entry& e : fs::directory_iterator(spec)) {
      if (!e.is_regular_file()) continue;
      const std::string ext = lower(e.path().extension().string());
      if (ext == ".at2" || ext == ".txt" || ext == ".csv") files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    std::map<std::string, int> stems;
    for (const fs::path& f : files) ++stems[f.stem().string()];
    for (const fs::path& f : files) {
      BatchRecord r;
      r.path = fs::absolute(f).lexically_normal().string();
      r.shown = f.filename().string();
      std::string label = f.stem().string();
      if (stems[label] > 1) label += "_" + f.extension().string().substr(1);  // x.AT2 and x.txt
      r.label = sanitize_label(label);
      set.push_back(r);
    }
    if (set.empty())
      throw BatchInputError("records folder '" + spec + "' has no record files (*.AT2, *.at2, *.txt, *.csv)");
  } else {
    if (lower(fs::path(spec).extension().string()) == ".at2")
      throw BatchInputError("--records " + spec + " is a record, not a record list: give a list file (lines "
                            "'path scale [label]') or the folder of the records");
    std::ifstream f(spec);
    if (!f) throw BatchInputError("cannot read record list '" + spec + "'");
    const fs::path base = fs::absolute(spec).parent_path();
    int line_no = 0;
    for (std::string line; std::getline(f, line);) {
      ++line_no;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      const std::size_t hash = line.find('#');
      if (hash != std::string::npos) line.erase(hash);
      std::istringstream s(line);
      std::vector<std::string> tok;
      for (std::string t; s >> t;) tok.push_back(t);
      if (tok.empty()) continue;
      const std::string where = spec + ":" + std::to_string(line_no) + ": ";
      if (tok.size() < 2)
        throw BatchInputError(where + "expected 'path scale [label]', got '" + tok[0] + "' with no scale factor");
      if (tok.size() > 3)
        throw BatchInputError(where + "expected 'path scale [label]', got " + std::to_string(tok.size()) +
                              " fields (paths with spaces are not supported)");
      BatchRecord r;
      r.line = line_no;
      r.shown = tok[0];
      const fs::path p(tok[0]);
      r.path = (p.is_absolute() ? p : base / p).lexically_normal().string();
      char* end = nullptr;
      r.scale = std::strtod(tok[1].c_str(), &end);
      if (end == tok[1].c_str() || *end != '\0' || !std::isfinite(r.scale))
        throw BatchInputError(where + "scale factor '" + tok[1] + "' is not a number");
      if (!(r.scale > 0.0) || r.scale > 100.0)
        throw BatchInputError(where + "scale factor " + tok[1] + " is outside (0, 100]");
      if (tok.size() == 3) {
        if (!valid_label(tok[2]))
          throw BatchInputError(where + "label '" + tok[2] +
                                "' must be letters, digits, '.', '_' or '-' (not starting with '.', "
                                "not ending in .partial)");
        r.label = tok[2];
      } else {
        r.label = sanitize_label(p.stem().string());
        if (r.scale != 1.0) r.label += "_x" + sanitize_label(tok[1]);
      }
      set.push_back(r);
    }
    if (set.empty()) throw BatchInputError("record list '" + spec + "' names no records");
  }
  std::map<std::string, const BatchRecord*> seen;
  for (const BatchRecord& r : set) {
    auto [it, fresh] = seen.emplace(r.label, &r);
    if (!fresh) {
      throw BatchInputError(spec + (r.line ? ":" + std::to_string(r.line) : std::string()) + ": label '" +
                            r.label + "' is used twice (also " +
                            (it->second->line ? "line " + std::to_string(it->second->line) : it->second->shown) +
                            "); give each record its own label (third field)");
    }
  }
  return set;
}

namespace {

// ---------------------------------------------------------------------------------------
// manifest and results

struct BatchSet {
  std::string config;                 // absolute
  std::string records_spec;           // absolute
  std::string name;                   // config run name
  int stories = 0;
  int dampers = 0;
  double duration_s = 0.0;            // simulated per run (< 0: whole records)
  std::vector<BatchRecord> records;
};

json manifest_json(const BatchSet& b) {
  json j;
  j["config"] = b.config;
  j["records"] = b.records_spec;
  j["name"] = b.name;
  j["stories"] = b.stories;
  j["dampers"] = b.dampers;
  j["duration_s"] = b.duration_s;
  json recs = json::array();
  for (std::size_t i = 0; i < b.records.size(); ++i) {
    const BatchRecord& r = b.records[i];
    recs.push_back({{"index", i}, {"label", r.label}, {"record", r.shown}, {"path", r.path}, {"scale", r.scale}});
  }
  j["set"] = recs;
  return j;
}

BatchSet manifest_from_json(const json& j) {
  BatchSet b;
  b.config = j.at("config").get<std::string>();
  b.records_spec = j.at("records").get<std::string>();
  b.name = j.value("name", "");
  b.stories = j.at("stories").get<int>();
  b.dampers = j.at("dampers").get<int>();
  b.duration_s = j.value("duration_s", 0.0);
  for (const json& r : j.at("set")) {
    BatchRecord rec;
    rec.label = r.at("label").get<std::string>();
    rec.shown = r.at("record").get<std::string>();
    rec.path = r.at("path").get<std::string>();
    rec.scale = r.at("scale").get<double>();
    b.records.push_back(rec);
  }
  return b;
}

fs::path runs_dir(const std::string& out) { return fs::path(out) / "runs"; }
fs::path final_dir(const std::string& out, const std::string& label) { return runs_dir(out) / label; }
fs::path partial_dir(const std::string& out, const std::string& label) { return runs_dir(out) / (label + ".partial"); }

/// The result of one record as the summary sees it.
struct RunResult {
  std::string state = "not_run";   // "ok", "failed", "not_run"
  bool finished = false;           // in runs/<label>/ (final)
  json summary;                    // summary.json (null if none)
};

/// Reads the result of `label`: the finished folder, else a .partial folder holding a failed
/// summary (machinery failure of this session), else not run.
RunResult read_result(const std::string& out, const std::string& label) {
  RunResult r;
  for (const fs::path& dir : {final_dir(out, label), partial_dir(out, label)}) {
    const fs::path s = dir / "summary.json";
    std::error_code ec;
    if (!fs::exists(s, ec)) continue;
    try {
      r.summary = json::parse(read_file(s));
      r.state = r.summary.value("status", "failed") == "ok" ? "ok" : "failed";
    } catch (const std::exception& e) {
      r.summary = json{{"status", "failed"}, {"error", "unreadable summary.json: " + std::string(e.what())}};
      r.state = "failed";
    }
    r.finished = dir == final_dir(out, label);
    if (!r.finished && r.state == "ok") r.state = "not_run";  // never renamed: not a result
    return r;
  }
  return r;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) {
    if (c == '"') q += '"';
    q += (c == '\n' || c == '\r') ? ' ' : c;
  }
  return q + "\"";
}

/// summary.csv: one row per record of the set, in set order.
std::string summary_csv(const BatchSet& b, const std::vector<RunResult>& results) {
  std::ostringstream o;
  o << "record,label,scale,pga_g";
  for (int i = 1; i <= b.stories; ++i) o << ",peak_drift_story" << i << "_in";
  for (int i = 1; i <= b.stories; ++i) o << ",residual_drift_story" << i << "_in";
  for (int i = 1; i <= b.stories; ++i) o << ",peak_floor_accel_floor" << i << "_g";
  for (int k = 1; k <= b.dampers; ++k) o << ",peak_damper_force_damper" << k << "_kip";
  for (int k = 1; k <= b.dampers; ++k) o << ",damper_energy_damper" << k << "_kip_in";
  o << ",status,error\n";
  for (std::size_t i = 0; i < b.records.size(); ++i) {
    const BatchRecord& r = b.records[i];
    const RunResult& res = results[i];
    o << csv_field(r.shown) << "," << csv_field(r.label) << "," << fmt(r.scale);
    const json& s = res.summary;
    // Figures only when the run got going (the record was read): a run that failed on its
    // record has empty arrays.
    const bool figures = s.is_object() && s.contains("peak_drift_in") && s["peak_drift_in"].is_array() &&
                         !s["peak_drift_in"].empty();
    o << "," << (figures ? fmt(s["pga_g"].get<double>()) : "");
    auto vec = [&](const char* key, int n) {
      for (int k = 0; k < n; ++k) {
        o << ",";
        if (figures && s.contains(key) && s[key].is_array() && static_cast<int>(s[key].size()) > k)
          o << fmt(s[key][k].get<double>());
      }
    };
    vec("peak_drift_in", b.stories);
    vec("residual_drift_in", b.stories);
    vec("peak_floor_accel_g", b.stories);
    vec("peak_damper_force_kip", b.dampers);
    vec("damper_energy_kip_in", b.dampers);
    std::string error = s.is_object() ? s.value("error", "") : "";
    if (res.state == "failed" && !res.finished && !error.empty()) error += " (not final: redone on resume)";
    o << "," << res.state << "," << csv_field(error) << "\n";
  }
  return o.str();
}

/// Gnuplot plots of the ok runs: drift envelope (peak drift vs story, every record, mean and
/// max) and peak drift vs PGA (one series per story). Returns "" or a warning.
std::string make_plots(const std::string& out, const BatchSet& b, const std::vector<RunResult>& results) {
  const fs::path dir = fs::path(out) / "plots";
  fs::create_directories(dir);
  std::ofstream env(dir / "drift-envelope.dat"), stats(dir / "drift-envelope-stats.dat"), pga(dir / "drift-vs-pga.dat");
  env << "# story peak_drift_in; one block per ok record (gnuplot index)\n";
  pga << "# pga_g peak_drift_story1_in ... (ok records)\n";
  int blocks = 0;
  std::vector<double> sum(b.stories, 0.0), mx(b.stories, 0.0);
  for (std::size_t i = 0; i < b.records.size(); ++i) {
    if (results[i].state != "ok") continue;
    const json& s = results[i].summary;
    if (!s.contains("peak_drift_in") || static_cast<int>(s["peak_drift_in"].size()) != b.stories) continue;
    env << "# " << b.records[i].label << "\n0 0\n";
    pga << fmt(s["pga_g"].get<double>());
    for (int k = 0; k < b.stories; ++k) {
      const double d = s["peak_drift_in"][k].get<double>();
      env << k + 1 << " " << fmt(d) << "\n";
      pga << " " << fmt(d);
      sum[k] += d;
      mx[k] = std::max(mx[k], d);
    }
    env << "\n\n";
    pga << "\n";
    ++blocks;
  }
  stats << "# story mean_peak_drift_in max_peak_drift_in\n0 0 0\n";
  for (int k = 0; k < b.stories; ++k)
    stats << k + 1 << " " << fmt(blocks ? sum[k] / blocks : 0.0) << " " << fmt(mx[k]) << "\n";
  env.close();
  stats.close();
  pga.close();
  if (blocks == 0) return "no ok runs: no plots";

  std::ofstream gp(dir / "plots.gp");
  gp << "# gnuplot script written by hybridsim batch; run from " << dir.string() << "\n"
     << "set terminal pngcairo size 900,650 noenhanced\n"
     << "set grid\n"
     << "set key outside right\n"
     << "set output '../drift-envelope.png'\n"
     << "set title 'Peak interstory drift envelope: " << b.name << ", " << blocks << " records'\n"
     << "set xlabel 'peak interstory drift (in)'\nset ylabel 'story'\n"
     << "set ytics 1\nset yrange [0:" << b.stories << "]\nset xrange [0:*]\n"
     << "plot for [i=0:" << blocks - 1
     << "] 'drift-envelope.dat' index i using 2:1 with linespoints lc rgb '#b0b0b0' pt 7 ps 0.5 notitle, \\\n"
     << "     'drift-envelope-stats.dat' using 2:1 with linespoints lw 3 lc rgb '#1f77b4' pt 7 title 'mean', \\\n"
     << "     'drift-envelope-stats.dat' using 3:1 with linespoints lw 3 lc rgb '#d62728' pt 5 title 'max'\n"
     << "set output '../drift-vs-pga.png'\n"
     << "set title 'Peak interstory drift vs PGA: " << b.name << "'\n"
     << "set xlabel 'PGA (g)'\nset ylabel 'peak interstory drift (in)'\n"
     << "set autoscale\nset ytics auto\nset xrange [0:*]\nset yrange [0:*]\n"
     << "plot for [s=1:" << b.stories << "] 'drift-vs-pga.dat' using 1:(column(s+1)) with points pt 7 ps 1.3 title sprintf('story %d', s)\n";
  gp.close();
  const std::string cmd = "cd '" + dir.string() + "' && gnuplot plots.gp > gnuplot.log 2>&1";
  const int rc = std::system(cmd.c_str());
  if (rc != 0) return "gnuplot failed (exit " + std::to_string(rc) + "): see " + (dir / "gnuplot.log").string();
  return "";
}

struct Counts {
  int records = 0, ok = 0, failed = 0, not_run = 0;
};

Counts count(const std::vector<RunResult>& results) {
  Counts c;
  c.records = static_cast<int>(results.size());
  for (const RunResult& r : results) {
    if (r.state == "ok") ++c.ok;
    else if (r.state == "failed") ++c.failed;
    else ++c.not_run;
  }
  return c;
}

/// Writes summary.csv and the plots; prints where they are.
void write_outputs(const std::string& out, const BatchSet& b, const std::vector<RunResult>& results, bool quiet) {
  write_file_atomic(fs::path(out) / "summary.csv", summary_csv(b, results));
  const std::string warning = make_plots(out, b, results);
  if (!warning.empty()) std::cerr << "hybridsim batch: warning: " << warning << "\n";
  if (!quiet) {
    std::cout << "summary: " << (fs::path(out) / "summary.csv").string() << "\n";
    if (warning.empty())
      std::cout << "plots: " << (fs::path(out) / "drift-envelope.png").string() << ", "
                << (fs::path(out) / "drift-vs-pga.png").string() << "\n";
  }
}

void print_final_line(const Counts& c, double seconds) {
  std::cout << "records=" << c.records << " ok=" << c.ok << " failed=" << c.failed
            << " seconds=" << fixed(seconds, 2) << std::endl;
}

// ---------------------------------------------------------------------------------------
// progress

class Progress {
 public:
  /// `bar_allowed`: false under MPI (mpirun hands ranks a pseudo-terminal, and bars of
  /// several ranks on one line are unreadable): plain lines.
  Progress(int total, int already_done, int to_run, int jobs, bool quiet, const std::string& prefix, bool bar_allowed)
      : total_(total), done_(already_done), to_run_(to_run), jobs_(jobs), quiet_(quiet), prefix_(prefix),
        tty_(bar_allowed && isatty(STDOUT_FILENO) == 1), start_(Clock::now()) {}

  void started() {
    ++running_;
    draw();
  }

  void finished(const BatchRecord& r, const std::string& state, const std::string& error, double wall_s) {
    --running_;
    ++done_;
    ++finished_now_;
    if (state != "ok") ++failed_;
    if (quiet_) return;
    std::ostringstream line;
    line << prefix_ << "[" << done_ << "/" << total_ << "] " << std::left << std::setw(7) << state << r.label
         << " (" << fixed(wall_s, 2) << " s)";
    if (!error.empty()) line << ": " << error;
    if (tty_) {
      if (state != "ok") std::cout << "\r\033[K" << line.str() << "\n";
      draw();
    } else {
      line << "  | failed " << failed_ << ", elapsed " << fixed(elapsed(), 1) << " s, left " << eta_text();
      std::cout << line.str() << std::endl;
    }
  }

  void tick() {
    if (tty_ && !quiet_ && std::chrono::duration<double>(Clock::now() - last_draw_).count() > 0.25) draw();
  }

  void end() {
    if (tty_ && !quiet_) std::cout << "\n" << std::flush;
  }

 private:
  double elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  std::string eta_text() const {
    const int left = to_run_ - finished_now_;
    if (left <= 0) return "0 s";
    if (finished_now_ == 0) return "?";
    const double s = elapsed() / finished_now_ * left;
    std::ostringstream o;
    if (s >= 3600) o << static_cast<int>(s / 3600) << " h " << static_cast<int>(std::fmod(s, 3600) / 60) << " min";
    else if (s >= 60) o << static_cast<int>(s / 60) << " min " << static_cast<int>(std::fmod(s, 60)) << " s";
    else o << fixed(s, 0) << " s";
    return o.str();
  }

  void draw() {
    if (!tty_ || quiet_) return;
    last_draw_ = Clock::now();
    const int width = 30;
    const int filled = total_ ? done_ * width / total_ : width;
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(width, '.');
    std::cout << "\r\033[K" << prefix_ << "[" << bar << "] " << done_ << "/" << total_ << " done, " << failed_
              << " failed, " << running_ << " running, " << fixed(elapsed(), 0) << " s elapsed, ~"
              << eta_text() << " left" << std::flush;
  }

  int total_, done_, to_run_, jobs_;
  bool quiet_;
  std::string prefix_;
  bool tty_;
  Clock::time_point start_, last_draw_{};
  int running_ = 0, failed_ = 0, finished_now_ = 0;
};

// ---------------------------------------------------------------------------------------
// the driver

/// Loads and checks the config and the record set.
BatchSet prepare_set(const BatchOptions& o) {
  if (o.config.empty()) throw BatchInputError("--config is required (e.g. configs/three-story.yaml)");
  if (o.records.empty()) throw BatchInputError("--records is required: a record list file or a folder");
  BatchSet b;
  const RunConfig config = load_run_config(o.config);
  if (config.damper.mode != "virtual" || config.damper.launch != "spawn")
    throw BatchInputError("config " + o.config + ": a batch runs virtual substructures it spawns itself "
                          "(damper.mode: virtual, damper.launch: spawn); run physical tests one at a "
                          "time with hybridsim run");
  const structure::ShearBuilding building(config.building);
  b.config = fs::absolute(o.config).lexically_normal().string();
  b.records_spec = fs::absolute(o.records).lexically_normal().string();
  b.name = config.name;
  b.stories = building.num_stories();
  b.dampers = building.num_dampers();
  b.duration_s = o.duration_s != 0.0 ? o.duration_s : config.record.duration_s;
  b.records = load_record_set(o.records);
  return b;
}

/// Stops with an error if runs/<label>/ holds a different record or scale than the set says
/// (e.g. the list file changed a scale but kept the label): resuming would mix results.
void check_finished_matches(const std::string& out, const BatchRecord& r, double duration_s) {
  const fs::path info = final_dir(out, r.label) / "batch-run.json";
  std::error_code ec;
  if (!fs::exists(info, ec)) return;
  const json j = json::parse(read_file(info));
  const std::string path = j.value("path", "");
  const double scale = j.value("scale", 0.0);
  if (path != r.path || scale != r.scale)
    throw BatchInputError("runs/" + r.label + " in " + out + " holds record " + path + " at scale " + fmt(scale) +
                          ", but the set now says " + r.path + " at scale " + fmt(r.scale) +
                          ": use another --out or another label");
  const double duration = j.value("duration_s", duration_s);
  if (duration != duration_s)
    throw BatchInputError("runs/" + r.label + " in " + out + " simulated " + fmt(duration) +
                          " s (record.duration_s), but this batch asks for " + fmt(duration_s) +
                          " s: use another --out");
}

/// Moves a finished failed run aside (runs/<label>.failed-<n>/) so that it is redone; nothing
/// is deleted.
void set_failed_aside(const std::string& out, const std::string& label) {
  for (int n = 1;; ++n) {
    const fs::path aside = runs_dir(out) / (label + ".failed-" + std::to_string(n));
    std::error_code ec;
    if (fs::exists(aside, ec)) continue;
    fs::rename(final_dir(out, label), aside);
    return;
  }
}

struct DriverResult {
  int ran = 0;       // runs started in this call
  int skipped = 0;   // already finished
  bool interrupted = false;  // SIGINT/SIGTERM: running runs stopped, the rest not started
};

volatile sig_atomic_t g_interrupted = 0;

/// The signals that stop a batch.
sigset_t stop_signals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGHUP);
  return set;
}

/// Blocks the stop signals while a worker is forked and exec'ed. Between fork and exec the
/// child still has the driver's handlers: a SIGTERM (its PR_SET_PDEATHSIG when the driver is
/// killed) or a Ctrl-C arriving then would only set a flag in the child, which would run on
/// as an orphan. Blocked, the signal stays pending through exec and the worker, which
/// unblocks them first thing (unblock_stop_signals), dies of it.
class StopSignalsBlocked {
 public:
  StopSignalsBlocked() {
    const sigset_t set = stop_signals();
    pthread_sigmask(SIG_BLOCK, &set, &old_);
  }
  ~StopSignalsBlocked() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }

 private:
  sigset_t old_;
};

void unblock_stop_signals() {
  const sigset_t set = stop_signals();
  pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
}
extern "C" void on_interrupt(int) { g_interrupted = 1; }

/// Ctrl-C or kill of a local batch: stop launching, stop the running workers (their
/// .partial folders are redone on resume), write the summary of what is finished, and end
/// with the final line. Not under MPI (mpirun handles signals for all ranks).
void install_interrupt_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_interrupt;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGHUP, &sa, nullptr);
}

/// Runs the records `mine` (indices into b.records) that are not finished yet, `jobs` at a
/// time, one worker process each.
DriverResult run_records(const BatchOptions& o, const BatchSet& b, const std::vector<std::size_t>& mine,
                         const std::string& progress_prefix) {
  DriverResult result;
  std::vector<std::size_t> todo;
  for (std::size_t i : mine) {
    const BatchRecord& r = b.records[i];
    std::error_code ec;
    const bool finished = fs::exists(final_dir(o.out, r.label) / "summary.json", ec);
    if (finished) {
      if (o.retry_failed && read_result(o.out, r.label).state == "failed") {
        set_failed_aside(o.out, r.label);
      } else {
        ++result.skipped;
        continue;
      }
    } else if (fs::exists(final_dir(o.out, r.label), ec)) {
      // A final folder without summary.json is not something a batch writes; keep it aside.
      fs::rename(final_dir(o.out, r.label),
                 runs_dir(o.out) / (r.label + ".stale-" + std::to_string(messages::now_utime())));
    }
    todo.push_back(i);
  }

  if (!o.quiet) {
    std::cout << progress_prefix << "batch: " << mine.size() << " records, " << result.skipped
              << " already finished, " << todo.size() << " to run, " << o.jobs << " at a time; results in "
              << o.out << std::endl;
  }
  Progress progress(static_cast<int>(mine.size()), result.skipped, static_cast<int>(todo.size()), o.jobs, o.quiet,
                    progress_prefix, !o.mpi);

  struct Slot {
    ChildProcess proc;
    std::size_t index;
    Clock::time_point start;
  };
  std::vector<std::unique_ptr<Slot>> running;
  std::size_t next = 0;
  const std::string exe = self_exe();
  const RunConfig base = load_run_config(o.config);

  auto launch = [&](std::size_t i) {
    const BatchRecord& r = b.records[i];
    const fs::path partial = partial_dir(o.out, r.label);
    fs::remove_all(partial);  // an interrupted run: redone from the start
    fs::create_directories(partial);
    char idx[16];
    std::snprintf(idx, sizeof idx, "R%04zu_", i);
    const std::string prefix = o.same_channel_prefix ? base.transport.channel_prefix
                                                     : base.transport.channel_prefix + idx;
    std::vector<std::string> args{"batch", "worker", "--config", b.config, "--record", r.path,
                                  "--scale", fmt(r.scale), "--label", r.label, "--runs-dir",
                                  fs::absolute(runs_dir(o.out)).string(), "--channel-prefix", prefix,
                                  "--index", std::to_string(i)};
    if (o.shared_netns) args.push_back("--shared-netns");
    if (o.duration_s != 0.0) {
      args.push_back("--duration");
      args.push_back(fmt(o.duration_s));
    }
    auto slot = std::make_unique<Slot>();
    slot->index = i;
    slot->start = Clock::now();
    {
      StopSignalsBlocked blocked;
      slot->proc = ChildProcess(exe, args, (partial / "worker.log").string());
    }
    running.push_back(std::move(slot));
    ++result.ran;
    progress.started();
  };

  auto collect = [&](Slot& s, int code) {
    const BatchRecord& r = b.records[s.index];
    const double wall = std::chrono::duration<double>(Clock::now() - s.start).count();
    std::error_code ec;
    const fs::path partial = partial_dir(o.out, r.label);
    if (!fs::exists(final_dir(o.out, r.label) / "summary.json", ec) && !fs::exists(partial / "summary.json", ec)) {
      // The worker died without a word (crash, killed): a machinery failure, redone on resume.
      RunSummary failed;
      failed.status = "failed";
      failed.error = "batch worker exited with code " + std::to_string(code) + " without a result";
      const std::string tail = last_lines(partial / "worker.log", 3);
      if (!tail.empty()) failed.error += ": " + tail;
      RunConfig c = base;
      c.record.path = r.path;
      c.record.scale = r.scale;
      if (fs::exists(partial, ec)) write_summary_json(failed, c, (partial / "summary.json").string());
    }
    const RunResult res = read_result(o.out, r.label);
    std::string error = res.summary.is_object() ? res.summary.value("error", "") : "";
    if (code == kWorkerInfraFailed || !res.finished) error += error.empty() ? "not finished" : " (not final: redone on resume)";
    progress.finished(r, res.state == "ok" ? "ok" : "failed", error, wall);
  };

  while (next < todo.size() || !running.empty()) {
    if (g_interrupted) {
      for (auto& slot : running) {
        if (slot->proc.pid() > 0) ::kill(slot->proc.pid(), SIGTERM);
        slot->proc.wait_or_kill(3.0);
      }
      running.clear();
      result.interrupted = true;
      break;
    }
    while (next < todo.size() && static_cast<int>(running.size()) < o.jobs) launch(todo[next++]);
    for (auto it = running.begin(); it != running.end();) {
      if (!(*it)->proc.running()) {
        const int code = (*it)->proc.wait_or_kill(0.0);
        collect(**it, code);
        it = running.erase(it);
      } else {
        ++it;
      }
    }
    progress.tick();
    if (!running.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  progress.end();
  return result;
}

/// Holds an exclusive lock on OUT/.batch.lock while a local batch runs in OUT. The lock is
/// inherited by the worker processes (no O_CLOEXEC), so a batch restarted right after a kill
/// waits until the old workers are gone before it touches their .partial folders.
class DirLock {
 public:
  explicit DirLock(const std::string& out) {
    const std::string path = (fs::path(out) / ".batch.lock").string();
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT, 0644);
    if (fd_ < 0) throw BatchInputError("cannot create " + path);
    const auto deadline = Clock::now() + std::chrono::seconds(10);
    while (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      if (Clock::now() > deadline) {
        ::close(fd_);
        fd_ = -1;
        throw BatchInputError("another hybridsim batch is running in " + out + " (" + path + " is locked)");
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  ~DirLock() {
    if (fd_ >= 0) ::close(fd_);
  }

 private:
  int fd_ = -1;
};

/// Result texts of the indices `mine`, as a JSON array [{index, summary, finished}] for the
/// gather on rank 0.
std::string results_payload(const std::string& out, const BatchSet& b, const std::vector<std::size_t>& mine) {
  json arr = json::array();
  for (std::size_t i : mine) {
    const RunResult r = read_result(out, b.records[i].label);
    arr.push_back({{"index", i}, {"state", r.state}, {"finished", r.finished}, {"summary", r.summary}});
  }
  return arr.dump();
}

int run_batch(const BatchOptions& o, BatchComm& comm) {
  const auto t0 = Clock::now();
  BatchSet b;
  std::string setup_error;
  try {
    if (o.jobs < 1) throw BatchInputError("--jobs must be at least 1");
    if (o.out.empty()) throw BatchInputError("--out is required (the batch folder)");
    if (o.mpi && o.shared_netns) throw BatchInputError("--shared-netns cannot be used with --mpi");
    b = prepare_set(o);
  } catch (const std::exception& e) {
    setup_error = e.what();
  }
  if (!comm.all(setup_error.empty())) {
    if (comm.rank() == 0) std::cerr << "hybridsim batch: " << (setup_error.empty() ? "another rank failed to start" : setup_error) << "\n";
    return 2;
  }

  std::unique_ptr<DirLock> lock;
  try {
    fs::create_directories(runs_dir(o.out));
    if (!o.mpi && !o.slurm_task) lock = std::make_unique<DirLock>(o.out);
    // Finished runs must be of this set (same record, scale, duration) before anything is
    // written: resuming must not mix two different batches.
    for (const BatchRecord& r : b.records) check_finished_matches(o.out, r, b.duration_s);
    if (comm.rank() == 0) {
      std::ostringstream m;
      m << std::setw(2) << manifest_json(b) << "\n";
      write_file_atomic(fs::path(o.out) / "batch.json", m.str());
    }
    if (o.shared_netns && !messages::in_private_network_namespace()) messages::enter_private_network_namespace();
  } catch (const std::exception& e) {
    setup_error = e.what();
  }
  if (!comm.all(setup_error.empty())) {
    if (!setup_error.empty()) std::cerr << "hybridsim batch: " << setup_error << "\n";
    return 2;
  }

  // Which records this process runs.
  std::vector<std::size_t> mine;
  if (o.slurm_task) {
    const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
    char* end = nullptr;
    const long task = id ? std::strtol(id, &end, 10) : -1;
    if (!id || *end != '\0' || task < 0) {
      std::cerr << "hybridsim batch: --slurm-task needs SLURM_ARRAY_TASK_ID (0-based record index; "
                   "submit with sbatch --array=0-" << b.records.size() - 1 << ")\n";
      return 2;
    }
    if (static_cast<std::size_t>(task) >= b.records.size()) {
      std::cout << "slurm task " << task << ": the set has " << b.records.size() << " records, nothing to do\n";
      print_final_line(Counts{}, std::chrono::duration<double>(Clock::now() - t0).count());
      return 0;
    }
    mine.push_back(static_cast<std::size_t>(task));
  } else {
    for (std::size_t i = static_cast<std::size_t>(comm.rank()); i < b.records.size(); i += comm.size()) mine.push_back(i);
  }

  const std::string prefix = comm.size() > 1 ? "rank " + std::to_string(comm.rank()) + ": " : "";
  bool interrupted = false;
  if (!o.mpi) install_interrupt_handlers();
  try {
    interrupted = run_records(o, b, mine, prefix).interrupted;
  } catch (const std::exception& e) {
    setup_error = e.what();
    std::cerr << "hybridsim batch: " << prefix << setup_error << "\n";
  }
  // Every rank reaches the gather, even after an error, so that no rank waits forever.
  const std::vector<std::string> payloads = comm.gather(results_payload(o.out, b, mine));
  const bool all_ran = comm.all(setup_error.empty());
  if (comm.rank() != 0) return all_ran ? 0 : 2;

  std::vector<RunResult> results(b.records.size());
  std::vector<bool> have(b.records.size(), false);
  for (const std::string& p : payloads) {
    for (const json& r : json::parse(p)) {
      const std::size_t i = r.at("index").get<std::size_t>();
      results[i].state = r.at("state").get<std::string>();
      results[i].finished = r.at("finished").get<bool>();
      results[i].summary = r.at("summary");
      have[i] = true;
    }
  }
  // Records other processes ran (Slurm tasks, earlier batches): read from disk.
  for (std::size_t i = 0; i < b.records.size(); ++i)
    if (!have[i]) results[i] = read_result(o.out, b.records[i].label);

  Counts c;
  if (o.slurm_task) {
    std::vector<RunResult> own;
    for (std::size_t i : mine) own.push_back(results[i]);
    c = count(own);
    if (!o.quiet) std::cout << "slurm task " << mine[0] << " (" << b.records[mine[0]].label
                            << ") done; build the summary with: hybridsim batch merge --out " << o.out << "\n";
  } else {
    write_outputs(o.out, b, results, o.quiet);
    c = count(results);
    if (c.not_run > 0) std::cout << "not run: " << c.not_run << " (run the batch again to finish them)\n";
  }
  if (interrupted) std::cout << "interrupted: run the same command again to resume\n";
  print_final_line(c, std::chrono::duration<double>(Clock::now() - t0).count());
  if (interrupted) return 130;
  if (!all_ran) return 2;
  return (c.failed == 0 && c.not_run == 0) ? 0 : 1;
}

double children_cpu_s() {
  struct rusage ru {};
  getrusage(RUSAGE_CHILDREN, &ru);
  return ru.ru_utime.tv_sec + ru.ru_stime.tv_sec + 1e-6 * (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// --bench: the same set with 1 job and with max(2, --jobs) jobs, alternated --bench-repeat
/// times (a shared machine's load drifts: alternating and taking the best of each is fairer
/// than one run of each). Prints every pass, then records/s, speedup and efficiency.
int bench(const BatchOptions& o) {
  BatchSet b;
  try {
    if (o.out.empty()) throw BatchInputError("--out is required (the benchmark writes OUT/bench/)");
    if (o.bench_repeat < 1) throw BatchInputError("--bench-repeat must be at least 1");
    b = prepare_set(o);
  } catch (const std::exception& e) {
    std::cerr << "hybridsim batch: " << e.what() << "\n";
    return 2;
  }
  const RunConfig config = load_run_config(o.config);
  const std::vector<int> jobs_list{1, std::max(2, o.jobs)};
  std::map<int, std::vector<double>> rates, cpu_per_record;
  std::cout << "bench: " << b.records.size() << " records, "
            << (b.duration_s > 0 ? fixed(b.duration_s, 1) + " s simulated each" : std::string("whole records"))
            << ", dt " << fmt(config.dt_s) << " s, " << std::thread::hardware_concurrency() << " cores, "
            << o.bench_repeat << " alternating pass(es)" << std::endl;
  Counts last;
  double last_wall = 0.0;
  for (int pass = 1; pass <= o.bench_repeat; ++pass) {
    for (int jobs : jobs_list) {
      BatchOptions run = o;
      run.bench = false;
      run.jobs = jobs;
      run.quiet = true;
      run.out = (fs::path(o.out) / "bench" / ("jobs" + std::to_string(jobs))).string();
      fs::remove_all(run.out);  // benchmark scratch only
      fs::create_directories(runs_dir(run.out));
      std::vector<std::size_t> all(b.records.size());
      for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
      const double cpu0 = children_cpu_s();
      const auto t0 = Clock::now();
      run_records(run, b, all, "");
      const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
      const double cpu = children_cpu_s() - cpu0;
      std::vector<RunResult> results;
      for (const BatchRecord& r : b.records) results.push_back(read_result(run.out, r.label));
      last = count(results);
      last_wall = wall;
      const double rate = b.records.size() / wall;
      rates[jobs].push_back(rate);
      cpu_per_record[jobs].push_back(cpu / b.records.size());
      std::cout << "pass " << pass << " jobs=" << jobs << ": " << b.records.size() << " records in " << fixed(wall, 2)
                << " s = " << fixed(rate, 3) << " records/s, CPU " << fixed(cpu / b.records.size(), 2)
                << " s per record (" << fixed(cpu / wall, 2) << " cores busy), ok " << last.ok << ", failed "
                << last.failed << std::endl;
    }
  }
  const int j2 = jobs_list[1];
  for (int jobs : jobs_list) {
    const auto& r = rates[jobs];
    std::cout << "jobs=" << jobs << ": " << fixed(*std::max_element(r.begin(), r.end()), 3) << " records/s best, "
              << fixed(median(r), 3) << " median" << std::endl;
  }
  const double best = *std::max_element(rates[j2].begin(), rates[j2].end()) /
                      *std::max_element(rates[1].begin(), rates[1].end());
  const double med = median(rates[j2]) / median(rates[1]);
  std::cout << "speedup with " << j2 << " jobs: " << fixed(best, 2) << "x (best) / " << fixed(med, 2)
            << "x (median); scaling efficiency " << fixed(100.0 * best / j2, 1) << " % (best), "
            << fixed(100.0 * med / j2, 1) << " % (median)" << std::endl;
  print_final_line(last, last_wall);
  return last.failed == 0 ? 0 : 1;
}

}  // namespace

int batch_command(const BatchOptions& o) {
  if (o.list) {
    try {
      const std::vector<BatchRecord> set = load_record_set(o.records);
      for (std::size_t i = 0; i < set.size(); ++i)
        std::cout << i << " " << set[i].label << " " << fmt(set[i].scale) << " " << set[i].path << "\n";
      return 0;
    } catch (const std::exception& e) {
      std::cerr << "hybridsim batch: " << e.what() << "\n";
      return 2;
    }
  }
  if (o.bench) return bench(o);
  if (o.mpi) {
    if (o.slurm_task) {
      std::cerr << "hybridsim batch: --mpi and --slurm-task exclude each other\n";
      return 2;
    }
    std::unique_ptr<BatchComm> comm;
    try {
      comm = make_mpi_comm();
    } catch (const std::exception& e) {
      std::cerr << "hybridsim batch: " << e.what() << "\n";
      return 2;
    }
    return run_batch(o, *comm);
  }
  LocalComm comm;
  return run_batch(o, comm);
}

int batch_merge_command(const std::string& out) {
  const auto t0 = Clock::now();
  BatchSet b;
  try {
    const fs::path m = fs::path(out) / "batch.json";
    if (!fs::exists(m)) throw BatchInputError(m.string() + " not found: is " + out + " a batch folder?");
    b = manifest_from_json(json::parse(read_file(m)));
  } catch (const std::exception& e) {
    std::cerr << "hybridsim batch merge: " << e.what() << "\n";
    return 2;
  }
  std::vector<RunResult> results;
  for (const BatchRecord& r : b.records) results.push_back(read_result(out, r.label));
  write_outputs(out, b, results, false);
  const Counts c = count(results);
  if (c.not_run > 0) std::cout << "not run yet: " << c.not_run << "\n";
  print_final_line(c, std::chrono::duration<double>(Clock::now() - t0).count());
  return (c.failed == 0 && c.not_run == 0) ? 0 : 1;
}

// ---------------------------------------------------------------------------------------
// the worker

int batch_worker_command(const BatchWorkerOptions& w) {
  unblock_stop_signals();  // blocked by the driver around fork/exec; a pending one kills us now
  const auto t0 = Clock::now();
  const fs::path partial = fs::path(w.runs_dir) / (w.label + ".partial");
  const fs::path final_path = fs::path(w.runs_dir) / w.label;
  fs::create_directories(partial);
  const std::string run_id = "batch-" + w.label + "-" + std::to_string(messages::now_utime()) + "-" +
                             std::to_string(getpid());

  RunConfig config;
  RunSummary summary;
  bool infra_failure = false;
  try {
    config = load_run_config(w.config);
  } catch (const std::exception& e) {
    std::cerr << "hybridsim batch worker: " << e.what() << "\n";
    summary.status = "failed";
    summary.error = e.what();
    infra_failure = true;
  }
  config.record.path = w.record;
  config.record.scale = w.scale;
  config.output.dir = partial.string();
  if (w.duration_s != 0.0) config.record.duration_s = w.duration_s;
  config.transport.channel_prefix = w.channel_prefix.empty() ? config.transport.channel_prefix : w.channel_prefix;

  json info{{"label", w.label},          {"index", w.index},
            {"path", w.record},          {"scale", w.scale},
            {"duration_s", config.record.duration_s},
            {"run_id", run_id},          {"channel_prefix", config.transport.channel_prefix},
            {"network_namespace", w.shared_netns ? "shared with the batch" : "own"},
            {"started_utc", utc_now()},  {"worker_pid", getpid()}};

  if (!infra_failure) {
    std::ofstream(partial / "effective-config.yaml") << run_config_to_yaml(config);
    // The record: a bad one fails this run, with the reason.
    bool record_ok = true;
    try {
      structure::read_ground_motion(config.record.path, config.record.scale);
    } catch (const std::exception& e) {
      summary.status = "failed";
      summary.error = e.what();
      record_ok = false;
    }
    if (record_ok) {
      // The machinery: own network namespace, LCM, the substructure process.
      try {
        if (!w.shared_netns) messages::enter_private_network_namespace();
        else if (!messages::in_private_network_namespace())
          throw messages::TransportError("--shared-netns: the batch is not in a private network namespace");
      } catch (const std::exception& e) {
        summary.status = "failed";
        summary.error = e.what();
        infra_failure = true;
      }
    }
    if (record_ok && !infra_failure) {
      std::error_code ec;
      info["netns"] = fs::read_symlink("/proc/self/ns/net", ec).string();
      try {
        if (config.transport.kind == "in_process") {
          InProcessSubstructure sub(config.damper_model);
          summary = run_hybrid(config, sub, run_id);
        } else {
          LcmLinkSettings link;
          link.url = config.transport.url;
          link.lab_network = config.transport.lab_network;
          link.channels.prefix = config.transport.channel_prefix;
          link.step_timeout_s = config.transport.step_timeout_s;
          link.start_timeout_s = config.transport.start_timeout_s;
          if (config.transport.write_lcm_log) link.log_path = (partial / "run.lcmlog").string();
          LcmSubstructure sub(link);
          ChildProcess child;
          try {
            child = spawn_substructure(config, partial.string(), run_id, (partial / "substructure.log").string());
          } catch (const std::exception&) {
            infra_failure = true;
            throw;
          }
          summary = run_hybrid(config, sub, run_id);
          const int code = child.wait_or_kill(2.0);
          if (code != 0 && summary.status == "ok")
            std::cerr << "hybridsim batch worker: warning: substructure exited with code " << code << "\n";
        }
      } catch (const std::exception& e) {
        summary.status = "failed";
        summary.error = e.what();
      }
    }
  }

  info["status"] = summary.status;
  info["wall_s"] = std::chrono::duration<double>(Clock::now() - t0).count();
  info["finished_utc"] = utc_now();
  try {
    std::ofstream(partial / "batch-run.json") << std::setw(2) << info << "\n";
    write_summary_json(summary, config, (partial / "summary.json").string());
  } catch (const std::exception& e) {
    std::cerr << "hybridsim batch worker: cannot write results: " << e.what() << "\n";
    return kWorkerInfraFailed;
  }
  std::cout << format_summary(summary);
  if (infra_failure) {
    std::cerr << "hybridsim batch worker: " << summary.error << " (left in " << partial.string()
              << ", redone on resume)\n";
    return kWorkerInfraFailed;
  }
  // Durable, then visible: every file on disk before the rename makes the run final.
  for (const fs::directory_entry& e : fs::directory_iterator(partial))
    if (e.is_regular_file()) fsync_path(e.path());
  fsync_path(partial);
  std::cout << std::flush;
  // renameat2(RENAME_NOREPLACE): never replaces a finished result.
  if (::renameat2(AT_FDCWD, partial.c_str(), AT_FDCWD, final_path.c_str(), RENAME_NOREPLACE) != 0) {
    std::cerr << "hybridsim batch worker: cannot rename " << partial.string() << " to " << final_path.string()
              << ": " << std::strerror(errno) << "\n";
    return kWorkerInfraFailed;
  }
  fsync_path(w.runs_dir);
  return summary.status == "ok" ? kWorkerOk : kWorkerRunFailed;
}

}  // namespace server
