#pragma once
// Paths the tests use, set by CMake: the source tree, the build's bin folder, and
// ../shared beside the project (may be absent on a user's machine: tests that need it skip).
#include <filesystem>
#include <string>

namespace test_paths {
inline std::string source_dir() { return HYBRIDSIM_SOURCE_DIR; }
inline std::string bin_dir() { return HYBRIDSIM_BIN_DIR; }
inline std::string shared_dir() { return HYBRIDSIM_SOURCE_DIR "/../shared"; }
inline bool have_shared() { return std::filesystem::exists(shared_dir() + "/data/brfd"); }
}  // namespace test_paths
