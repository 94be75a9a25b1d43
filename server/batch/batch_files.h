#pragma once
/// @file batch_files.h
/// File helpers of the batch driver and its workers: whole-file reads, durable writes
/// (temp file + fsync + rename), fsync of a path, UTC time stamps, this executable's path
/// and the tail of a log.

#include <filesystem>
#include <string>

namespace server::batch_internal {

/// The whole file as text ("" if it cannot be read).
std::string read_file(const std::filesystem::path& p);
/// Writes `text` to `path` atomically (temp file in the same folder, fsync, rename).
/// Throws std::runtime_error naming the file.
void write_file_atomic(const std::filesystem::path& path, const std::string& text);
/// fsync()s a file or folder by path (errors ignored).
void fsync_path(const std::filesystem::path& p);
/// Now, as 2026-11-23T13:37:00Z.
std::string utc_now();
/// Path of the running executable (/proc/self/exe).
std::string self_exe();
/// The last `n` non-empty lines of a text file, joined with " | ".
std::string last_lines(const std::filesystem::path& p, int n);

}  // namespace server::batch_internal
