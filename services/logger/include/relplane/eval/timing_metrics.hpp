#pragma once
// Timing of a run: per-stage and end-to-end latency by seq from the receive times of SIM_TRUTH
// (published with the cloud), PLANES and POSE, and each service's own STATUS reports.

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "relplane/eval/trajectory_metrics.hpp"
#include "relplane/eval/types.hpp"

namespace relplane::eval {

struct LatencySummary {
  int64_t samples = 0;
  double p50_ms = kNaN;
  double p99_ms = kNaN;
  double max_ms = kNaN;
};

// What a service said about itself over the run.
struct ServiceTiming {
  int64_t reports = 0;
  int64_t frames_processed = 0;  // from the last report
  int64_t frames_dropped = 0;
  int64_t inputs_rejected = 0;
  double p50_ms = kNaN;  // median of the per-second p50s
  double p99_ms = kNaN;  // largest per-second p99 (an upper bound of the run's p99)
  double max_ms = kNaN;
};

struct TimingMetrics {
  LatencySummary end_to_end;  // SIM_TRUTH -> POSE
  LatencySummary segmenter;   // SIM_TRUTH -> PLANES
  LatencySummary mapper;      // PLANES -> POSE
  std::map<std::string, ServiceTiming> services;
  int64_t frames_dropped_total = 0;
};

// Collects receive times and STATUS reports as they arrive.
class TimingRecorder {
 public:
  enum Stage { kCloud = 0, kPlanes = 1, kPose = 2 };

  // The first arrival of `seq` at `stage`, `receive_us` on one host clock.
  void Arrived(Stage stage, int64_t seq, int64_t receive_us);
  // Returns true when the report's counters differ from the service's previous report.
  bool Status(const StatusSample& status);
  TimingMetrics Compute() const;

 private:
  struct Reports {
    std::vector<double> p50;
    double p99 = 0.0;
    double max = 0.0;
    StatusSample last;
  };
  std::map<int64_t, std::array<int64_t, 3>> arrivals_;
  std::map<std::string, Reports> reports_;
};

// Nearest-rank percentile summary of `samples_ms`.
LatencySummary Summarise(std::vector<double> samples_ms);

}  // namespace relplane::eval
