#include "server/run/hdf5_time_history.h"

#include <hdf5.h>

#include <algorithm>
#include <stdexcept>

namespace server {

namespace {

constexpr hsize_t kChunkRows = 8192;

/// Writes a fixed-length, null-terminated UTF-8 string attribute on `obj`.
bool write_string_attribute(hid_t obj, const std::string& name, const std::string& value) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  if (type < 0) return false;
  H5Tset_size(type, value.size() + 1);  // room for the terminating null
  H5Tset_strpad(type, H5T_STR_NULLTERM);
  H5Tset_cset(type, H5T_CSET_UTF8);
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attr = H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
  bool ok = attr >= 0 && H5Awrite(attr, type, value.empty() ? "" : value.data()) >= 0;
  if (attr >= 0) ok = H5Aclose(attr) >= 0 && ok;
  H5Sclose(space);
  H5Tclose(type);
  return ok;
}

/// Writes a scalar float64 attribute on `obj`.
bool write_number_attribute(hid_t obj, const std::string& name, double value) {
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attr = H5Acreate2(obj, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT);
  bool ok = attr >= 0 && H5Awrite(attr, H5T_NATIVE_DOUBLE, &value) >= 0;
  if (attr >= 0) ok = H5Aclose(attr) >= 0 && ok;
  H5Sclose(space);
  return ok;
}

}  // namespace

Hdf5TimeHistory::Hdf5TimeHistory(const std::string& path, const std::vector<std::string>& columns,
                                 const std::vector<std::string>& units,
                                 const std::vector<std::pair<std::string, std::string>>& attributes,
                                 const std::vector<std::pair<std::string, double>>& numbers, long expected_rows)
    : path_(path) {
  if (units.size() != columns.size()) throw std::invalid_argument("HDF5 time history: one unit per column");
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors become exceptions naming the file
  file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file_ < 0) throw std::runtime_error("cannot create HDF5 file " + path);
  std::string names;
  for (const std::string& c : columns) names += (names.empty() ? "" : ",") + c;
  bool ok = write_string_attribute(file_, "columns", names);
  for (const auto& [key, value] : attributes) ok = ok && write_string_attribute(file_, key, value);
  for (const auto& [key, value] : numbers) ok = ok && write_number_attribute(file_, key, value);
  const hid_t group = H5Gcreate2(file_, "time_history", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  ok = ok && group >= 0;
  const hsize_t chunk = std::clamp<hsize_t>(static_cast<hsize_t>(std::max(1L, expected_rows)), 64, kChunkRows);
  chunk_rows_ = chunk;
  buffer_.assign(static_cast<std::size_t>(chunk) * columns.size(), 0.0);  // one chunk per column, before the run
  const hsize_t dims0 = 0, maxdims = H5S_UNLIMITED;
  for (std::size_t i = 0; ok && i < columns.size(); ++i) {
    const hid_t space = H5Screate_simple(1, &dims0, &maxdims);
    const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, 1, &chunk);
    // Every row up to the extent is written: no fill values to write first (callgrind: the
    // chunk fill was a quarter of the writer thread's instructions).
    H5Pset_fill_time(dcpl, H5D_FILL_TIME_NEVER);
    const hid_t ds = H5Dcreate2(group, columns[i].c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    H5Pclose(dcpl);
    H5Sclose(space);
    if (ds < 0) {
      ok = false;
      break;
    }
    datasets_.push_back(ds);
    ok = write_string_attribute(ds, "units", units[i]);
  }
  if (group >= 0) H5Gclose(group);
  if (!ok) {
    close();
    throw std::runtime_error("cannot create the datasets of HDF5 file " + path);
  }
  if (H5Fflush(file_, H5F_SCOPE_LOCAL) < 0) throw std::runtime_error("cannot write HDF5 file " + path);
}

Hdf5TimeHistory::~Hdf5TimeHistory() {
  try {
    close();
  } catch (...) {
  }
}

void Hdf5TimeHistory::write_rows(const double* values, std::size_t rows) {
  if (file_ < 0) throw std::runtime_error("HDF5 file " + path_ + " is closed");
  // Rows are gathered column by column into one chunk's worth (chunk_rows_ rows per column)
  // and each column is written once per chunk: one H5Dwrite of a whole, aligned chunk per
  // column instead of one per 1024-row block, and the file flushed when the chunk is
  // complete (flushing every block rewrote the same partly filled 64 KB chunks up to 8 times:
  // 10-story, about 48 MB through the page cache for a 7.6 MB file). close() writes the rest,
  // also for a run that fails.
  const std::size_t ncol = datasets_.size();
  while (rows > 0) {
    const std::size_t take = std::min<std::size_t>(rows, chunk_rows_ - buffered_);
    for (std::size_t c = 0; c < ncol; ++c) {
      double* column = buffer_.data() + c * chunk_rows_ + buffered_;
      for (std::size_t r = 0; r < take; ++r) column[r] = values[r * ncol + c];
    }
    buffered_ += take;
    values += take * ncol;
    rows -= take;
    if (buffered_ == chunk_rows_) write_buffer(true);
  }
}

void Hdf5TimeHistory::write_buffer(bool flush) {
  if (buffered_ == 0) return;
  const std::size_t ncol = datasets_.size();
  const hsize_t start = rows_, count = buffered_, new_size = rows_ + buffered_;
  const hid_t memspace = H5Screate_simple(1, &count, nullptr);
  bool ok = memspace >= 0;
  for (std::size_t c = 0; ok && c < ncol; ++c) {
    ok = H5Dset_extent(datasets_[c], &new_size) >= 0;
    const hid_t filespace = ok ? H5Dget_space(datasets_[c]) : -1;
    ok = ok && filespace >= 0 && H5Sselect_hyperslab(filespace, H5S_SELECT_SET, &start, nullptr, &count, nullptr) >= 0 &&
         H5Dwrite(datasets_[c], H5T_NATIVE_DOUBLE, memspace, filespace, H5P_DEFAULT,
                  buffer_.data() + c * chunk_rows_) >= 0;
    if (filespace >= 0) H5Sclose(filespace);
  }
  if (memspace >= 0) H5Sclose(memspace);
  if (ok && flush) ok = H5Fflush(file_, H5F_SCOPE_LOCAL) >= 0;
  if (!ok) throw std::runtime_error("write failed on " + path_);
  rows_ = new_size;
  buffered_ = 0;
}

void Hdf5TimeHistory::close() {
  if (file_ < 0) return;
  bool ok = true;
  std::string error;
  try {
    write_buffer(false);
  } catch (const std::exception& e) {
    ok = false;
    error = e.what();
  }
  for (hid_t ds : datasets_) ok = H5Dclose(ds) >= 0 && ok;
  datasets_.clear();
  ok = H5Fclose(file_) >= 0 && ok;
  file_ = -1;
  if (!ok) throw std::runtime_error(error.empty() ? "cannot close HDF5 file " + path_ : error);
}

}  // namespace server
