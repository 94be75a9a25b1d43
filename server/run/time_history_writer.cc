#include "server/run/time_history_writer.h"

#include <stdexcept>

namespace server {

namespace {
constexpr std::size_t kRowsPerBlock = 1024;
// Preallocated blocks: enough for 64 s at 1024 rows/s. Blocks are reused once written, so
// a run of any length streams through this pool (the pool never scales with the run).
constexpr std::size_t kPreallocatedBlocks = 64;
// The pool grows only while the writer lags; beyond this the step loop waits for the disk
// instead of holding an unbounded backlog in memory.
constexpr std::size_t kMaxBlocks = 1024;
}  // namespace

TimeHistoryWriter::TimeHistoryWriter(std::unique_ptr<TimeHistorySink> sink, std::size_t columns, long expected_rows)
    : sink_(std::move(sink)), columns_(columns), block_values_(kRowsPerBlock * columns) {
  if (!sink_ || columns == 0) throw std::invalid_argument("TimeHistoryWriter: no sink or no columns");
  const std::size_t blocks =
      std::min(static_cast<std::size_t>(std::max(1L, expected_rows)) / kRowsPerBlock + 2, kPreallocatedBlocks);
  storage_.resize(blocks);
  queue_.reserve(blocks + 64);    // a block is in at most one of the two lists at a time
  written_.reserve(blocks + 64);
  // Value-initialized: the pages are touched here, not by the step loop (a first-touch page
  // fault costs microseconds on a virtual machine).
  for (Block& b : storage_) b.values.reset(new double[block_values_]());
  take_free_block(nullptr);
  thread_ = std::thread(&TimeHistoryWriter::writer_loop, this);
}

TimeHistoryWriter::~TimeHistoryWriter() { finish(); }

void TimeHistoryWriter::end_row() {
  if (cursor_ >= block_end_) hand_over();
}

// Called with mutex_ held (or before the writer thread exists).
void TimeHistoryWriter::take_free_block(std::unique_lock<std::mutex>* lock) {
  if (lock && next_free_ >= storage_.size() && written_.empty() && storage_.size() >= kMaxBlocks) {
    block_written_.wait(*lock, [&] { return !written_.empty(); });
  }
  if (next_free_ < storage_.size()) {
    current_ = &storage_[next_free_++];
  } else if (!written_.empty()) {
    current_ = written_.back();
    written_.pop_back();
  } else {
    storage_.emplace_back();  // grows only when the writer lags far behind
    storage_.back().values.reset(new double[block_values_]());
    current_ = &storage_.back();
    // Mark it taken: without this the next call handed out the same block again while it
    // was queued, and a lagging writer lost the rows of the block written over (seen as
    // 256-1000 missing rows at the end of short runs with flush_every_steps 256).
    next_free_ = storage_.size();
  }
  current_->count = 0;
  cursor_ = current_->values.get();
  block_end_ = cursor_ + block_values_;
}

void TimeHistoryWriter::hand_over() {
  std::unique_lock<std::mutex> lock(mutex_);
  const std::size_t count = static_cast<std::size_t>(cursor_ - current_->values.get());
  if (count == 0) return;
  current_->count = count;
  queue_.push_back(current_);
  wake_writer_.notify_one();
  take_free_block(&lock);
  lock.unlock();
}

void TimeHistoryWriter::finish() {
  if (!thread_.joinable()) return;
  hand_over();
  {
    std::unique_lock<std::mutex> lock(mutex_);
    written_all_.wait(lock, [&] { return queue_.empty() && !busy_; });
    stopping_ = true;
  }
  wake_writer_.notify_one();
  thread_.join();
  try {
    sink_->close();
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (error_.empty()) error_ = e.what();
  }
}

std::size_t TimeHistoryWriter::allocated_blocks() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return storage_.size();
}

std::string TimeHistoryWriter::error() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

void TimeHistoryWriter::writer_loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_writer_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
    if (queue_.empty() && stopping_) return;
    Block* block = queue_.front();
    queue_.erase(queue_.begin());  // a handful of entries at most: no allocation
    busy_ = true;
    lock.unlock();
    write_block(*block);
    lock.lock();
    busy_ = false;
    written_.push_back(block);
    block_written_.notify_all();
    if (queue_.empty()) written_all_.notify_all();
  }
}

void TimeHistoryWriter::write_block(const Block& block) {
  try {
    sink_->write_rows(block.values.get(), block.count / columns_);
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (error_.empty()) error_ = e.what();
  }
}

}  // namespace server
