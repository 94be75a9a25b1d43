#pragma once
// Runs a program to completion for CLI tests, capturing stdout and stderr.
#include <string>
#include <vector>

namespace test_support {

struct ProcessResult {
  int exit_code = -1;   // 128 + signal if killed by a signal
  std::string out;      // stdout
  std::string err;      // stderr
};

/// Runs `argv` (argv[0] is the executable path) and waits for it.
ProcessResult run_process(const std::vector<std::string>& argv);

/// Writes `text` to `path` (creating parent folders).
void write_text(const std::string& path, const std::string& text);
/// Reads a whole file ("" if it does not exist).
std::string read_text(const std::string& path);
/// A fresh empty folder under the system temp dir.
std::string fresh_temp_dir(const std::string& name);

}  // namespace test_support
