#include "server/cli/ida_commands.h"

#include "server/ida/ida.h"

#include <iostream>
#include <memory>

void add_ida_commands(CLI::App& app) {
  auto o = std::make_shared<server::ida::IdaOptions>();
  CLI::App* ida = app.add_subcommand(
      "ida",
      "incremental dynamic analysis (hunt-and-fill, Vamvatsikos & Cornell 2002) of every case of an IDA config\n"
      "over a record set, on the batch engine; IDA curves with 16/50/84 % fractiles and lognormal fragility\n"
      "curves (maximum likelihood) as CSV and PNG. Resumable: run the same command again.\n"
      "Ends with: cases=<n> records=<n> runs=<n> failed=<n> seconds=<wall>. Exit 0 ok, 1 runs failed, 2 bad input.");
  ida->add_option("--config", o->config, "IDA config (e.g. configs/ida-three-story.yaml): IM, drift limits, cases")
      ->required();
  ida->add_option("--records", o->records, "record list file (lines 'path 1 [label]') or a folder of records")
      ->required();
  ida->add_option("--out", o->out, "IDA folder (runs/, CSV, plots); run again to resume")->required();
  ida->add_option("--jobs", o->jobs, "runs at a time (per MPI rank), at least 1");
  ida->add_flag("--mpi", o->mpi, "share each round's runs among MPI ranks (mpirun -np N hybridsim ida --mpi ...)");
  ida->add_flag("--slurm-task", o->slurm_task,
                "trace only record SLURM_ARRAY_TASK_ID (0-based); then run the same command without it");
  ida->add_flag("--quiet", o->quiet, "no progress output (the fragility lines and the final line are printed)");
  ida->callback([o] {
    const int code = server::ida::ida_command(*o);
    std::cout << std::flush;
    if (code != 0) throw CLI::RuntimeError(code);
  });
}
