#pragma once
/// @file hdf5_time_history.h
/// The time history as HDF5 (`output.format: hdf5`), through Debian's libhdf5 C API: one
/// column per dataset, so readers take the columns they need without parsing text.
///
/// Layout of time_history.h5:
///   /                          attributes: run (name), record, units_system ("kip, in, s;
///                              accelerations in g"), columns (the column names in order,
///                              comma separated), effective_config_yaml (the full effective
///                              config), producer (strings); dt_s, record_scale,
///                              output_every_n_steps (float64)
///   /time_history/<column>     1-D float64 (IEEE little endian), chunked, extendible; one
///                              value per written row; attribute `units` (s, g, in, kip)
/// Column names are those of time_history.csv (time_s, ground_accel_g, floor1_disp_in, ...).
/// The values are the very doubles of the run (no conversion): identical bit for bit to the
/// CSV, whose shortest round-trip text reads back to the same doubles.
///
/// Reading: h5py `f["time_history/time_s"][:]`; pandas
/// `pd.DataFrame({k: v[:] for k, v in h5py.File(p)["time_history"].items()})`; MATLAB
/// `h5read(p, "/time_history/time_s")`; `h5dump -d /time_history/time_s p` (hdf5-tools).
/// Rows are flushed to the file (H5Fflush) with every completed chunk (8192 rows: 8 s at
/// 1024 Hz) and at close, so a run that fails keeps every row it computed (close writes them);
/// a process killed mid-write may leave the file unreadable: the CSV is the format for
/// crash-safe logging.

#include "server/run/time_history_sink.h"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace server {

class Hdf5TimeHistory : public TimeHistorySink {
 public:
  /// Creates (truncates) `path` with the datasets of `columns` (`units[i]` for column i), the
  /// string `attributes` and the float64 `numbers` on the root group. Throws
  /// std::runtime_error naming the file.
  Hdf5TimeHistory(const std::string& path, const std::vector<std::string>& columns,
                  const std::vector<std::string>& units,
                  const std::vector<std::pair<std::string, std::string>>& attributes,
                  const std::vector<std::pair<std::string, double>>& numbers, long expected_rows);
  ~Hdf5TimeHistory() override;
  /// Appends `rows` rows (row-major, columns.size() values per row). Throws on error.
  void write_rows(const double* values, std::size_t rows) override;
  /// Flushes and closes the file (idempotent).
  void close() override;

 private:
  std::string path_;
  std::int64_t file_ = -1;
  std::vector<std::int64_t> datasets_;
  /// Writes the buffered rows (each column's part of buffer_) and, if `flush`, H5Fflush.
  void write_buffer(bool flush);
  std::vector<double> buffer_;  // chunk_rows_ values per column, column after column
  std::size_t buffered_ = 0;    // rows in buffer_
  unsigned long long rows_ = 0; // rows in the file
  std::size_t chunk_rows_ = 1;  // rows per chunk: written and flushed when one is complete
};

}  // namespace server
