#pragma once
/// @file run_guard.h
/// What keeps one run's results folder to that run, and stops it cleanly on a signal:
///  - FolderLock: an exclusive flock(2) on <folder>/.hybridsim.lock held while a run writes
///    the folder; a second run into the same folder is refused (the kernel drops the lock
///    when the holder exits, also on SIGKILL, so a crash never leaves a stale lock);
///  - the exit-code convention of every hybridsim subcommand and executable;
///  - SIGINT/SIGTERM: a handler that only records the signal; the step loop polls it, stops,
///    flushes what it computed and exits with 128 + signal.

#include <csignal>
#include <stdexcept>
#include <string>

namespace common {

/// Exit codes of every subcommand (README "Exit codes").
enum ExitCode : int {
  kExitOk = 0,            ///< finished, results ok
  kExitRunFailed = 1,     ///< the run (or some run of a batch) failed; results say why
  kExitBadInput = 2,      ///< bad config, record, data file, option or folder; nothing ran
  kExitSigint = 130,      ///< interrupted by SIGINT (128 + 2), results so far on disk
  kExitSigterm = 143,     ///< interrupted by SIGTERM (128 + 15), results so far on disk
};

/// The results folder is held by another run.
class FolderBusyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Exclusive lock of a results folder (created if missing) for the lifetime of the object.
class FolderLock {
 public:
  FolderLock() = default;
  /// Takes the lock without waiting; throws FolderBusyError naming the folder and the
  /// holder's pid if another process holds it, std::runtime_error if the folder cannot be
  /// created or the lock file cannot be opened.
  explicit FolderLock(const std::string& folder);
  FolderLock(FolderLock&& other) noexcept;
  FolderLock& operator=(FolderLock&& other) noexcept;
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  ~FolderLock();
  bool held() const { return fd_ >= 0; }

  /// Name of the lock file inside the folder.
  static constexpr const char* kFileName = ".hybridsim.lock";

 private:
  int fd_ = -1;
};

/// Installs SIGINT and SIGTERM handlers that record the signal (first one wins) and return;
/// no SA_RESTART, so a blocking wait returns EINTR and its loop can look at the flag.
void install_interrupt_handlers();
/// 0, or the number of the first SIGINT/SIGTERM received since install_interrupt_handlers().
int interrupt_signal();
/// Exit code for an interrupted run: 128 + signal.
inline int exit_code_for_signal(int sig) { return 128 + sig; }
/// "SIGINT", "SIGTERM", or "signal N".
std::string signal_name(int sig);

/// A run stopped by SIGINT/SIGTERM (thrown by waits that notice interrupt_signal()).
class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int sig);
  int signal() const { return signal_; }

 private:
  int signal_;
};

/// Throws Interrupted if a SIGINT/SIGTERM has arrived.
inline void throw_if_interrupted() {
  if (const int sig = interrupt_signal()) throw Interrupted(sig);
}

}  // namespace common
