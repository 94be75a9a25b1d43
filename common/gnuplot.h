#pragma once
/// @file gnuplot.h
/// The one way the project draws its PNG figures: a gnuplot script written next to its data,
/// run by Debian's gnuplot (gnuplot-nox) as a child process (no shell).

#include <string>

namespace common {

/// `text` as a gnuplot single-quoted string literal ('' escapes a quote).
std::string gnuplot_quote(const std::string& text);

/// Runs `gnuplot script_path` in `working_dir` ("" = the current folder; a script that names
/// its data files relative to its own folder runs there), its output going to `log_path`
/// ("" = discarded; a relative log path is relative to the caller's current folder, the
/// script path to `working_dir`). Returns "" on success, else a message naming the script (and
/// the log) for the caller to print as a warning: a missing figure never fails a run.
std::string run_gnuplot(const std::string& script_path, const std::string& working_dir = "",
                        const std::string& log_path = "");

}  // namespace common
