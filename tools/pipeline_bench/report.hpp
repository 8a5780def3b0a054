#pragma once
// The pipeline benchmark's outputs: bench.json, a latency histogram SVG and the terminal table
// with PASS/FAIL against the 30 it/s budget (DESIGN.md "Real-time budget").

#include <ostream>
#include <string>
#include <vector>

#include "latency_table.hpp"

namespace relplane::bench {

struct ResolutionResult {
  std::string name;  // e.g. "160x120"
  int points_per_frame = 0;
  std::vector<RateResult> rates;
  std::vector<double> e2e_ms_at_30hz;  // for the histogram
  // Each stage's own compute per frame on the same clouds, in one process and thread (thread
  // CPU time; see stage_profile.hpp).
  LatencySummary segmenter_compute;
  LatencySummary mapper_compute;
};

struct BenchReport {
  std::string scenario;
  std::string machine;  // CPU model and core count
  std::vector<ResolutionResult> resolutions;
};

// The targets of the benchmark (issue: p99 end to end <= 5 ms at 30 Hz with 160x120 clouds;
// >= 300 it/s held; 640x480 at 30 Hz with zero drops).
struct Verdict {
  bool pass = true;
  std::vector<std::string> lines;  // one per check: "PASS ..." or "FAIL ..."
};
Verdict Judge(const BenchReport& report);

// Highest requested rate held (unpaced counts with its achieved rate), 0 if none.
double HighestHeldRate(const ResolutionResult& r);

void WriteJson(const BenchReport& report, const Verdict& verdict, std::ostream& out);
void WriteHistogramSvg(const BenchReport& report, std::ostream& out);
void PrintTable(const BenchReport& report, const Verdict& verdict, std::ostream& out);

}  // namespace relplane::bench
