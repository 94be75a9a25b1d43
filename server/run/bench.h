#pragma once
/// @file bench.h
/// `hybridsim bench`: figures, not pass/fail. Prints raw LCM round trips between two
/// processes (brfd-substructure --echo), hybrid step round trips over LCM (a real run of the
/// 3-story config), and in-process speed for the 3- and 10-story configs, ending with
///   lcm_rtt_p50_us=… lcm_rtt_p99_us=… step_rtt_p50_us=… step_rtt_p99_us=… inprocess_ten_story_x_realtime=…
///   … inprocess_ten_story_cpu_x_realtime=… ten_story_hdf5_cpu_x_realtime=…
/// In-process figures on wall time and on CPU time (RunSummary::loop_cpu_s, cpu_s): on a
/// shared machine the CPU-time figures are the run's own cost.

#include <string>

namespace server {

struct BenchOptions {
  std::string three_story_config = "configs/three-story.yaml";
  std::string ten_story_config = "configs/ten-story.yaml";
  int round_trips = 5000;
};

int bench_command(const BenchOptions& options);

}  // namespace server
