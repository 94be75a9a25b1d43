#include "server/run/time_history_sink.h"

#include <charconv>
#include <cstdio>
#include <stdexcept>

namespace server {

namespace {

/// CSV text: std::to_chars shortest round-trip form, so the file reproduces the doubles bit
/// for bit.
class CsvTimeHistory : public TimeHistorySink {
 public:
  CsvTimeHistory(const std::string& path, const std::vector<std::string>& columns)
      : path_(path), columns_(columns.size()) {
    file_ = std::fopen(path.c_str(), "w");
    if (!file_) throw std::runtime_error("cannot write " + path);
    for (std::size_t i = 0; i < columns.size(); ++i) {
      std::fputs(columns[i].c_str(), file_);
      std::fputc(i + 1 < columns.size() ? ',' : '\n', file_);
    }
    if (std::fflush(file_) != 0) throw std::runtime_error("write failed on " + path);
  }
  ~CsvTimeHistory() override {
    if (file_) std::fclose(file_);
  }

  void write_rows(const double* values, std::size_t rows) override {
    const std::size_t n = rows * columns_;
    text_.resize(n * 32 + rows + 1);
    char* out = text_.data();
    char* const end = text_.data() + text_.size();
    for (std::size_t i = 0; i < n; ++i) {
      out = std::to_chars(out, end, values[i]).ptr;
      *out++ = (i + 1) % columns_ == 0 ? '\n' : ',';
    }
    const std::size_t bytes = static_cast<std::size_t>(out - text_.data());
    if (std::fwrite(text_.data(), 1, bytes, file_) != bytes || std::fflush(file_) != 0)
      throw std::runtime_error("write failed on " + path_);
  }

  void close() override {
    if (!file_) return;
    const bool ok = std::fflush(file_) == 0;
    const bool closed = std::fclose(file_) == 0;
    file_ = nullptr;
    if (!ok || !closed) throw std::runtime_error("write failed on " + path_);
  }

 private:
  std::string path_;
  std::size_t columns_;
  std::FILE* file_ = nullptr;
  std::vector<char> text_;
};

}  // namespace

std::unique_ptr<TimeHistorySink> make_csv_time_history(const std::string& path,
                                                       const std::vector<std::string>& columns) {
  return std::make_unique<CsvTimeHistory>(path, columns);
}

}  // namespace server
