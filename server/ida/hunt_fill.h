#pragma once
/// @file hunt_fill.h
/// Hunt-and-fill tracing of one record's IDA curve (Vamvatsikos & Cornell 2002,
/// "Incremental dynamic analysis", Earthquake Eng. Struct. Dyn. 31(3), §6):
///   1. hunt up: IM_k = IM_0 + k·s + ½k(k−1)·Δs (the step grows by Δs after every run
///      that did not collapse), until the first collapse or the IM ceiling;
///   2. bracket: bisect between the highest non-collapsed IM and the lowest collapsed IM
///      until the gap is at most `bracket_resolution`;
///   3. fill: the runs left of the budget halve the largest IM gaps between non-collapsed
///      runs (starting from IM = 0), largest first.
/// "Collapse" is the IDA flatline: a peak interstory drift ratio at or above the collapse
/// limit, or a run that failed (non-finite response, the model stopped).
///
/// The next runs are a pure function of the finished ones: a traced record that is started
/// again (after a kill) asks for exactly the runs that were not finished. Hunt and bracket
/// runs are sequential (each depends on the last); the fill runs are handed out together.

#include <vector>

namespace server::ida {

struct HuntFillSettings {
  double first_im = 0.1;            ///< IM of the first run (g)
  double step = 0.1;                ///< first hunt step (g)
  double step_increment = 0.05;     ///< added to the step after every non-collapsed run (g)
  double max_im = 5.0;              ///< hunt ceiling (g): the record is censored there
  double bracket_resolution = 0.05; ///< bisect until collapse − last non-collapse ≤ this (g)
  int max_runs = 12;                ///< runs per record and case, all phases
};

/// One finished run of a record.
struct TracePoint {
  double im = 0.0;            ///< intensity measure of the run (g)
  double drift_ratio = 0.0;   ///< peak interstory drift ratio over the stories (in/in)
  bool collapse = false;      ///< at/above the collapse limit, or the run failed
};

/// The hunt IMs IM_0, IM_1, ... (clamped to max_im, which ends the sequence).
std::vector<double> hunt_sequence(const HuntFillSettings& s);

/// The IMs to run next, given the finished runs (any order). Empty: the record is traced.
/// @throws std::invalid_argument on bad settings.
std::vector<double> next_runs(const HuntFillSettings& s, const std::vector<TracePoint>& done);

/// Checks the settings; throws std::invalid_argument naming the field.
void validate(const HuntFillSettings& s);

}  // namespace server::ida
