#include "server/batch/driver.h"

#include "common/number_format.h"
#include "common/process.h"
#include "messages/lcm_bus.h"
#include "server/batch/batch_files.h"
#include "server/batch/progress.h"
#include "server/run/hybrid_run.h"
#include "server/run/run_config.h"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <poll.h>
#include <sys/file.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cstdio>
#include <map>
#include <memory>
#include <thread>

namespace server::batch_internal {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

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

volatile sig_atomic_t g_interrupted = 0;

/// pidfd_open(2) of a child: a file descriptor that polls readable when the child exits.
struct PidFd {
  int fd = -1;
  PidFd() = default;
  explicit PidFd(int pid) : fd(pid > 0 ? static_cast<int>(::syscall(SYS_pidfd_open, pid, 0)) : -1) {}
  PidFd(PidFd&& o) noexcept : fd(o.fd) { o.fd = -1; }
  PidFd& operator=(PidFd&& o) noexcept {
    std::swap(fd, o.fd);
    return *this;
  }
  ~PidFd() {
    if (fd >= 0) ::close(fd);
  }
};

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

/// One worker process of the driver.
struct Slot {
  ChildProcess proc;
  std::size_t index;
  Clock::time_point start;
  PidFd exit_fd;  // readable when the worker has exited
};

/// Blocks until a worker exits, a signal arrives or `timeout_s` passes (for the progress
/// bar). Short runs (in-process, a few ms each) make the driver's reaction time part of the
/// batch's throughput: a fixed polling sleep would idle the cores between runs.
void wait_for_an_exit(const std::vector<std::unique_ptr<Slot>>& running, double timeout_s) {
  std::vector<pollfd> fds;
  for (const auto& slot : running)
    if (slot->exit_fd.fd >= 0) fds.push_back({slot->exit_fd.fd, POLLIN, 0});
  if (fds.size() != running.size()) {  // no pidfd (old kernel): poll the way it was
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    return;
  }
  ::poll(fds.data(), fds.size(), static_cast<int>(timeout_s * 1000));  // EINTR: the loop checks the flag
}


}  // namespace

void unblock_stop_signals() {
  const sigset_t set = stop_signals();
  pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
}
namespace {
extern "C" void on_interrupt(int) { g_interrupted = 1; }
}  // namespace

void install_interrupt_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_interrupt;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGHUP, &sa, nullptr);
}

DriverResult run_records(const BatchOptions& o, const BatchSet& b, const std::vector<std::size_t>& mine,
                         const std::string& progress_prefix, Progress* shared_progress) {
  DriverResult result;
  std::vector<std::size_t> todo;
  for (std::size_t i : mine) {
    const BatchRecord& r = b.records[i];
    std::error_code ec;
    const fs::path summary_path = final_dir(o.out, r.label) / "summary.json";
    std::string why;
    const bool finished = readable_summary(summary_path, &why);
    if (!finished && fs::exists(summary_path, ec)) {
      // Written by a batch on a full disk before summaries were atomic: not a result.
      const fs::path aside = runs_dir(o.out) / (r.label + ".unreadable-" + std::to_string(messages::now_utime()));
      std::cerr << progress_prefix << "batch: " << summary_path.string() << " is unreadable (" << why
                << "): kept aside as " << aside.string() << ", the record runs again\n";
      fs::rename(final_dir(o.out, r.label), aside);
    } else if (finished) {
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

  if (!o.quiet && !shared_progress) {
    std::cout << progress_prefix << "batch: " << mine.size() << " records, " << result.skipped
              << " already finished, " << todo.size() << " to run, " << o.jobs << " at a time; results in "
              << o.out << std::endl;
  }
  std::unique_ptr<Progress> own_progress;
  if (!shared_progress)
    own_progress = std::make_unique<Progress>(static_cast<int>(mine.size()), result.skipped,
                                              static_cast<int>(todo.size()), o.jobs, o.quiet, progress_prefix, !o.mpi);
  Progress& progress = shared_progress ? *shared_progress : *own_progress;

  std::vector<std::unique_ptr<Slot>> running;
  std::size_t next = 0;
  const std::string exe = self_exe();
  // The run config of each record: the batch's, or the record's own (IDA cases).
  std::map<std::string, RunConfig> configs;
  auto config_of = [&](const BatchRecord& r) -> const RunConfig& {
    const std::string& path = r.config.empty() ? b.config : r.config;
    auto it = configs.find(path);
    if (it == configs.end()) it = configs.emplace(path, load_run_config(path)).first;
    return it->second;
  };

  auto launch = [&](std::size_t i) {
    const BatchRecord& r = b.records[i];
    const RunConfig& base = config_of(r);
    const fs::path partial = partial_dir(o.out, r.label);
    fs::remove_all(partial);  // an interrupted run: redone from the start
    fs::create_directories(partial);
    char idx[16];
    std::snprintf(idx, sizeof idx, "R%04zu_", i);
    const std::string prefix = o.same_channel_prefix ? base.transport.channel_prefix
                                                     : base.transport.channel_prefix + idx;
    std::vector<std::string> args{"batch", "worker", "--config", r.config.empty() ? b.config : r.config, "--record", r.path,
                                  "--scale", common::format_shortest(r.scale), "--label", r.label, "--runs-dir",
                                  fs::absolute(runs_dir(o.out)).string(), "--channel-prefix", prefix,
                                  "--index", std::to_string(i)};
    if (o.shared_netns) args.push_back("--shared-netns");
    if (!o.transport.empty()) {
      args.push_back("--transport");
      args.push_back(o.transport);
    }
    if (o.duration_s != 0.0) {
      args.push_back("--duration");
      args.push_back(common::format_shortest(o.duration_s));
    }
    auto slot = std::make_unique<Slot>();
    slot->index = i;
    slot->start = Clock::now();
    {
      StopSignalsBlocked blocked;
      slot->proc = ChildProcess(exe, args, (partial / "worker.log").string());
    }
    slot->exit_fd = PidFd(slot->proc.pid());
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
      RunConfig c = config_of(r);
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
    if (!running.empty()) wait_for_an_exit(running, 0.25);
  }
  if (own_progress) own_progress->end();
  return result;
}

DirLock::DirLock(const std::string& out) {
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

DirLock::~DirLock() {
  if (fd_ >= 0) ::close(fd_);
}

std::string results_payload(const std::string& out, const BatchSet& b, const std::vector<std::size_t>& mine) {
  json arr = json::array();
  for (std::size_t i : mine) {
    const RunResult r = read_result(out, b.records[i].label);
    arr.push_back({{"index", i}, {"state", r.state}, {"finished", r.finished}, {"summary", r.summary}});
  }
  return arr.dump();
}

}  // namespace server::batch_internal
