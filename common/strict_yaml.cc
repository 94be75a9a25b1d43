#include "common/strict_yaml.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

namespace common {

YamlSection::YamlSection(YAML::Node node, std::string file, std::string path)
    : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)) {
  if (!node_.IsMap()) {
    throw ConfigError(file_ + where(node_) + ": " + (path_.empty() ? "top level" : path_) +
                      ": expected a mapping of keys");
  }
  // yaml-cpp keeps both entries of a duplicated key and reads the first: refuse it, naming
  // both lines, so that an edit lower in the file never goes silently unused.
  std::map<std::string, int> first_line;
  for (const auto& kv : node_) {
    if (!kv.first.IsScalar()) continue;
    const std::string key = kv.first.Scalar();
    const int line = kv.first.Mark().line + 1;
    const auto [it, inserted] = first_line.emplace(key, line);
    if (!inserted) {
      throw ConfigError(file_ + where(kv.first) + ": " + key_path(key) + ": duplicated key (first given on line " +
                        std::to_string(it->second) + ")");
    }
  }
}

YamlSection YamlSection::load_file(const std::string& file) {
  YAML::Node root;
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) throw ConfigError(file + ": is a folder, not a config file");
  try {
    root = YAML::LoadFile(file);
  } catch (const YAML::BadFile&) {
    throw ConfigError(file + ": cannot open config file");
  } catch (const YAML::Exception& e) {
    throw ConfigError(file + ":" + std::to_string(e.mark.line + 1) + ": invalid YAML: " + e.msg);
  } catch (const std::exception& e) {  // e.g. std::ios_base::failure on an unreadable file
    throw ConfigError(file + ": cannot read config file: " + e.what());
  }
  if (!root || root.IsNull()) throw ConfigError(file + ": empty config file");
  return YamlSection(root, file, "");
}

std::string YamlSection::where(const YAML::Node& n) const {
  const YAML::Mark m = n.Mark();
  return m.line >= 0 ? ":" + std::to_string(m.line + 1) : std::string();
}

std::string YamlSection::key_path(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

std::string YamlSection::location(const std::string& key) const {
  YAML::Node n = node_[key];
  return file_ + (n ? where(n) : where(node_));
}

void YamlSection::fail(const std::string& key, const std::string& message) const {
  YAML::Node n = node_[key];
  const std::string line = n ? where(n) : where(node_);
  throw ConfigError(file_ + line + ": " + key_path(key) + ": " + message);
}

void YamlSection::allow_only(std::initializer_list<const char*> allowed) const {
  for (const auto& kv : node_) {
    const std::string key = kv.first.as<std::string>();
    bool ok = false;
    for (const char* a : allowed) ok = ok || key == a;
    if (!ok) {
      std::ostringstream known;
      for (const char* a : allowed) known << " " << a;
      throw ConfigError(file_ + where(kv.first) + ": " + key_path(key) +
                        ": unknown key (known keys:" + known.str() + ")");
    }
  }
}

bool YamlSection::has(const std::string& key) const { return static_cast<bool>(node_[key]); }

YAML::Node YamlSection::child(const std::string& key) const {
  YAML::Node n = node_[key];
  if (!n) throw ConfigError(file_ + where(node_) + ": " + key_path(key) + ": missing required key");
  return n;
}

double YamlSection::get_double(const std::string& key) const {
  YAML::Node n = child(key);
  double v = 0.0;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    fail(key, "expected a number, got '" + (n.IsScalar() ? n.Scalar() : std::string("non-scalar")) + "'");
  }
  if (!std::isfinite(v)) fail(key, "must be finite");
  return v;
}
double YamlSection::get_double(const std::string& key, double fallback) const {
  return has(key) ? get_double(key) : fallback;
}
double YamlSection::get_double_in(const std::string& key, double lo, double hi) const {
  const double v = get_double(key);
  if (v < lo || v > hi) {
    std::ostringstream msg;
    msg << "must be in [" << lo << ", " << hi << "], got " << v;
    fail(key, msg.str());
  }
  return v;
}
double YamlSection::get_double_in(const std::string& key, double fallback, double lo, double hi) const {
  return has(key) ? get_double_in(key, lo, hi) : fallback;
}
int YamlSection::get_int(const std::string& key) const {
  YAML::Node n = child(key);
  try {
    return n.as<int>();
  } catch (const YAML::Exception&) {
    fail(key, "expected an integer, got '" + (n.IsScalar() ? n.Scalar() : std::string("non-scalar")) + "'");
  }
}
int YamlSection::get_int(const std::string& key, int fallback) const {
  return has(key) ? get_int(key) : fallback;
}
bool YamlSection::get_bool(const std::string& key, bool fallback) const {
  if (!has(key)) return fallback;
  YAML::Node n = child(key);
  try {
    return n.as<bool>();
  } catch (const YAML::Exception&) {
    fail(key, "expected true or false, got '" + (n.IsScalar() ? n.Scalar() : std::string("non-scalar")) + "'");
  }
}
std::string YamlSection::get_string(const std::string& key) const {
  YAML::Node n = child(key);
  if (!n.IsScalar()) fail(key, "expected a string");
  return n.Scalar();
}
std::string YamlSection::get_string(const std::string& key, const std::string& fallback) const {
  return has(key) ? get_string(key) : fallback;
}
std::string YamlSection::get_choice(const std::string& key, std::initializer_list<const char*> choices) const {
  const std::string v = get_string(key);
  std::ostringstream known;
  for (const char* c : choices) {
    if (v == c) return v;
    known << " " << c;
  }
  fail(key, "unknown value '" + v + "' (expected one of:" + known.str() + ")");
}
std::string YamlSection::get_choice(const std::string& key, const std::string& fallback,
                                    std::initializer_list<const char*> choices) const {
  return has(key) ? get_choice(key, choices) : fallback;
}
std::vector<double> YamlSection::get_double_list(const std::string& key) const {
  YAML::Node n = child(key);
  if (!n.IsSequence()) fail(key, "expected a list of numbers");
  std::vector<double> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    try {
      out.push_back(n[i].as<double>());
    } catch (const YAML::Exception&) {
      fail(key, "entry [" + std::to_string(i) + "] is not a number");
    }
    if (!std::isfinite(out.back())) fail(key, "entry [" + std::to_string(i) + "] is not finite");
  }
  return out;
}
std::vector<int> YamlSection::get_int_list(const std::string& key) const {
  YAML::Node n = child(key);
  if (!n.IsSequence()) fail(key, "expected a list of integers");
  std::vector<int> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    try {
      out.push_back(n[i].as<int>());
    } catch (const YAML::Exception&) {
      fail(key, "entry [" + std::to_string(i) + "] is not an integer");
    }
  }
  return out;
}
YamlSection YamlSection::section(const std::string& key) const {
  YAML::Node n = child(key);
  if (!n.IsMap()) fail(key, "expected a mapping");
  return YamlSection(n, file_, key_path(key));
}
std::vector<YamlSection> YamlSection::section_list(const std::string& key) const {
  YAML::Node n = child(key);
  if (!n.IsSequence()) fail(key, "expected a list");
  std::vector<YamlSection> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    if (!n[i].IsMap()) fail(key, "entry [" + std::to_string(i) + "] is not a mapping");
    out.emplace_back(n[i], file_, key_path(key) + "[" + std::to_string(i) + "]");
  }
  return out;
}

}  // namespace common
