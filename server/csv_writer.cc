#include "server/csv_writer.h"

#include <charconv>
#include <stdexcept>

namespace server {

namespace {
constexpr std::size_t kBlockBytes = 1 << 16;
constexpr std::size_t kMaxValueChars = 32;
}  // namespace

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& columns)
    : path_(path), buffer_(kBlockBytes + 4096) {
  file_ = std::fopen(path.c_str(), "w");
  if (!file_) throw std::runtime_error("cannot write " + path);
  for (std::size_t i = 0; i < columns.size(); ++i) {
    std::fputs(columns[i].c_str(), file_);
    std::fputc(i + 1 < columns.size() ? ',' : '\n', file_);
  }
}

CsvWriter::~CsvWriter() {
  if (file_) {
    flush();
    std::fclose(file_);
  }
}

void CsvWriter::add(double value) {
  if (used_ + kMaxValueChars + 2 > buffer_.size()) buffer_.resize(buffer_.size() * 2);
  if (row_started_) buffer_[used_++] = ',';
  // Shortest representation that round-trips exactly: results are reproducible bit for bit.
  const auto r = std::to_chars(buffer_.data() + used_, buffer_.data() + buffer_.size(), value);
  used_ = static_cast<std::size_t>(r.ptr - buffer_.data());
  row_started_ = true;
}

void CsvWriter::end_row() {
  buffer_[used_++] = '\n';
  row_started_ = false;
  if (used_ >= kBlockBytes) flush();
}

void CsvWriter::flush() {
  if (used_ > 0) {
    if (std::fwrite(buffer_.data(), 1, used_, file_) != used_) {
      throw std::runtime_error("write failed on " + path_);
    }
    used_ = 0;
  }
  std::fflush(file_);
}

}  // namespace server
