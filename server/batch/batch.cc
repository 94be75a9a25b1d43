// `hybridsim batch` and `hybridsim batch merge` (batch.h): the set, the lock, the share of
// each MPI rank or Slurm task, the driver, the gather and the report.
#include "server/batch/batch.h"

#include "common/number_format.h"
#include "messages/lcm_bus.h"
#include "server/batch/batch_bench.h"
#include "server/batch/batch_files.h"
#include "server/batch/batch_report.h"
#include "server/batch/driver.h"

#include <chrono>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace server {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using nlohmann::json;
using namespace batch_internal;

namespace {

class LocalComm : public BatchComm {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  bool all(bool ok) override { return ok; }
  std::vector<std::string> gather(const std::string& text) override { return {text}; }
};

int run_batch(const BatchOptions& o, BatchComm& comm) {
  const auto t0 = Clock::now();
  BatchSet b;
  std::string setup_error;
  try {
    if (o.jobs < 1) throw BatchInputError("--jobs must be at least 1");
    if (o.out.empty()) throw BatchInputError("--out is required (the batch folder)");
    if (o.mpi && o.shared_netns) throw BatchInputError("--shared-netns cannot be used with --mpi");
    b = prepare_set(o);
  } catch (const std::exception& e) {
    setup_error = e.what();
  }
  if (!comm.all(setup_error.empty())) {
    if (comm.rank() == 0) std::cerr << "hybridsim batch: " << (setup_error.empty() ? "another rank failed to start" : setup_error) << "\n";
    return 2;
  }

  std::unique_ptr<DirLock> lock;
  try {
    fs::create_directories(runs_dir(o.out));
    if (!o.mpi && !o.slurm_task) lock = std::make_unique<DirLock>(o.out);
    // Finished runs must be of this set (same record, scale, duration) before anything is
    // written: resuming must not mix two different batches.
    for (const BatchRecord& r : b.records) check_finished_matches(o.out, r, b.duration_s);
    if (comm.rank() == 0) {
      std::ostringstream m;
      m << std::setw(2) << manifest_json(b) << "\n";
      write_file_atomic(fs::path(o.out) / "batch.json", m.str());
    }
    if (o.shared_netns && !messages::in_private_network_namespace()) messages::enter_private_network_namespace();
  } catch (const std::exception& e) {
    setup_error = e.what();
  }
  if (!comm.all(setup_error.empty())) {
    if (!setup_error.empty()) std::cerr << "hybridsim batch: " << setup_error << "\n";
    return 2;
  }

  // Which records this process runs.
  std::vector<std::size_t> mine;
  if (o.slurm_task) {
    const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
    char* end = nullptr;
    const long task = id ? std::strtol(id, &end, 10) : -1;
    if (!id || *end != '\0' || task < 0) {
      std::cerr << "hybridsim batch: --slurm-task needs SLURM_ARRAY_TASK_ID (0-based record index; "
                   "submit with sbatch --array=0-" << b.records.size() - 1 << ")\n";
      return 2;
    }
    if (static_cast<std::size_t>(task) >= b.records.size()) {
      std::cout << "slurm task " << task << ": the set has " << b.records.size() << " records, nothing to do\n";
      print_final_line(Counts{}, std::chrono::duration<double>(Clock::now() - t0).count());
      return 0;
    }
    mine.push_back(static_cast<std::size_t>(task));
  } else {
    for (std::size_t i = static_cast<std::size_t>(comm.rank()); i < b.records.size(); i += comm.size()) mine.push_back(i);
  }

  const std::string prefix = comm.size() > 1 ? "rank " + std::to_string(comm.rank()) + ": " : "";
  bool interrupted = false;
  if (!o.mpi) install_interrupt_handlers();
  try {
    interrupted = run_records(o, b, mine, prefix).interrupted;
  } catch (const std::exception& e) {
    setup_error = e.what();
    std::cerr << "hybridsim batch: " << prefix << setup_error << "\n";
  }
  // Every rank reaches the gather, even after an error, so that no rank waits forever.
  const std::vector<std::string> payloads = comm.gather(results_payload(o.out, b, mine));
  const bool all_ran = comm.all(setup_error.empty());
  if (comm.rank() != 0) return all_ran ? 0 : 2;

  std::vector<RunResult> results(b.records.size());
  std::vector<bool> have(b.records.size(), false);
  for (const std::string& p : payloads) {
    for (const json& r : json::parse(p)) {
      const std::size_t i = r.at("index").get<std::size_t>();
      results[i].state = r.at("state").get<std::string>();
      results[i].finished = r.at("finished").get<bool>();
      results[i].summary = r.at("summary");
      have[i] = true;
    }
  }
  // Records other processes ran (Slurm tasks, earlier batches): read from disk.
  for (std::size_t i = 0; i < b.records.size(); ++i)
    if (!have[i]) results[i] = read_result(o.out, b.records[i].label);

  Counts c;
  if (o.slurm_task) {
    std::vector<RunResult> own;
    for (std::size_t i : mine) own.push_back(results[i]);
    c = count(own);
    if (!o.quiet) std::cout << "slurm task " << mine[0] << " (" << b.records[mine[0]].label
                            << ") done; build the summary with: hybridsim batch merge --out " << o.out << "\n";
  } else {
    write_outputs(o.out, b, results, o.quiet);
    c = count(results);
    if (c.not_run > 0) std::cout << "not run: " << c.not_run << " (run the batch again to finish them)\n";
  }
  if (interrupted) std::cout << "interrupted: run the same command again to resume\n";
  print_final_line(c, std::chrono::duration<double>(Clock::now() - t0).count());
  if (interrupted) return 130;
  if (!all_ran) return 2;
  return (c.failed == 0 && c.not_run == 0) ? 0 : 1;
}

}  // namespace

int batch_command(const BatchOptions& o) {
  if (!o.laws.empty() && !o.list && !o.bench) return batch_laws_command(o);
  if (o.list) {
    try {
      const std::vector<BatchRecord> set = load_record_set(o.records);
      for (std::size_t i = 0; i < set.size(); ++i)
        std::cout << i << " " << set[i].label << " " << common::format_shortest(set[i].scale) << " " << set[i].path << "\n";
      return 0;
    } catch (const std::exception& e) {
      std::cerr << "hybridsim batch: " << e.what() << "\n";
      return 2;
    }
  }
  if (o.bench) return batch_bench(o);
  if (o.mpi) {
    if (o.slurm_task) {
      std::cerr << "hybridsim batch: --mpi and --slurm-task exclude each other\n";
      return 2;
    }
    std::unique_ptr<BatchComm> comm;
    try {
      comm = make_mpi_comm();
    } catch (const std::exception& e) {
      std::cerr << "hybridsim batch: " << e.what() << "\n";
      return 2;
    }
    return run_batch(o, *comm);
  }
  LocalComm comm;
  return run_batch(o, comm);
}

int batch_merge_command(const std::string& out) {
  const auto t0 = Clock::now();
  BatchSet b;
  try {
    const fs::path m = fs::path(out) / "batch.json";
    if (!fs::exists(m)) throw BatchInputError(m.string() + " not found: is " + out + " a batch folder?");
    b = manifest_from_json(json::parse(read_file(m)));
  } catch (const std::exception& e) {
    std::cerr << "hybridsim batch merge: " << e.what() << "\n";
    return 2;
  }
  std::vector<RunResult> results;
  for (const BatchRecord& r : b.records) results.push_back(read_result(out, r.label));
  write_outputs(out, b, results, false);
  const Counts c = count(results);
  if (c.not_run > 0) std::cout << "not run yet: " << c.not_run << "\n";
  print_final_line(c, std::chrono::duration<double>(Clock::now() - t0).count());
  return (c.failed == 0 && c.not_run == 0) ? 0 : 1;
}

}  // namespace server
