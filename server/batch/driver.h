#pragma once
/// @file driver.h
/// The batch driver: runs records `jobs` at a time, one `hybridsim batch worker` process
/// each, skipping finished runs (resume), setting failed ones aside on --retry-failed, and
/// stopping cleanly on Ctrl-C/SIGTERM/SIGHUP. Also the lock of a batch folder and the
/// payload of results gathered over MPI.

#include "server/batch/batch_set.h"
#include "server/batch/progress.h"

#include <string>
#include <vector>

namespace server::batch_internal {

struct DriverResult {
  int ran = 0;       // runs started in this call
  int skipped = 0;   // already finished
  bool interrupted = false;  // SIGINT/SIGTERM: running runs stopped, the rest not started
};

/// Unblocks SIGINT/SIGTERM/SIGHUP (the worker does this first thing: the driver blocks them
/// around fork/exec, so a pending one kills the worker at once).
void unblock_stop_signals();

/// Ctrl-C or kill of a local batch: stop launching, stop the running workers (their
/// .partial folders are redone on resume), write the summary of what is finished, and end
/// with the final line. Not under MPI (mpirun handles signals for all ranks).
void install_interrupt_handlers();

/// Runs the records `mine` (indices into b.records) that are not finished yet, `jobs` at a
/// time, one worker process each (a record's own run config if it names one, else b.config;
/// o.transport, if set, overrides the transport of every run). Progress goes to
/// `shared_progress` if given (IDA rounds), else to a display of its own.
DriverResult run_records(const BatchOptions& o, const BatchSet& b, const std::vector<std::size_t>& mine,
                         const std::string& progress_prefix, Progress* shared_progress = nullptr);

/// Holds an exclusive lock on OUT/.batch.lock while a local batch runs in OUT. The lock is
/// inherited by the worker processes (no O_CLOEXEC), so a batch restarted right after a kill
/// waits until the old workers are gone before it touches their .partial folders.
class DirLock {
 public:
  explicit DirLock(const std::string& out);
  ~DirLock();
  DirLock(const DirLock&) = delete;
  DirLock& operator=(const DirLock&) = delete;

 private:
  int fd_ = -1;
};

/// Result texts of the indices `mine`, as a JSON array [{index, summary, finished}] for the
/// gather on rank 0.
std::string results_payload(const std::string& out, const BatchSet& b, const std::vector<std::size_t>& mine);

}  // namespace server::batch_internal
