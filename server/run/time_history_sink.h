#pragma once
/// @file time_history_sink.h
/// Where the time-history rows go: a file format behind one interface, fed block by block by
/// the writer thread of TimeHistoryWriter (time_history_writer.h). Implementations: CSV
/// (shortest round-trip text, std::to_chars) and HDF5 (hdf5_time_history.h).

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace server {

class TimeHistorySink {
 public:
  virtual ~TimeHistorySink() = default;
  /// Appends `rows` rows, row-major. Throws std::runtime_error (naming the file) on failure.
  virtual void write_rows(const double* values, std::size_t rows) = 0;
  /// Flushes and closes; idempotent. Throws on failure.
  virtual void close() = 0;
};

/// CSV: header line of column names, then one line per row, values as the shortest text that
/// reads back to the same double. Opens (truncates) `path`; throws naming it.
std::unique_ptr<TimeHistorySink> make_csv_time_history(const std::string& path,
                                                       const std::vector<std::string>& columns);

}  // namespace server
