#pragma once
// A sweep written earlier with --json, read back as the baseline a new sweep is compared with:
// each change to the mapper or the segmenter is judged by how the same seeds fare before and
// after it, run by run, not by the totals alone.

#include <cstdint>
#include <string>
#include <vector>

#include "relplane/accuracy/sweep.hpp"

namespace relplane::accuracy {

// What a baseline keeps of one run.
struct BaselineRun {
  std::string scenario;
  uint64_t seed = 0;
  bool meets_targets = false;
  double ate_rmse_m = 0.0;  // NaN where the run had no pose to score
};

// The runs of a sweep's JSON text (SweepJson). Throws std::runtime_error with a one-line reason
// when the text is not such a sweep.
std::vector<BaselineRun> ParseBaseline(const std::string& json);

// The same, read from `path`; a missing or unreadable file is a std::runtime_error naming it.
std::vector<BaselineRun> ReadBaseline(const std::string& path);

// One run seen in both sweeps.
struct RunChange {
  std::string scenario;
  uint64_t seed = 0;
  double ate_before_m = 0.0;
  double ate_after_m = 0.0;
  std::vector<std::string> misses_after;  // why a run now misses
};

// A sweep against its baseline, over the runs (scenario and seed) both hold.
struct BaselineComparison {
  double threshold_m = 0.001;  // the ATE change that counts as better or worse
  int common = 0;
  int not_in_baseline = 0;  // runs of the new sweep the baseline does not hold
  int meeting_before = 0;
  int meeting_after = 0;
  double ate_sum_before_m = 0.0;
  double ate_sum_after_m = 0.0;
  int better = 0;  // ATE lower by more than the threshold
  int worse = 0;   // ATE higher by more than the threshold
  std::vector<RunChange> now_met;
  std::vector<RunChange> now_missed;
  std::vector<RunChange> most_worse;  // the largest ATE increases over the threshold, at most 3
};

// Compares `runs` with `baseline`; `threshold_m` is the ATE change that counts as better or
// worse (the runs are deterministic, so any change is real, but a millimetre is not news).
BaselineComparison CompareWithBaseline(const std::vector<BaselineRun>& baseline,
                                       const std::vector<SweepRun>& runs,
                                       double threshold_m = 0.001);

// A few lines for the terminal: meeting and ATE sums before and after, the runs now met and now
// missed, how many got better or worse and the worst of them.
std::string ComparisonText(const BaselineComparison& c, const std::string& baseline_name);

}  // namespace relplane::accuracy
