#pragma once
/// @file time_history_writer.h
/// Time histories written off the step loop. The loop only copies doubles into preallocated
/// blocks (no formatting, no system call, no allocation while the preallocation lasts); a
/// writer thread hands each block to the file format (time_history_sink.h: CSV in the
/// shortest round-trip text, or HDF5 columns, hdf5_time_history.h) as soon as it is handed
/// over. hand_over() is non-blocking; finish() waits until every row is on disk.
/// Memory does not grow with the run: a fixed pool of blocks (64 × 1024 rows) is written and
/// reused; only a writer lagging by more than that grows it, up to a cap where the loop waits.

#include "server/run/time_history_sink.h"

#include <condition_variable>
#include <cstdio>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace server {

class TimeHistoryWriter {
 public:
  /// Rows of `columns` values go to `sink`; starts the writer thread. `expected_rows` sizes
  /// the preallocated blocks.
  TimeHistoryWriter(std::unique_ptr<TimeHistorySink> sink, std::size_t columns, long expected_rows);
  ~TimeHistoryWriter();  ///< finish()es
  TimeHistoryWriter(const TimeHistoryWriter&) = delete;
  TimeHistoryWriter& operator=(const TimeHistoryWriter&) = delete;

  void add(double value) { *cursor_++ = value; }  ///< next value of the current row
  void end_row();     ///< ends the row; hands the block over when it is full
  void hand_over();   ///< gives the rows so far to the writer thread (non-blocking)
  void finish();      ///< hands over, waits until everything is written, closes the file
  /// Error of the writer thread, "" if none (a full disk must not go unnoticed).
  std::string error() const;
  /// Blocks of 1024 rows allocated so far (pool + growth): bounded, whatever the run's length.
  std::size_t allocated_blocks() const;

 private:
  struct Block {
    std::unique_ptr<double[]> values;
    std::size_t count = 0;           // set when handed over
  };
  void writer_loop();
  void write_block(const Block& block);
  /// Next block for the step loop; with `lock` (mutex_ held) it may wait for the writer
  /// when the pool is at its cap.
  void take_free_block(std::unique_lock<std::mutex>* lock);


  // Touched by the step loop on every value: a cache line of its own, so the writer
  // thread's reads never bounce it between cores.
  alignas(64) double* cursor_ = nullptr;
  double* block_end_ = nullptr;
  Block* current_ = nullptr;
  alignas(64) std::unique_ptr<TimeHistorySink> sink_;
  std::size_t columns_ = 0;
  std::size_t block_values_ = 0;
  std::deque<Block> storage_;        // preallocated blocks (stable addresses), reused
  std::size_t next_free_ = 0;
  std::vector<Block*> queue_;        // handed over, not yet written (capacity reserved: no allocation per block)
  std::vector<Block*> written_;      // written, may be reused (capacity reserved)
  mutable std::mutex mutex_;
  std::condition_variable wake_writer_, written_all_, block_written_;
  bool stopping_ = false;
  bool busy_ = false;
  std::string error_;
  std::thread thread_;
};

}  // namespace server
