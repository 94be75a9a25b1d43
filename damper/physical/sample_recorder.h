#pragma once
/// @file sample_recorder.h
/// Per-step record of the physical substructure (physical.csv): rows of doubles collected in
/// preallocated chunks by the control loop and formatted and written by a writer thread, so
/// the loop never formats text or touches the disk. A full chunk is handed over at once;
/// finish() (also on a trip) writes every row recorded so far.

#include <condition_variable>
#include <cstdio>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace damper::physical {

class SampleRecorder {
 public:
  /// Creates `path` and writes the header line. Throws std::runtime_error naming the file.
  SampleRecorder(const std::string& path, const std::vector<std::string>& columns, std::size_t chunk_rows = 4096);
  ~SampleRecorder();
  SampleRecorder(const SampleRecorder&) = delete;
  SampleRecorder& operator=(const SampleRecorder&) = delete;

  /// Appends one row of columns().size() values.
  void add_row(const double* values);
  /// Writes everything recorded, closes the file. Idempotent.
  void finish();
  std::size_t columns() const { return columns_; }
  long rows() const { return rows_; }

 private:
  void writer_loop();
  void hand_over();

  std::size_t columns_;
  std::size_t chunk_rows_;
  std::FILE* file_ = nullptr;
  std::vector<double> current_;
  std::size_t current_rows_ = 0;
  long rows_ = 0;
  std::vector<std::vector<double>> spare_;
  std::deque<std::pair<std::vector<double>, std::size_t>> queue_;
  std::mutex mutex_;
  std::condition_variable cv_;
  bool stop_ = false;
  bool finished_ = false;
  std::thread writer_;
};

}  // namespace damper::physical
