// The record set of a batch: a list file or a folder of records (batch.h: load_record_set).
#include "server/batch/batch.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace server {

namespace fs = std::filesystem;

namespace {

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

}  // namespace

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

}  // namespace server
