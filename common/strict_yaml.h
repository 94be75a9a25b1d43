#pragma once
/// @file strict_yaml.h
/// Strict reading of YAML configs: every key must be known, every value of the right type
/// and in range. Errors are ConfigError naming the file, the line and the key path, e.g.
///   configs/three-story.yaml:12: building.story_mass_kip_s2_per_in[1]: must be > 0, got -1

#include <yaml-cpp/yaml.h>

#include <initializer_list>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace common {

/// A user-input error in a config file.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A view of one YAML mapping with its file and key path, for strict typed reads.
class YamlSection {
 public:
  YamlSection(YAML::Node node, std::string file, std::string path);

  /// Loads a file; throws ConfigError if it is missing or not valid YAML.
  static YamlSection load_file(const std::string& file);

  /// Throws ConfigError if the mapping has a key not in `allowed`.
  void allow_only(std::initializer_list<const char*> allowed) const;
  bool has(const std::string& key) const;

  double get_double(const std::string& key) const;  ///< required
  double get_double(const std::string& key, double fallback) const;
  /// Required double within [lo, hi].
  double get_double_in(const std::string& key, double lo, double hi) const;
  double get_double_in(const std::string& key, double fallback, double lo, double hi) const;
  int get_int(const std::string& key) const;
  int get_int(const std::string& key, int fallback) const;
  bool get_bool(const std::string& key, bool fallback) const;
  std::string get_string(const std::string& key) const;
  std::string get_string(const std::string& key, const std::string& fallback) const;
  /// Required string that must be one of `choices`.
  std::string get_choice(const std::string& key, std::initializer_list<const char*> choices) const;
  std::string get_choice(const std::string& key, const std::string& fallback,
                         std::initializer_list<const char*> choices) const;
  std::vector<double> get_double_list(const std::string& key) const;
  std::vector<int> get_int_list(const std::string& key) const;
  /// Required nested mapping.
  YamlSection section(const std::string& key) const;
  /// Required sequence of mappings.
  std::vector<YamlSection> section_list(const std::string& key) const;

  [[noreturn]] void fail(const std::string& key, const std::string& message) const;
  /// "file:line" of `key` (of this mapping if the key is absent), for checks made later.
  std::string location(const std::string& key) const;
  const YAML::Node& node() const { return node_; }
  const std::string& file() const { return file_; }
  /// Key path of this section ("" at the top level) joined with `key`.
  std::string key_path(const std::string& key) const;

 private:
  YAML::Node child(const std::string& key) const;
  std::string where(const YAML::Node& n) const;
  YAML::Node node_;
  std::string file_;
  std::string path_;
};

}  // namespace common
