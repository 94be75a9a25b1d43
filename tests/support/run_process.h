#pragma once
// Runs a program to completion for CLI tests, capturing stdout and stderr.
#include <sys/types.h>

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

/// Starts `argv` in the background, stdout and stderr to `log_path`; returns its pid.
pid_t start_process(const std::vector<std::string>& argv, const std::string& log_path);

/// SIGKILLs `pid` (no chance to clean up) and waits for it, then reaps for up to 10 s the
/// orphans handed to this process (a test that kills a batch driver makes itself the
/// subreaper, PR_SET_CHILD_SUBREAPER: the workers get SIGTERM when their driver dies, their
/// substructures when they die). Returns false if the kill failed.
bool kill_and_reap(pid_t pid);

/// Writes `text` to `path` (creating parent folders).
void write_text(const std::string& path, const std::string& text);
/// Reads a whole file ("" if it does not exist).
std::string read_text(const std::string& path);
/// A fresh empty folder under the system temp dir.
std::string fresh_temp_dir(const std::string& name);

}  // namespace test_support
