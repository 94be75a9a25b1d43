#include "server/batch/batch_files.h"

#include "common/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace server::batch_internal {

namespace fs = std::filesystem;

std::string read_file(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// One helper for every durable write of the project (common/atomic_file.h).
void write_file_atomic(const fs::path& path, const std::string& text) { common::write_file_atomic(path.string(), text); }

void fsync_path(const fs::path& p) { common::fsync_path(p.string()); }

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

std::string self_exe() { return fs::read_symlink("/proc/self/exe").string(); }

std::string last_lines(const fs::path& p, int n) {
  std::ifstream f(p);
  std::vector<std::string> lines;
  for (std::string l; std::getline(f, l);)
    if (!l.empty()) lines.push_back(l);
  std::string out;
  for (std::size_t i = lines.size() > static_cast<std::size_t>(n) ? lines.size() - n : 0; i < lines.size(); ++i)
    out += (out.empty() ? "" : " | ") + lines[i];
  return out;
}

}  // namespace server::batch_internal
