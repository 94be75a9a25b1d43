#include "server/run/time_history_writer.h"

#include <stdexcept>

namespace server {

namespace {
constexpr std::size_t kRowsPerBlock = 1024;
}  // namespace

TimeHistoryWriter::TimeHistoryWriter(std::unique_ptr<TimeHistorySink> sink, std::size_t columns, long expected_rows)
    : sink_(std::move(sink)), columns_(columns), block_values_(kRowsPerBlock * columns) {
  if (!sink_ || columns == 0) throw std::invalid_argument("TimeHistoryWriter: no sink or no columns");
  const std::size_t blocks = static_cast<std::size_t>(std::max(1L, expected_rows)) / kRowsPerBlock + 2;
  storage_.resize(blocks);
  queue_.reserve(blocks + 64);    // a block is in at most one of the two lists at a time
  written_.reserve(blocks + 64);
  // Value-initialized: the pages are touched here, not by the step loop (a first-touch page
  // fault costs microseconds on a virtual machine).
  for (Block& b : storage_) b.values.reset(new double[block_values_]());
  take_free_block();
  thread_ = std::thread(&TimeHistoryWriter::writer_loop, this);
}

TimeHistoryWriter::~TimeHistoryWriter() { finish(); }

void TimeHistoryWriter::end_row() {
  if (cursor_ >= block_end_) hand_over();
}

// Called with mutex_ held (or before the writer thread exists).
void TimeHistoryWriter::take_free_block() {
  if (next_free_ < storage_.size()) {
    current_ = &storage_[next_free_++];
  } else if (!written_.empty()) {
    current_ = written_.back();
    written_.pop_back();
  } else {
    storage_.emplace_back();  // grows only when the writer lags far behind
    storage_.back().values.reset(new double[block_values_]());
    current_ = &storage_.back();
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
  take_free_block();
  lock.unlock();
  wake_writer_.notify_one();
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
