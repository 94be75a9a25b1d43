#pragma once
/// @file batch_report.h
/// What a batch reports: OUT/summary.csv (one row per record), the gnuplot figures
/// (drift envelope, drift vs PGA) and the final line `records=… ok=… failed=… seconds=…`.

#include "server/batch/batch_set.h"

#include <string>
#include <vector>

namespace server::batch_internal {

struct Counts {
  int records = 0, ok = 0, failed = 0, not_run = 0;
};

/// `s` as one CSV field (RFC 4180): quoted when it holds a comma, quote or line break, inner
/// quotes doubled, line breaks turned into spaces (one record per line).
std::string csv_field(const std::string& s);

Counts count(const std::vector<RunResult>& results);

/// summary.csv: one row per record of the set, in set order.
std::string summary_csv(const BatchSet& b, const std::vector<RunResult>& results);

/// Gnuplot plots of the ok runs: drift envelope (peak drift vs story, every record, mean and
/// max) and peak drift vs PGA (one series per story). Returns "" or a warning.
std::string make_plots(const std::string& out, const BatchSet& b, const std::vector<RunResult>& results);

/// Writes summary.csv and the plots; prints where they are.
void write_outputs(const std::string& out, const BatchSet& b, const std::vector<RunResult>& results, bool quiet);

/// `records=<n> ok=<n> failed=<n> seconds=<wall>`
void print_final_line(const Counts& c, double seconds);

}  // namespace server::batch_internal
