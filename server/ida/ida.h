#pragma once
/// @file ida.h
/// `hybridsim ida --config IDA.yaml --records LIST --out DIR`: incremental dynamic analysis
/// (Vamvatsikos & Cornell 2002) of every case of the IDA config (damper configs or control
/// laws side by side) over a record set, on the batch engine (server/batch: worker processes
/// N at a time, resume, MPI ranks, Slurm array tasks).
///
/// Each record is scaled to a ladder of intensity measures (IM: Sa(T1, ζ) of the record at
/// the case's first-mode period, structure/response_spectrum.h, or PGA) chosen by
/// hunt-and-fill (hunt_fill.h); each run's damage measure is its peak interstory drift ratio
/// (max over stories of peak drift / story height). Results in DIR:
///   ida.json               the set: cases (T1), records, IM of each record at scale 1
///   effective-ida.yaml     every value of the IDA config used
///   runs/<case>.<record>.im<IM>/   one batch run each (summary.json, time history, ...)
///   ida_runs.csv           case, record, IM, scale, drift ratio, collapse, status
///   ida_fractiles.csv      case, IM, 16/50/84 % drift ratio across records
///   capacities.csv         case, drift limit, record, capacity IM (or censored)
///   fragility.csv          case, drift limit, median, beta, 95 % bounds, method
///   ida-curves.png, fragility.png (gnuplot), plots/ (data and script)
/// Resume: the same command again runs only what is not finished (the next IMs are a pure
/// function of the finished runs). Ends with the line
/// `cases=<n> records=<n> runs=<n> failed=<n> seconds=<wall>`.

#include <string>

namespace server::ida {

struct IdaOptions {
  std::string config;        ///< IDA config (configs/ida-three-story.yaml)
  std::string records;       ///< record list file (scales must be 1) or folder
  std::string out;           ///< results folder
  int jobs = 1;              ///< runs at a time (per MPI rank)
  bool mpi = false;          ///< share each round's runs among MPI ranks (shared file system)
  bool slurm_task = false;   ///< trace only record SLURM_ARRAY_TASK_ID (all cases); then run
                             ///< the same command without it to build the results
  bool quiet = false;
};

/// Returns the exit code: 0 every run ok, 1 some runs failed or the set is not finished,
/// 2 bad input, 130 interrupted.
int ida_command(const IdaOptions& options);

}  // namespace server::ida
