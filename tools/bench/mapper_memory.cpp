// Long-run memory and time of the mapper (issue 5, "bounded memory"): drives the ideal-segmenter
// hallway loop lap after lap for N minutes of simulated time and reports, at 1, 10 and 30
// minutes (and every minute as progress), the process's resident memory, what the mapper holds
// (rltplanes, stored observations, comparisons, groups), the time per iteration (median, p99,
// max over the last minute; includes every loop closure in that minute) and the pose error
// over that minute (RMS and worst, against the driven poses): flat memory must not cost
// accuracy. Not a unit test: run by
// hand or from `./relplane bench`; the machine's load shows in the times, not in the memory.
#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "ideal_segmenter.hpp"
#include "relplane/common/cli.hpp"
#include "relplane/common/service_stats.hpp"

namespace {

using namespace relplane::mapper::testing;
using relplane::mapper::Mapper;
using relplane::mapper::MapperStats;

// Resident set size of this process in MiB, from /proc/self/status (0 where it is absent).
double ResidentMiB() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  }
  return 0.0;
}

struct Sample {
  double minute = 0.0;
  double rss_mib = 0.0;
  double heap_mib = 0.0;  // bytes the allocator has handed out: what the mapper really holds
  size_t planes = 0;
  size_t observations = 0;
  size_t comparisons = 0;
  size_t groups = 0;
  double p50_ms = 0.0;
  double p99_ms = 0.0;
  double max_ms = 0.0;
  double rms_error_m = 0.0;
  double max_error_m = 0.0;
};

// The pose errors of one minute.
struct Errors {
  double sum_sq = 0.0;
  double max = 0.0;
  size_t n = 0;
  void Add(double e) {
    sum_sq += e * e;
    max = std::max(max, e);
    ++n;
  }
};

Sample Measure(const Mapper& mapper, double minute, const std::vector<double>& window_ms,
               const Errors& errors) {
  const MapperStats stats = mapper.Stats();
  Sample s;
  s.minute = minute;
  s.rss_mib = ResidentMiB();
  s.heap_mib = static_cast<double>(mallinfo2().uordblks) / (1024.0 * 1024.0);
  s.planes = stats.planes;
  s.observations = stats.observations;
  s.comparisons = stats.comparisons;
  s.groups = stats.groups;
  s.p50_ms = relplane::Percentile(window_ms, 0.5);
  s.p99_ms = relplane::Percentile(window_ms, 0.99);
  s.max_ms = window_ms.empty() ? 0.0 : *std::max_element(window_ms.begin(), window_ms.end());
  s.rms_error_m = errors.n > 0 ? std::sqrt(errors.sum_sq / errors.n) : 0.0;
  s.max_error_m = errors.max;
  return s;
}

void Print(const Sample& s) {
  std::printf("%6.1f min  rss %7.1f MiB  heap %7.2f MiB  planes %6zu  observations %8zu  "
              "comparisons %7zu  groups %6zu  ms/iteration p50 %.3f p99 %.3f max %.2f  "
              "pose error rms %.3f max %.3f m\n",
              s.minute, s.rss_mib, s.heap_mib, s.planes, s.observations, s.comparisons, s.groups,
              s.p50_ms, s.p99_ms, s.max_ms, s.rms_error_m, s.max_error_m);
  std::fflush(stdout);
}

void WriteJson(const std::string& path, const std::vector<Sample>& samples, bool noisy) {
  std::ofstream out(path);
  out << "{\n  \"world\": \"hallway_loop 16x10 m, recesses every 3 m\",\n  \"noisy\": "
      << (noisy ? "true" : "false") << ",\n  \"samples\": [\n";
  for (size_t i = 0; i < samples.size(); ++i) {
    const Sample& s = samples[i];
    out << "    {\"minute\": " << s.minute << ", \"rss_mib\": " << s.rss_mib
        << ", \"heap_mib\": " << s.heap_mib
        << ", \"planes\": " << s.planes << ", \"observations\": " << s.observations
        << ", \"comparisons\": " << s.comparisons << ", \"groups\": " << s.groups
        << ", \"p50_ms\": " << s.p50_ms << ", \"p99_ms\": " << s.p99_ms
        << ", \"max_ms\": " << s.max_ms << ", \"rms_error_m\": " << s.rms_error_m
        << ", \"max_error_m\": " << s.max_error_m << "}" << (i + 1 < samples.size() ? "," : "") << "\n";
  }
  out << "  ]\n}\n";
}

}  // namespace

int main(int argc, char** argv) {
  relplane::cli::Parser parser{
      "Drives the mapper round a hallway loop for N simulated minutes and reports "
      "resident memory, stored observations and time per iteration at 1, 10 and 30 "
      "minutes (issue 5: bounded memory)."};
  double minutes = 30.0;
  bool noisy = false;
  std::string json;
  parser.Add("--minutes", &minutes, "Simulated minutes to run (30 Hz)").Range(0.1, 600.0);
  parser.AddFlag("--noisy", &noisy, "Plane-level noise of a sigma = 1 cm segmenter");
  parser.Add("--json", &json, "Also write the samples to this JSON file");
  if (const auto code = parser.Parse(argc, argv)) return *code;

  constexpr double kRate = 30.0;
  const World world = HallwayLoop(16.0, 10.0, 2.0, 3.0);
  // Drive enough laps of the centre line for `minutes`.
  const std::vector<Eigen::Vector2d> corners = {{0, 0}, {14, 0}, {14, 8}, {0, 8}};
  const int64_t iterations = std::llround(minutes * 60 * kRate);
  const auto lap = static_cast<int64_t>(Drive(corners, 1.0, 0.8, kRate, 1).size());
  const auto poses = Drive(corners, 1.0, 0.8, kRate, static_cast<int>(iterations / lap) + 2);

  IdealSegmenter segmenter(world, {}, noisy ? Noise{0.003, 0.003, 0.015, 7} : Noise{});
  Mapper mapper;
  std::vector<Sample> samples;
  samples.push_back(Measure(mapper, 0.0, {}, {}));
  Print(samples.back());
  std::vector<double> window_ms;
  Errors errors;
  const int64_t per_minute = static_cast<int64_t>(60 * kRate);
  for (int64_t k = 0; k < iterations; ++k) {
    const auto planes = segmenter.Planes(poses[k]);
    const auto start = std::chrono::steady_clock::now();
    const auto estimate = mapper.Process(k, planes);
    window_ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
    errors.Add((estimate.pose.Translation() - poses[k].Translation()).norm());
    if ((k + 1) % per_minute == 0 || k + 1 == iterations) {
      samples.push_back(Measure(mapper, (k + 1) / (60 * kRate), window_ms, errors));
      Print(samples.back());
      window_ms.clear();
      errors = {};
    }
  }
  if (!json.empty()) WriteJson(json, samples, noisy);
  return 0;
}
