#include "damper/physical/sample_recorder.h"

#include <pthread.h>
#include <sched.h>

#include <stdexcept>

namespace damper::physical {

SampleRecorder::SampleRecorder(const std::string& path, const std::vector<std::string>& columns,
                               std::size_t chunk_rows)
    : columns_(columns.size()), chunk_rows_(chunk_rows) {
  file_ = std::fopen(path.c_str(), "w");
  if (!file_) throw std::runtime_error("cannot write '" + path + "'");
  for (std::size_t i = 0; i < columns.size(); ++i) std::fprintf(file_, "%s%s", i ? "," : "", columns[i].c_str());
  std::fputc('\n', file_);
  std::fflush(file_);
  current_.resize(columns_ * chunk_rows_);
  for (int i = 0; i < 3; ++i) spare_.emplace_back(columns_ * chunk_rows_);
  writer_ = std::thread(&SampleRecorder::writer_loop, this);
}

SampleRecorder::~SampleRecorder() { finish(); }

void SampleRecorder::add_row(const double* values) {
  double* dst = current_.data() + current_rows_ * columns_;
  for (std::size_t i = 0; i < columns_; ++i) dst[i] = values[i];
  ++current_rows_;
  ++rows_;
  if (current_rows_ == chunk_rows_) hand_over();
}

void SampleRecorder::hand_over() {
  std::unique_lock<std::mutex> lock(mutex_);
  std::vector<double> next;
  if (!spare_.empty()) {
    next = std::move(spare_.back());
    spare_.pop_back();
  } else {
    next.resize(columns_ * chunk_rows_);  // writer behind by 3 chunks: allocate rather than block
  }
  queue_.emplace_back(std::move(current_), current_rows_);
  current_ = std::move(next);
  current_rows_ = 0;
  lock.unlock();
  cv_.notify_one();
}

void SampleRecorder::writer_loop() {
  // Formatting is not real-time work: never compete with the control loop's SCHED_FIFO.
  sched_param sp{};
  sp.sched_priority = 0;
  pthread_setschedparam(pthread_self(), SCHED_OTHER, &sp);
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    cv_.wait(lock, [&] { return stop_ || !queue_.empty(); });
    if (queue_.empty() && stop_) return;
    auto chunk = std::move(queue_.front());
    queue_.pop_front();
    lock.unlock();
    for (std::size_t r = 0; r < chunk.second; ++r) {
      const double* v = chunk.first.data() + r * columns_;
      for (std::size_t i = 0; i < columns_; ++i) std::fprintf(file_, i ? ",%.10g" : "%.10g", v[i]);
      std::fputc('\n', file_);
    }
    std::fflush(file_);
    lock.lock();
    spare_.push_back(std::move(chunk.first));
  }
}

void SampleRecorder::finish() {
  if (finished_) return;
  finished_ = true;
  if (current_rows_ > 0) hand_over();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  cv_.notify_one();
  if (writer_.joinable()) writer_.join();
  if (file_) std::fclose(file_);
  file_ = nullptr;
}

}  // namespace damper::physical
