#pragma once
/// @file batch.h
/// `hybridsim batch`: one hybrid run per ground-motion record, N at a time, resumable, with a
/// summary table and plots. Also runs across MPI ranks and Slurm array tasks.
///
/// Layout of a batch folder OUT:
///   OUT/batch.json                the record set (manifest; `batch merge` reads it)
///   OUT/runs/<label>.partial/     a run in progress (or interrupted: redone on resume)
///   OUT/runs/<label>/             a finished run: summary.json (status ok or failed),
///                                 time_history.csv, effective-config.yaml, run.lcmlog,
///                                 batch-run.json, worker.log, substructure.log
///   OUT/summary.csv               one row per record
///   OUT/drift-envelope.png, OUT/drift-vs-pga.png, OUT/plots/ (gnuplot data and script)
///
/// Each run is a separate process (`hybridsim batch worker`, started by the driver) that
/// enters its own private network namespace before it opens LCM and spawns its
/// brfd-substructure, and uses its own channel prefix and run id: parallel runs cannot hear
/// each other. A run writes into <label>.partial/ and renames it to <label>/ when done
/// (rename never replaces an existing result).

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace server {

/// One record of a batch.
struct BatchRecord {
  std::string path;        ///< absolute path of the record file
  std::string shown;       ///< as written in the list file (or the file name in folder mode)
  double scale = 1.0;      ///< multiplies the record's accelerations
  std::string label;       ///< unique name of the run: OUT/runs/<label>/
  int line = 0;            ///< line of the list file (0 in folder mode)
  std::string config;      ///< run config of this record; "" = the batch's --config (IDA cases)
};

/// A record list file or folder that cannot be used (names the file and line).
class BatchInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Reads the record set: `spec` is a list file (one record per line: `path scale [label]`,
/// `#` comments, blank lines allowed, paths relative to the list file) or a folder (every
/// *.AT2/*.at2/*.txt/*.csv file in it, sorted by name, scale 1). Labels default to the file
/// name without extension, plus `_x<scale>` when the scale is not 1; they must be unique.
/// Throws BatchInputError. A record file that is missing or bad is NOT an error here: its run
/// fails with the reason.
std::vector<BatchRecord> load_record_set(const std::string& spec);

/// What `hybridsim batch` was asked to do.
struct BatchOptions {
  std::string config;            ///< run config (e.g. configs/three-story.yaml)
  std::string records;           ///< list file or folder
  std::string out;               ///< batch folder
  int jobs = 1;                  ///< runs at a time (per MPI rank)
  bool mpi = false;              ///< divide the records among MPI ranks, gather on rank 0
  bool slurm_task = false;       ///< run the record SLURM_ARRAY_TASK_ID only (merge later)
  bool bench = false;            ///< time the set with 1 and 2 jobs, print records/s
  int bench_repeat = 3;          ///< alternating passes of the benchmark
  bool list = false;             ///< print the record set and exit
  bool retry_failed = false;     ///< redo finished failed runs (the old folder is kept aside)
  bool shared_netns = false;     ///< test aid: all runs in ONE private namespace
  bool same_channel_prefix = false;  ///< test aid: all runs on the config's channel prefix
  bool quiet = false;            ///< no progress output (the final line is still printed)
  double duration_s = 0.0;       ///< overrides record.duration_s of the config (< 0: whole
                                 ///< records); 0 keeps the config's value
  /// Overrides transport.kind of every run: "in_process" calls the damper model inside the
  /// worker (the same model code as brfd-substructure, no LCM, no network namespace), "lcm"
  /// forces the two-process run; "" keeps the config's.
  std::string transport;
  /// Comma-separated control laws (control/controller.h): the set is run once per law in
  /// OUT/<law>/ and OUT/laws-summary.csv + OUT/criteria-J*.png + OUT/drift-envelope-<record>.png
  /// compare them (batch_laws.cc). Empty: one ordinary batch.
  std::string laws;
};

/// `hybridsim batch ...`. Returns the exit code: 0 all records ok, 1 some failed or not run,
/// 2 bad input (config, list file, options). Ends with the line
/// `records=<n> ok=<n> failed=<n> seconds=<wall>`.
int batch_command(const BatchOptions& options);
/// `hybridsim batch --laws a,b,c ...` (called by batch_command when options.laws is set).
int batch_laws_command(const BatchOptions& options);

/// `hybridsim batch merge --out DIR`: summary.csv and plots from the finished runs of the
/// set in DIR/batch.json (after Slurm array tasks). Same exit codes and final line.
int batch_merge_command(const std::string& out_dir);

/// What the driver hands one worker process.
struct BatchWorkerOptions {
  std::string config;        ///< run config (absolute)
  std::string record;        ///< record file (absolute)
  double scale = 1.0;
  double duration_s = 0.0;   ///< overrides record.duration_s (0: the config's)
  std::string label;
  std::string runs_dir;      ///< OUT/runs: writes <label>.partial/, renames to <label>/
  std::string channel_prefix;
  int index = 0;
  bool shared_netns = false; ///< do not create a network namespace (the caller is in one)
  std::string transport;     ///< overrides transport.kind ("" keeps the config's)
};

/// Worker exit codes.
enum BatchWorkerExit { kWorkerOk = 0, kWorkerRunFailed = 1, kWorkerInfraFailed = 3 };

/// `hybridsim batch worker ...` (internal): one run. Enters a private network namespace
/// (unless shared_netns or the transport is in_process), runs like `hybridsim run`, writes summary.json, renames
/// <label>.partial/ to <label>/. A record that cannot be read is a failed run (exit 1). A
/// failure of the machinery (no namespace, cannot spawn) leaves the .partial folder with a
/// failed summary.json and exits 3: the run is redone on resume.
int batch_worker_command(const BatchWorkerOptions& options);

/// Collective operations of a batch spread over processes (MPI ranks); the local
/// implementation is one rank.
class BatchComm {
 public:
  virtual ~BatchComm() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  /// True on every rank iff `ok` is true on every rank.
  virtual bool all(bool ok) = 0;
  /// Gathers one string per rank on rank 0 (other ranks get an empty vector).
  virtual std::vector<std::string> gather(const std::string& text) = 0;
};

/// MPI_Init on construction, MPI_Finalize on destruction. Throws std::runtime_error if
/// hybridsim was built without MPI.
std::unique_ptr<BatchComm> make_mpi_comm();
/// True if hybridsim was built with MPI.
bool batch_has_mpi();

}  // namespace server
