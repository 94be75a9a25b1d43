#pragma once
/// @file progress.h
/// The batch progress display: on a terminal one redrawn bar (runs done, failed, running,
/// rate, elapsed, time left) with failures printed above it; otherwise (logs, MPI) one line
/// per finished run. Shared by `hybridsim batch` and `hybridsim ida` (whose total is an upper
/// bound, refined by set_plan() as the hunt-and-fill traces finish).

#include "server/batch/batch.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>

#include "common/number_format.h"

namespace server::batch_internal {

using Clock = std::chrono::steady_clock;

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
         << " (" << common::format_fixed(wall_s, 2) << " s)";
    if (!error.empty()) line << ": " << error;
    if (tty_) {
      if (state != "ok") std::cout << "\r\033[K" << line.str() << "\n";
      draw();
    } else {
      line << "  | failed " << failed_ << ", " << rate_text() << ", elapsed " << common::format_fixed(elapsed(), 1)
           << " s, left " << eta_text();
      std::cout << line.str() << std::endl;
    }
  }

  /// A new plan: `total` runs in all, `to_run` of them still to run (IDA rounds).
  void set_plan(int total, int to_run) {
    total_ = total;
    to_run_ = finished_now_ + to_run;
    draw();
  }

  int finished_now() const { return finished_now_; }  ///< runs finished since the start
  int failed() const { return failed_; }               ///< of those, failed

  void tick() {
    if (tty_ && !quiet_ && std::chrono::duration<double>(Clock::now() - last_draw_).count() > 0.25) draw();
  }

  void end() {
    if (tty_ && !quiet_) std::cout << "\n" << std::flush;
  }

 private:
  double elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  std::string rate_text() const {
    const double t = elapsed();
    return common::format_fixed(t > 0.0 ? finished_now_ / t : 0.0, 2) + " runs/s";
  }

  std::string eta_text() const {
    const int left = to_run_ - finished_now_;
    if (left <= 0) return "0 s";
    if (finished_now_ == 0) return "?";
    const double s = elapsed() / finished_now_ * left;
    std::ostringstream o;
    if (s >= 3600) o << static_cast<int>(s / 3600) << " h " << static_cast<int>(std::fmod(s, 3600) / 60) << " min";
    else if (s >= 60) o << static_cast<int>(s / 60) << " min " << static_cast<int>(std::fmod(s, 60)) << " s";
    else o << common::format_fixed(s, 0) << " s";
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
              << " failed, " << running_ << " running, " << rate_text() << ", " << common::format_fixed(elapsed(), 0)
              << " s elapsed, ~"
              << eta_text() << " left" << std::flush;
  }

  int total_, done_, to_run_, jobs_;
  bool quiet_;
  std::string prefix_;
  bool tty_;
  Clock::time_point start_, last_draw_{};
  int running_ = 0, failed_ = 0, finished_now_ = 0;
};

}  // namespace server::batch_internal
