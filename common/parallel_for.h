#pragma once
/// @file parallel_for.h
/// Independent tasks on a few threads (the candidate fits of `hybridsim diagnose`).

#include <cstddef>
#include <functional>

namespace common {

/// Runs task(i) for every i in [0, n) on up to `threads` threads (0: the machine's hardware
/// threads), the tasks taken in order of i. Each task must write only its own result slot: the
/// results then do not depend on the thread count. The first exception a task throws is rethrown
/// here after every thread has finished.
void parallel_for(std::size_t n, int threads, const std::function<void(std::size_t)>& task);

}  // namespace common
