#pragma once
/// @file atomic_file.h
/// Durable, all-or-nothing file writes for every file a later reader trusts (summary.json,
/// batch manifests, resume state): the text goes to a temporary name in the same folder, is
/// fsync()ed, renamed over the final name (rename(2) is atomic within a file system) and the
/// folder is fsync()ed. A reader sees the old file or the complete new one, never a 0-byte or
/// half-written file, also after a crash or on a full disk.

#include <stdexcept>
#include <string>

namespace common {

/// A file could not be written; the message names the file and the system error
/// (e.g. "No space left on device").
class FileWriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Writes `text` to `path` atomically and durably (see the file comment). On failure the
/// final name is untouched, the temporary file is removed, and FileWriteError is thrown.
void write_file_atomic(const std::string& path, const std::string& text);

/// fsync()s a file or folder by path; returns false (errno set) if it cannot be opened or synced.
bool fsync_path(const std::string& path);

/// Writes `text` to `path` (created or truncated) without fsync; throws FileWriteError naming
/// the file on any failed write or close. For files in a folder that becomes visible only by
/// a rename after sync_folder_files() (a batch run's `<label>.partial/`): one sync for all
/// of them at the end instead of one temporary file, fsync and folder fsync per file.
void write_file(const std::string& path, const std::string& text);

/// Makes every regular file of `folder` and the folder itself durable: starts the write-back
/// of all files at once (sync_file_range), then fsync()s each and the folder, so the journal
/// commits once or twice instead of once per file. Throws FileWriteError naming the file when
/// a sync fails (a full disk can first show at fsync with delayed allocation).
void sync_folder_files(const std::string& folder);

}  // namespace common
