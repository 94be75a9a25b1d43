#pragma once
/// @file process.h
/// Child processes of a run (brfd-substructure, brfd-rig): started with fork/exec, killed
/// when the server dies (PR_SET_PDEATHSIG), reaped with a timeout.

#include <string>
#include <vector>

namespace server {

class ChildProcess {
 public:
  ChildProcess() = default;
  /// Starts `executable` with `args`; stdout/stderr go to `log_path` (appended) if not empty.
  /// Throws std::runtime_error naming the executable if it cannot be started: a failed
  /// exec() is reported back at once through a close-on-exec pipe (errno of execv), so the
  /// caller never waits for a handshake with a process that does not exist.
  ChildProcess(const std::string& executable, const std::vector<std::string>& args,
               const std::string& log_path);
  ChildProcess(ChildProcess&& other) noexcept;
  ChildProcess& operator=(ChildProcess&& other) noexcept;
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess();  ///< kills and reaps a child still running

  /// False once the child has exited (reaped with WNOHANG; exit_code() then tells how).
  bool running();
  /// Exit code of an exited child (128 + signal if killed by one), -1 while unknown.
  int exit_code() const { return exit_code_; }
  /// Waits up to timeout_s for exit; returns the exit code, or -1 if it had to be killed.
  int wait_or_kill(double timeout_s);
  int pid() const { return pid_; }

 private:
  int pid_ = -1;
  int exit_code_ = -1;
};

/// Path of an executable that sits beside the running program (e.g. brfd-substructure beside
/// hybridsim), unless `name` already contains a '/'.
std::string sibling_executable(const std::string& name);

}  // namespace server
