#include "common/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

namespace common {

namespace {
std::string system_error_text(int err) { return std::strerror(err); }

// Writes all of `text` to fd (a write interrupted by a signal is repeated). Returns 0, or the
// errno of the failed write.
int write_all(int fd, const std::string& text) {
  const char* p = text.data();
  std::size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return 0;
}
}  // namespace

bool fsync_path(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  errno = err;
  return rc == 0;
}

void write_file(const std::string& path, const std::string& text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw FileWriteError("cannot write " + path + ": " + system_error_text(errno));
  if (const int err = write_all(fd, text)) {
    ::close(fd);
    throw FileWriteError("cannot write " + path + " (write): " + system_error_text(err));
  }
  if (::close(fd) != 0) throw FileWriteError("cannot write " + path + " (close): " + system_error_text(errno));
}

void sync_folder_files(const std::string& folder) {
  std::vector<std::pair<int, std::string>> files;
  auto close_all = [&] {
    for (const auto& f : files) ::close(f.first);
  };
  std::error_code ec;
  for (const std::filesystem::directory_entry& e : std::filesystem::directory_iterator(folder, ec)) {
    if (!e.is_regular_file(ec)) continue;
    const int fd = ::open(e.path().c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
      const int err = errno;
      close_all();
      throw FileWriteError("cannot sync " + e.path().string() + ": " + system_error_text(err));
    }
    files.emplace_back(fd, e.path().string());
    ::sync_file_range(fd, 0, 0, SYNC_FILE_RANGE_WRITE);  // start the write-back, do not wait
  }
  if (ec) {
    close_all();
    throw FileWriteError("cannot list " + folder + ": " + ec.message());
  }
  for (const auto& [fd, name] : files) {
    if (::fsync(fd) != 0) {
      const int err = errno;
      close_all();
      throw FileWriteError("cannot sync " + name + ": " + system_error_text(err));
    }
  }
  close_all();
  if (!fsync_path(folder)) throw FileWriteError("cannot sync folder " + folder + ": " + system_error_text(errno));
}

void write_file_atomic(const std::string& path, const std::string& text) {
  const std::filesystem::path final_path(path);
  const std::filesystem::path folder =
      final_path.has_parent_path() ? final_path.parent_path() : std::filesystem::path(".");
  // Unique per process and call: two writers of one name never share a temporary file.
  static std::atomic<int> counter{0};
  const std::string tmp = path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(++counter);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw FileWriteError("cannot write " + path + ": " + system_error_text(errno));
  auto fail = [&](const char* what) {
    const int err = errno;
    ::close(fd);
    ::unlink(tmp.c_str());
    throw FileWriteError("cannot write " + path + " (" + what + "): " + system_error_text(err));
  };
  if (const int err = write_all(fd, text)) {
    errno = err;
    fail("write");
  }
  if (::fsync(fd) != 0) fail("fsync");
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw FileWriteError("cannot write " + path + " (close): " + system_error_text(err));
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw FileWriteError("cannot write " + path + " (rename): " + system_error_text(err));
  }
  fsync_path(folder.string());  // the rename itself durable
}

}  // namespace common
