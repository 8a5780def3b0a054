#pragma once
// The pipeline benchmark's outputs: bench.json, a latency histogram SVG and the terminal table
// with PASS/FAIL against the 30 it/s budget (DESIGN.md "Real-time budget").

#include <ostream>
#include <string>
#include <vector>

#include "bus_floor.hpp"
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
  // The transport alone, with this resolution's clouds, measured just before its rates.
  BusFloor floor;
};

struct BenchReport {
  std::string scenario;
  std::string machine;  // CPU model and core count
  std::string buses;    // how the buses were laid out ("clouds on a bus of their own", ...)
  std::string date;     // UTC, when the bench started
  std::vector<ResolutionResult> resolutions;
};

// The targets of the benchmark (issues 10 and 54: p99 end to end <= 5 ms at 30 Hz with 160x120
// clouds and p50 within 3x the bus floor; >= 300 it/s held; the mapper process's CPU per frame
// within 2x its algorithm alone; 640x480 at 30 Hz with zero drops, within its frame period).
struct Verdict {
  bool pass = true;
  std::vector<std::string> lines;  // one per check: "PASS ..." or "FAIL ..."
};
Verdict Judge(const BenchReport& report);

// The last line: "PASS: all N checks" or "FAIL: K of N checks: <each failing check>".
std::string Headline(const Verdict& verdict);

// The rest of the machine during the pipeline runs, averaged: CPU of other processes in cores
// (negative when unknown) and the highest load average seen.
struct MachineLoad {
  double other_cores = -1.0;
  double load_average = -1.0;
};
MachineLoad LoadDuringRuns(const BenchReport& report);
// A note when other work shared the machine (other processes used more than a tenth of a core
// on average): the latencies are not a quiet machine's; "" when it was quiet or unknown.
std::string LoadNote(const BenchReport& report);

// One line as a rate's run ends: rate achieved, drops, end-to-end p50/p99, ratio to the bus
// floor, CPU per frame, the machine's load.
std::string ProgressLine(const std::string& resolution, const RateResult& r,
                         const BusFloor& floor);

// Highest requested rate held (unpaced counts with its achieved rate), 0 if none.
double HighestHeldRate(const ResolutionResult& r);

void WriteJson(const BenchReport& report, const Verdict& verdict, std::ostream& out);
void WriteHistogramSvg(const BenchReport& report, std::ostream& out);
void PrintTable(const BenchReport& report, const Verdict& verdict, std::ostream& out);

}  // namespace relplane::bench
