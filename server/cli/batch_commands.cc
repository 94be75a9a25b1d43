#include "server/cli/batch_commands.h"

#include "server/batch/batch.h"

#include <iostream>
#include <memory>

namespace {

void finish(int code) {
  std::cout << std::flush;
  if (code != 0) throw CLI::RuntimeError(code);
}

}  // namespace

void add_batch_commands(CLI::App& app) {
  auto o = std::make_shared<server::BatchOptions>();
  CLI::App* batch = app.add_subcommand(
      "batch",
      "one hybrid run per ground-motion record, N at a time; resumable; summary.csv and plots.\n"
      "Ends with: records=<n> ok=<n> failed=<n> seconds=<wall>. Exit 0 all ok, 1 some failed, 2 bad input.");
  batch->require_subcommand(0, 1);
  batch->add_option("--config", o->config, "run config (e.g. configs/three-story.yaml); its record block is replaced");
  batch->add_option("--records", o->records,
                    "record list file (lines 'path scale [label]', # comments, paths relative to the file) "
                    "or a folder (every *.AT2, *.at2, *.txt, *.csv in it, scale 1)");
  batch->add_option("--out", o->out, "batch folder (runs/, summary.csv, plots); run again to resume");
  batch->add_option("--jobs", o->jobs, "runs at a time (per MPI rank), at least 1");
  batch->add_option("--duration", o->duration_s,
                    "simulated seconds per run, overriding record.duration_s of the config (-1: whole records)");
  batch->add_option("--transport", o->transport,
                    "override transport.kind of the config: in_process (the damper model inside each worker, "
                    "no LCM: the batch throughput mode) or lcm")
      ->check(CLI::IsMember({"in_process", "lcm"}));
  batch->add_option("--laws", o->laws,
                    "comma-separated control laws (passive_off,passive_on,lyapunov,clipped_optimal,"
                    "modulated_homogeneous): the set once per law, a law x record table and plots");
  batch->add_flag("--mpi", o->mpi, "divide the records among MPI ranks (mpirun -np N hybridsim batch --mpi ...)");
  batch->add_flag("--slurm-task", o->slurm_task,
                  "run only record SLURM_ARRAY_TASK_ID (0-based) of the set; then 'hybridsim batch merge --out DIR'");
  batch->add_flag("--bench", o->bench, "time the set with 1 and 2 jobs (in OUT/bench/), print records/s and efficiency");
  batch->add_option("--bench-repeat", o->bench_repeat, "alternating passes of --bench (best and median reported)");
  batch->add_flag("--list", o->list, "print the record set (index label scale path) and exit");
  batch->add_flag("--retry-failed", o->retry_failed,
                  "redo finished failed runs (the old folder is kept as runs/<label>.failed-<n>)");
  batch->add_flag("--quiet", o->quiet, "no progress output (the final line is still printed)");
  batch->add_flag("--shared-netns", o->shared_netns,
                  "test aid: all runs in one private network namespace instead of one each")
      ->group("Testing");
  batch->add_flag("--same-channel-prefix", o->same_channel_prefix,
                  "test aid: all runs on the config's channel prefix (only the run id separates them)")
      ->group("Testing");

  auto merge_out = std::make_shared<std::string>();
  CLI::App* merge = batch->add_subcommand("merge", "build summary.csv and plots of a batch folder (after Slurm array tasks)");
  merge->add_option("--out", *merge_out, "batch folder")->required();
  merge->callback([merge_out] { finish(server::batch_merge_command(*merge_out)); });

  auto w = std::make_shared<server::BatchWorkerOptions>();
  CLI::App* worker = batch->add_subcommand("worker", "one run of a batch (started by the batch driver)");
  worker->group("");  // internal: hidden from --help
  worker->add_option("--config", w->config)->required();
  worker->add_option("--record", w->record)->required();
  worker->add_option("--scale", w->scale)->required();
  worker->add_option("--label", w->label)->required();
  worker->add_option("--runs-dir", w->runs_dir)->required();
  worker->add_option("--channel-prefix", w->channel_prefix);
  worker->add_option("--index", w->index);
  worker->add_option("--duration", w->duration_s);
  worker->add_flag("--shared-netns", w->shared_netns);
  worker->add_option("--transport", w->transport);
  worker->callback([w] { finish(server::batch_worker_command(*w)); });

  batch->callback([o, batch, merge, worker] {
    if (merge->parsed() || worker->parsed()) return;
    (void)batch;
    finish(server::batch_command(*o));
  });
}
