#pragma once
/// @file batch_bench.h
/// `hybridsim batch --bench`: the record set with 1 job and with max(2, --jobs) jobs,
/// alternated --bench-repeat times; prints every pass, records/s, speedup and scaling
/// efficiency.

#include "server/batch/batch.h"

namespace server::batch_internal {

/// Returns the exit code (0: every run ok, 1: some failed, 2: bad input).
int batch_bench(const BatchOptions& o);

}  // namespace server::batch_internal
