#include "server/run/csv_writer.h"

#include <charconv>
#include <stdexcept>

namespace server {

namespace {
constexpr std::size_t kRowsPerBlock = 1024;
}  // namespace

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& columns, long expected_rows)
    : path_(path), columns_(columns.size()), block_values_(kRowsPerBlock * columns.size()) {
  file_ = std::fopen(path.c_str(), "w");
  if (!file_) throw std::runtime_error("cannot write " + path);
  for (std::size_t i = 0; i < columns.size(); ++i) {
    std::fputs(columns[i].c_str(), file_);
    std::fputc(i + 1 < columns.size() ? ',' : '\n', file_);
  }
  std::fflush(file_);
  const std::size_t blocks = static_cast<std::size_t>(std::max(1L, expected_rows)) / kRowsPerBlock + 2;
  storage_.resize(blocks);
  // Value-initialized: the pages are touched here, not by the step loop (a first-touch page
  // fault costs microseconds on a virtual machine).
  for (Block& b : storage_) b.values.reset(new double[block_values_]());
  take_free_block();
  text_.resize(block_values_ * 32 + kRowsPerBlock);
  thread_ = std::thread(&CsvWriter::writer_loop, this);
}

CsvWriter::~CsvWriter() {
  finish();
  std::fclose(file_);
}

void CsvWriter::end_row() {
  if (cursor_ >= block_end_) hand_over();
}

// Called with mutex_ held (or before the writer thread exists).
void CsvWriter::take_free_block() {
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

void CsvWriter::hand_over() {
  std::unique_lock<std::mutex> lock(mutex_);
  const std::size_t count = static_cast<std::size_t>(cursor_ - current_->values.get());
  if (count == 0) return;
  current_->count = count;
  queue_.push_back(current_);
  take_free_block();
  lock.unlock();
  wake_writer_.notify_one();
}

void CsvWriter::finish() {
  if (!thread_.joinable()) return;
  hand_over();
  {
    std::unique_lock<std::mutex> lock(mutex_);
    written_all_.wait(lock, [&] { return queue_.empty() && !busy_; });
    stopping_ = true;
  }
  wake_writer_.notify_one();
  thread_.join();
  std::fflush(file_);
}

std::string CsvWriter::error() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

void CsvWriter::writer_loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_writer_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
    if (queue_.empty() && stopping_) return;
    Block* block = queue_.front();
    queue_.pop_front();
    busy_ = true;
    lock.unlock();
    write_block(*block);
    lock.lock();
    busy_ = false;
    written_.push_back(block);
    if (queue_.empty()) written_all_.notify_all();
  }
}

void CsvWriter::write_block(const Block& block) {
  char* out = text_.data();
  char* const end = text_.data() + text_.size();
  for (std::size_t i = 0; i < block.count; ++i) {
    out = std::to_chars(out, end, block.values[i]).ptr;
    *out++ = (i + 1) % columns_ == 0 ? '\n' : ',';
  }
  const std::size_t bytes = static_cast<std::size_t>(out - text_.data());
  if (std::fwrite(text_.data(), 1, bytes, file_) != bytes || std::fflush(file_) != 0) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (error_.empty()) error_ = "write failed on " + path_;
  }
}

}  // namespace server
