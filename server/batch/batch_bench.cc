#include "server/batch/batch_bench.h"

#include "common/number_format.h"
#include "server/batch/batch_report.h"
#include "server/batch/driver.h"
#include "server/run/run_config.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <map>
#include <thread>

namespace server::batch_internal {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

double children_cpu_s() {
  struct rusage ru {};
  getrusage(RUSAGE_CHILDREN, &ru);
  return ru.ru_utime.tv_sec + ru.ru_stime.tv_sec + 1e-6 * (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

/// --bench: the same set with 1 job and with max(2, --jobs) jobs, alternated --bench-repeat
/// times (a shared machine's load drifts: alternating and taking the best of each is fairer
/// than one run of each). Prints every pass, then records/s, speedup and efficiency.
int batch_bench(const BatchOptions& o) {
  BatchSet b;
  try {
    if (o.out.empty()) throw BatchInputError("--out is required (the benchmark writes OUT/bench/)");
    if (o.bench_repeat < 1) throw BatchInputError("--bench-repeat must be at least 1");
    b = prepare_set(o);
  } catch (const std::exception& e) {
    std::cerr << "hybridsim batch: " << e.what() << "\n";
    return 2;
  }
  const RunConfig config = load_run_config(o.config);
  // 1 and 2 jobs, then 4, 8, 16, ... up to --jobs (default: the machine's cores).
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int max_jobs = o.jobs > 1 ? o.jobs : std::max(2, cores);
  std::vector<int> jobs_list{1, 2};
  for (int j = 4; j <= max_jobs; j *= 2) jobs_list.push_back(j);
  if (max_jobs > 2 && jobs_list.back() != max_jobs) jobs_list.push_back(max_jobs);
  std::map<int, std::vector<double>> rates, cpu_per_record, cpu_x_realtime;
  std::cout << "bench: " << b.records.size() << " records, "
            << (b.duration_s > 0 ? common::format_fixed(b.duration_s, 1) + " s simulated each" : std::string("whole records"))
            << ", dt " << common::format_shortest(config.dt_s) << " s, " << std::thread::hardware_concurrency() << " cores, "
            << o.bench_repeat << " alternating pass(es), transport "
            << (o.transport.empty() ? config.transport.kind : o.transport) << std::endl;
  Counts last;
  double last_wall = 0.0;
  for (int pass = 1; pass <= o.bench_repeat; ++pass) {
    for (int jobs : jobs_list) {
      BatchOptions run = o;
      run.bench = false;
      run.jobs = jobs;
      run.quiet = true;
      run.out = (fs::path(o.out) / "bench" / ("jobs" + std::to_string(jobs))).string();
      fs::remove_all(run.out);  // benchmark scratch only
      fs::create_directories(runs_dir(run.out));
      std::vector<std::size_t> all(b.records.size());
      for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
      const double cpu0 = children_cpu_s();
      const auto t0 = Clock::now();
      run_records(run, b, all, "");
      const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
      const double cpu = children_cpu_s() - cpu0;
      std::vector<RunResult> results;
      double simulated_s = 0.0;  // from each run's summary.json
      for (const BatchRecord& r : b.records) {
        results.push_back(read_result(run.out, r.label));
        const nlohmann::json& j = results.back().summary;
        if (j.is_object() && j.contains("sim_time_s") && j["sim_time_s"].is_number()) simulated_s += j["sim_time_s"].get<double>();
      }
      last = count(results);
      last_wall = wall;
      const double rate = b.records.size() / wall;
      rates[jobs].push_back(rate);
      cpu_per_record[jobs].push_back(cpu / b.records.size());
      // CPU time (user + system of the workers and their substructures, getrusage) does not
      // count the time a run waits for a core that another process holds: on a shared
      // machine it is the steadier figure. x real time on CPU = simulated / CPU seconds.
      cpu_x_realtime[jobs].push_back(cpu > 0.0 ? simulated_s / cpu : 0.0);
      std::cout << "pass " << pass << " jobs=" << jobs << ": " << b.records.size() << " records in " << common::format_fixed(wall, 2)
                << " s = " << common::format_fixed(rate, 3) << " records/s (wall), " << common::format_fixed(simulated_s / wall, 0)
                << "x real time on wall; CPU " << common::format_fixed(cpu / b.records.size(), 3) << " s per record = "
                << common::format_fixed(cpu > 0.0 ? simulated_s / cpu : 0.0, 0) << "x real time on CPU ("
                << common::format_fixed(cpu / wall, 2) << " cores busy), ok " << last.ok << ", failed " << last.failed
                << std::endl;
    }
  }
  for (int jobs : jobs_list) {
    const auto& r = rates[jobs];
    const auto& c = cpu_per_record[jobs];
    std::cout << "jobs=" << jobs << ": " << common::format_fixed(*std::max_element(r.begin(), r.end()), 3) << " records/s best, "
              << common::format_fixed(median(r), 3) << " median (wall); CPU per record "
              << common::format_fixed(*std::min_element(c.begin(), c.end()), 3) << " s best, "
              << common::format_fixed(median(c), 3) << " s median; "
              << common::format_fixed(median(cpu_x_realtime[jobs]), 0) << "x real time on CPU (median)" << std::endl;
  }
  std::string summary = "bench_efficiency_pct";
  for (std::size_t k = 1; k < jobs_list.size(); ++k) {
    const int j2 = jobs_list[k];
    const double best = *std::max_element(rates[j2].begin(), rates[j2].end()) /
                        *std::max_element(rates[1].begin(), rates[1].end());
    const double med = median(rates[j2]) / median(rates[1]);
    std::cout << "speedup with " << j2 << " jobs: " << common::format_fixed(best, 2) << "x (best) / "
              << common::format_fixed(med, 2) << "x (median); scaling efficiency "
              << common::format_fixed(100.0 * best / j2, 1) << " % (best), " << common::format_fixed(100.0 * med / j2, 1)
              << " % (median)" << std::endl;
    summary += " jobs" + std::to_string(j2) + "=" + common::format_fixed(100.0 * best / j2, 1);
    // Work per record at j2 jobs against 1 job: the part of the scaling loss that parallel
    // runs cause themselves (contention for memory, disk, kernel), apart from the cores other
    // processes take (which wall time includes). 100 % = no extra work per record.
    const double cpu1 = median(cpu_per_record[1]), cpu2 = median(cpu_per_record[j2]);
    std::cout << "CPU per record with " << j2 << " jobs vs 1: " << common::format_fixed(cpu2, 3) << " s vs "
              << common::format_fixed(cpu1, 3) << " s (median): CPU-time efficiency "
              << common::format_fixed(cpu2 > 0.0 ? 100.0 * cpu1 / cpu2 : 0.0, 1) << " %" << std::endl;
  }
  std::cout << summary << std::endl;
  print_final_line(last, last_wall);
  return last.failed == 0 ? 0 : 1;
}

}  // namespace server::batch_internal
