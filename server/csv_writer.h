#pragma once
/// @file csv_writer.h
/// Fast CSV rows of doubles for the step loop: formats with std::to_chars into a buffer
/// and writes it out in blocks (no stream formatting, no allocation per row). flush()
/// pushes everything to the OS, so a failing run keeps every row written so far.

#include <cstdio>
#include <string>
#include <vector>

namespace server {

class CsvWriter {
 public:
  /// Opens (truncates) `path` and writes the header line; throws std::runtime_error naming it.
  CsvWriter(const std::string& path, const std::vector<std::string>& columns);
  ~CsvWriter();
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  void add(double value);  ///< next value of the current row
  void end_row();          ///< terminates the row (flushes the block when it is full)
  void flush();            ///< writes the buffer to the file and fflush()es it

 private:
  std::FILE* file_ = nullptr;
  std::string path_;
  std::vector<char> buffer_;
  std::size_t used_ = 0;
  bool row_started_ = false;
};

}  // namespace server
