#pragma once
/// @file resource_limits.h
/// What the machine can hold, asked before a run starts so that an impossible config is an
/// input error (exit 2 naming the key) rather than an out-of-memory kill or a full disk hours
/// later. Memory: MemAvailable of /proc/meminfo; disk: statvfs(3) f_bavail × f_frsize.

#include <cstdint>
#include <string>

namespace common {

/// Bytes of memory available to a new allocation without swapping (MemAvailable), or the
/// physical memory if /proc/meminfo cannot be read.
std::uint64_t available_memory_bytes();

/// Bytes free for an unprivileged writer on the file system holding `path` (the nearest
/// existing ancestor if `path` does not exist yet); UINT64_MAX if it cannot be asked.
std::uint64_t free_disk_bytes(const std::string& path);

/// "1.5 GB"-style text of a byte count, for messages.
std::string format_bytes(double bytes);

}  // namespace common
