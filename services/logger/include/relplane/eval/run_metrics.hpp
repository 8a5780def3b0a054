#pragma once
// Everything metrics.json reports about one run.

#include <cstdint>
#include <string>
#include <vector>

#include "relplane/eval/map_metrics.hpp"
#include "relplane/eval/timing_metrics.hpp"
#include "relplane/eval/trajectory_metrics.hpp"

namespace relplane::eval {

struct RunCounts {
  int64_t truth_poses = 0;     // SIM_TRUTH messages (distinct seq)
  int64_t estimate_poses = 0;  // POSE messages (distinct seq): the iterations
  int64_t map_updates = 0;     // MAP messages
  int64_t tracking = 0;        // POSE status counts
  int64_t motion_model = 0;
  int64_t initializing = 0;
  int64_t lost = 0;
  double duration_s = kNaN;    // first to last POSE, host receive clock
  double wall_rate_hz = kNaN;  // POSE messages per second of host time
  double sim_rate_hz = kNaN;   // POSE messages per second of simulated time (utime)
};

// The verdict on one `expect:` line.
struct ExpectationResult {
  std::string key;
  double limit = 0.0;
  double value = kNaN;  // NaN when the run gave no data for it (counts as a failure)
  bool is_max = true;   // value must be <= limit (else >= limit)
  bool pass = false;
};

struct RunMetrics {
  RunCounts run;
  TrajectoryMetrics trajectory;
  MapMetrics map;
  TimingMetrics timing;
  std::vector<ExpectationResult> expectations;
};

}  // namespace relplane::eval
