// Hunt-and-fill tracing (server/ida/hunt_fill.h) on synthetic IDA curves with a known
// collapse IM: the trace uses its whole budget, brackets the collapse IM to the resolution,
// and, stopped after any number of finished runs and started again, never asks for a
// finished run again.
#include "server/ida/hunt_fill.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace {

using namespace server::ida;

/// A building whose drift ratio grows as 0.02·IM and collapses at IM = collapse_im.
TracePoint run(double im, double collapse_im) { return {im, 0.02 * im, im >= collapse_im}; }

std::vector<TracePoint> trace(const HuntFillSettings& s, double collapse_im, std::vector<TracePoint> done = {}) {
  for (int guard = 0; guard < 1000; ++guard) {
    const std::vector<double> next = next_runs(s, done);
    if (next.empty()) break;
    for (double im : next) done.push_back(run(im, collapse_im));
  }
  return done;
}

TEST(HuntFill, HuntSequenceGrowsByTheIncrement) {
  HuntFillSettings s;
  s.first_im = 0.2;
  s.step = 0.1;
  s.step_increment = 0.05;
  s.max_im = 1.0;
  const std::vector<double> seq = hunt_sequence(s);
  const std::vector<double> expected{0.2, 0.3, 0.45, 0.65, 0.9, 1.0};
  ASSERT_EQ(seq.size(), expected.size());
  for (std::size_t i = 0; i < seq.size(); ++i) EXPECT_NEAR(seq[i], expected[i], 1e-12);
}

TEST(HuntFill, BracketsTheCollapseAndFillsTheBudget) {
  HuntFillSettings s;  // defaults: 0.1 + k·0.1 + ½k(k−1)·0.05, resolution 0.05
  s.max_runs = 16;      // enough for 11 hunt runs (collapse at 2.9 g) and 4 bisections
  for (double collapse_im : {0.37, 1.234, 2.9}) {
    const std::vector<TracePoint> t = trace(s, collapse_im);
    EXPECT_EQ(static_cast<int>(t.size()), s.max_runs) << collapse_im;
    double highest_ok = 0.0, lowest_collapse = 1e9;
    for (const TracePoint& p : t) {
      if (p.collapse) lowest_collapse = std::min(lowest_collapse, p.im);
      else highest_ok = std::max(highest_ok, p.im);
    }
    EXPECT_LE(lowest_collapse - highest_ok, s.bracket_resolution) << collapse_im;
    EXPECT_LT(highest_ok, collapse_im);
    EXPECT_GE(lowest_collapse, collapse_im);
    // No IM twice.
    for (std::size_t i = 0; i < t.size(); ++i)
      for (std::size_t j = i + 1; j < t.size(); ++j) EXPECT_NE(t[i].im, t[j].im);
  }
}

TEST(HuntFill, NoCollapseBelowTheCeilingIsCensoredThere) {
  HuntFillSettings s;
  s.max_im = 1.0;
  const std::vector<TracePoint> t = trace(s, 100.0);
  double top = 0.0;
  for (const TracePoint& p : t) top = std::max(top, p.im);
  EXPECT_EQ(top, 1.0);
  EXPECT_EQ(static_cast<int>(t.size()), s.max_runs);  // the rest of the budget fills gaps
}

TEST(HuntFill, ResumeAfterAnyStopRedoesNothing) {
  HuntFillSettings s;
  const double collapse_im = 1.7;
  const std::vector<TracePoint> full = trace(s, collapse_im);
  for (std::size_t stop = 0; stop <= full.size(); ++stop) {
    // Finished before the kill: the first `stop` runs (in the order they were handed out).
    std::vector<TracePoint> done(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(stop));
    const std::vector<double> next = next_runs(s, done);
    for (double im : next)
      for (const TracePoint& p : done) EXPECT_NE(im, p.im) << "stop after " << stop;
    const std::vector<TracePoint> resumed = trace(s, collapse_im, done);
    EXPECT_EQ(resumed.size(), full.size()) << "stop after " << stop;
  }
}

TEST(HuntFill, RejectsBadSettings) {
  HuntFillSettings s;
  s.step = 0.0;
  EXPECT_THROW(hunt_sequence(s), std::invalid_argument);
  s = HuntFillSettings{};
  s.max_runs = 1;
  EXPECT_THROW(hunt_sequence(s), std::invalid_argument);
}

}  // namespace
