#pragma once
// A seed sweep: the runs it is made of, the targets each run is held to, and the
// summary over a scenario's runs.

#include <cstdint>
#include <string>
#include <vector>

#include "relplane/accuracy/scenario_run.hpp"

namespace relplane::accuracy {

// Parses a seed list such as "1-6", "2,5" or "1-3,7" into seeds in the order given. Throws
// std::invalid_argument naming the bad part; seeds are positive (0 is the scenario's own).
std::vector<uint64_t> ParseSeeds(const std::string& text);

// Issue 4's σ = 1 cm targets, the defaults: ATE RMSE ≤ 5 cm, no duplicate wall, every scored
// wall within 1° and 5 cm.
struct Targets {
  double ate_rmse_m = 0.05;
  int64_t duplicates = 0;
  double normal_deg = 1.0;
  double offset_m = 0.05;
};

// The targets `r` misses, one short phrase each ("ATE 0.052 m"); empty when it meets them all.
// A run that mapped no wall, or has a frame without a pose, misses.
std::vector<std::string> Misses(const RunResult& r, const Targets& targets);

// One run of a sweep.
struct SweepRun {
  std::string scenario;  // the file's name without .yaml
  uint64_t seed = 0;     // 0: the scenario's own
  RunResult result;
  std::vector<std::string> misses;
  double seconds = 0.0;  // wall time of the run, for the progress lines only
};

// The runs of one scenario together.
struct ScenarioSummary {
  std::string scenario;
  int runs = 0;
  int meeting = 0;  // runs meeting every target
  double ate_sum_m = 0.0;
  double ate_worst_m = 0.0;
  std::vector<uint64_t> failing_seeds;
};

// Per scenario, in the order scenarios first appear in `runs`.
std::vector<ScenarioSummary> Summarise(const std::vector<SweepRun>& runs);

// The runs of one world kind together (world_kind.hpp): generated worlds are judged per kind.
struct KindSummary {
  std::string kind;
  int worlds = 0;
  int within_ate = 0;  // runs with ATE RMSE within the target
  int with_duplicates = 0;
  double ate_median_m = 0.0;
  double ate_worst_m = 0.0;
  double consistency = 0.0;  // mean share of frames within 3 sigma (x-y) of POSE's covariance
};

std::vector<KindSummary> SummariseByKind(const std::vector<SweepRun>& runs,
                                         const Targets& targets);

// The per-kind table as text, one line per kind, `sigma` in its title (m; negative: the
// scenarios' own).
std::string KindTable(const std::vector<KindSummary>& kinds, const Targets& targets, double sigma);

// One line for a run: "office seed 3: ATE 0.013 m, 0 duplicates, ... meets the targets".
std::string RunLine(const SweepRun& run);

// Every frame of a run as CSV (seq, status, estimate, truth, position and yaw error), for
// finding the iteration where a run goes wrong. Status is POSE's name, "REFUSED" for a frame
// the conversions refused.
std::string FramesCsv(const RunResult& r);

// The sweep as JSON: the targets, every run's metrics and misses, and the summaries.
std::string SweepJson(const std::vector<SweepRun>& runs, const Targets& targets,
                      const std::vector<std::string>& overrides);

}  // namespace relplane::accuracy
