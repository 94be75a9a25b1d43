// The step loop allocates nothing per step. This binary replaces the global operator new
// with one that counts calls (all threads, including the CSV writer's), then:
//  - BrfdModel::step and DamperBank::step over 10,000 steps: zero allocations;
//  - run_hybrid in-process (the real loop: CR, damper bank, energy ledger, CSV writer):
//    the allocation count of a 4 s run equals that of a 2 s run, i.e. every allocation is
//    set-up (per run), none is per step (2048 more steps, 0 more allocations).
#include "damper/model/brfd_model.h"
#include "damper/model/damper_model.h"
#include "in_process_run.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace {

TEST(Allocation, DamperModelAndBankStepAllocateNothing) {
  const damper::BrfdParams p = damper::BrfdParams{};
  damper::BrfdModel model(p);
  damper::DamperBank bank(model, 3);
  Eigen::VectorXd d(3), v(3), f(3);
  const long before = g_allocations.load();
  for (int i = 0; i < 10000; ++i) {
    const double t = i / 1024.0;
    damper::DamperInput in{std::sin(3.1 * t), 3.1 * std::cos(3.1 * t), 0.7, 0.9};
    model.step(in, 1.0 / 1024);
    d.setConstant(std::sin(3.1 * t));
    v.setConstant(3.1 * std::cos(3.1 * t));
    bank.step(d, v, 1.0 / 1024, f);
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
}

long allocations_of_run(double duration_s) {
  server::RunConfig c = server::load_run_config(test_paths::source_dir() + "/configs/ten-story.yaml");
  c.record.duration_s = duration_s;
  c.transport.kind = "in_process";
  // The CSV writer preallocates its blocks from the run length (set-up, proportional to the
  // duration): with one row per 8192 steps both runs preallocate the same two blocks, so any
  // difference left is the loop's. Hand-overs to the writer thread still happen every
  // flush_every_steps (1024) steps.
  c.output.every_n_steps = 8192;
  c.output.dir = (std::filesystem::temp_directory_path() / ("hybridsim-alloc-" + std::to_string(getpid()))).string();
  server::SubstructureSession session(c, c.output.dir, "alloc");
  const long before = g_allocations.load();
  const server::RunSummary s = server::run_hybrid(c, session.substructure(), "alloc");
  const long n = g_allocations.load() - before;
  EXPECT_EQ(s.status, "ok") << s.error;
  std::printf("[ measured ] run_hybrid, 10-story in-process, %.0f s (%ld steps): %ld allocations\n", duration_s,
              s.steps, n);
  return n;
}

TEST(Allocation, RunHybridAllocatesNothingPerStep) {
  allocations_of_run(0.5);  // first run: one-time initialisations (locale, static tables) not counted
  const long short_run = allocations_of_run(2.0);
  const long long_run = allocations_of_run(4.0);
  EXPECT_EQ(long_run, short_run) << "the 4 s run allocated " << long_run - short_run
                                 << " more times than the 2 s run: something allocates per step";
}

}  // namespace
