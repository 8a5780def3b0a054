// relplane-accuracy: scenarios through simulator, EM segmenter and mapper in one process, over
// a list of sensor-noise seeds, each run held to issue 4's targets (docs/results.md). No bus and
// no clock: a run gives the same numbers on any machine, so a change to the mapper or the
// segmenter is judged on many seeds in a few minutes.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "relplane/accuracy/baseline.hpp"
#include "relplane/accuracy/scenario_run.hpp"
#include "relplane/accuracy/sweep.hpp"
#include "relplane/common/cli.hpp"
#include "relplane/common/options.hpp"
#include "scenario.hpp"

namespace relplane::accuracy {
namespace {

// Where bare scenario names are looked up.
const std::string kScenariosDir = std::string(RELPLANE_SOURCE_DIR) + "/scenarios";

struct Flags {
  std::vector<std::string> scenarios;
  std::string seeds;
  std::string world_seeds;
  std::string world_kind;
  int generated = 0;
  double sigma = -1.0;
  int laps = 0;
  std::vector<std::string> overrides;
  double min_wall_length_m = 0.3;
  Targets targets;
  int jobs = 0;
  std::string json;
  std::string baseline;
  std::string frames_dir;
  std::string planes_dir;
  bool check = false;
};

// Writes `text` to `path`: "" when done, else why not.
std::string WriteFile(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  return out ? "" : "cannot write " + path;
}

std::string StemOf(const std::string& file) {
  std::string stem = file.substr(file.find_last_of('/') + 1);
  if (stem.size() > 5 && stem.compare(stem.size() - 5, 5, ".yaml") == 0)
    stem.resize(stem.size() - 5);
  return stem;
}

// Calls fn(i) for every i below n on `jobs` threads, each taking the next i as it is done.
void OnThreads(size_t n, int jobs, const std::function<void(size_t)>& fn) {
  std::atomic<size_t> next{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < std::max(1, jobs); ++t) {
    threads.emplace_back([&] {
      for (size_t i = next++; i < n; i = next++) fn(i);
    });
  }
  for (std::thread& t : threads) t.join();
}

// Keeps the runs whose world is of kind `label` (WorldKind::Label), classified on `jobs`
// threads (one per core when 0).
void KeepKind(const std::string& label, int jobs, std::vector<RunSpec>* specs,
              std::vector<SweepRun>* runs) {
  std::vector<char> keep(specs->size(), 0);
  std::vector<std::string> errors(specs->size());
  OnThreads(specs->size(), jobs > 0 ? jobs : static_cast<int>(std::thread::hardware_concurrency()),
            [&](size_t i) {
              try {
                keep[i] = ClassifyScenario((*specs)[i]).Label() == label;
              } catch (const std::exception& e) {
                errors[i] = e.what();
              }
            });
  for (const std::string& error : errors) {
    if (!error.empty()) throw std::runtime_error(error);
  }
  std::vector<RunSpec> kept_specs;
  std::vector<SweepRun> kept_runs;
  for (size_t i = 0; i < specs->size(); ++i) {
    if (!keep[i]) continue;
    kept_specs.push_back((*specs)[i]);
    kept_runs.push_back((*runs)[i]);
  }
  *specs = std::move(kept_specs);
  *runs = std::move(kept_runs);
}

int Main(int argc, char** argv) {
  Flags f;
  cli::Parser parser(
      "Runs each SCENARIO through simulator, EM segmenter and mapper in one process (no bus, no "
      "clock), once per sensor-noise seed, and holds each run to the mapper's targets (ATE RMSE, "
      "duplicate walls, worst wall normal and offset, a pose every frame). Prints a line per run "
      "as it ends and a summary per scenario. Example: "
      "relplane-accuracy office hallway_loop_doors --sigma 0.01 --seeds 1-6 "
      "--min-wall-length 0.31",
      "relplane-accuracy");
  parser.Add("scenarios", &f.scenarios,
             "scenario files, or names of the project's scenarios (office, hallway_loop, ...)");
  parser.Add("--seeds", &f.seeds, "sensor noise seeds, e.g. 1-6 or 2,5 (default: the scenario's)");
  parser.Add("--world-seeds", &f.world_seeds,
             "generated worlds: run each scenario (default random_indoor) in each of these worlds "
             "(sim.world.generators[0].seed). Development: 1-999; held out: 100001-100999 "
             "(docs/decisions/generated-worlds.md)");
  parser.Add("--world-kind", &f.world_kind,
             "generated worlds: run only those of this kind, from their true poses before any "
             "run: observable (the walls in view fix every frame), short (stretches they do not "
             "fix, none of 1 s), long (one of 1 s or more)");
  parser
      .Add("--generated", &f.generated,
           "generated worlds: the first N of the development range (--world-seeds 1-N)")
      .Positive();
  parser.Add("--sigma", &f.sigma, "sensor noise in metres (default: the scenario's)");
  parser.Add("--laps", &f.laps, "times round a closed trajectory (default: the scenario's)")
      .Positive();
  parser.Add("--set", &f.overrides, "override a scenario key, key.path=value (repeatable)")
      .OneValuePerUse();
  parser
      .Add("--min-wall-length", &f.min_wall_length_m,
           "true walls shorter than this are not scored, metres")
      .NonNegative()
      .ShowDefault();
  parser.Add("--ate-max", &f.targets.ate_rmse_m, "target: ATE RMSE, metres")
      .NonNegative()
      .ShowDefault();
  parser.Add("--duplicates-max", &f.targets.duplicates, "target: duplicate walls")
      .NonNegative()
      .ShowDefault();
  parser.Add("--normal-max", &f.targets.normal_deg, "target: worst wall normal, degrees")
      .NonNegative()
      .ShowDefault();
  parser.Add("--offset-max", &f.targets.offset_m, "target: worst wall offset, metres")
      .NonNegative()
      .ShowDefault();
  parser.Add("--jobs,-j", &f.jobs, "runs at once (default: one per core)").NonNegative();
  parser.Add("--json", &f.json, "also write every run's metrics and the summaries to FILE");
  parser.Add("--baseline", &f.baseline,
             "compare with an earlier sweep's --json FILE: runs now "
             "met and now missed, ATE better and worse, run by run");
  parser.Add("--frames", &f.frames_dir,
             "also write each run's poses, frame by frame, to "
             "DIR/SCENARIO-seedN.csv");
  parser.Add(
      "--planes", &f.planes_dir,
      "also write each run's segmented walls against the true ones, frame by frame, to "
      "DIR/SCENARIO-seedN-planes.csv: the fit's offset at its centroid and at the foot of "
      "the perpendicular from the sensor, and the angle between its normal and the true one");
  parser.AddFlag("--check", &f.check, "exit 1 unless every run meets the targets");
  if (auto code = parser.Parse(argc, argv)) return *code;
  if (f.generated > 0 && f.world_seeds.empty()) f.world_seeds = "1-" + std::to_string(f.generated);
  if (!f.world_seeds.empty() && f.scenarios.empty()) f.scenarios = {"random_indoor"};
  if (f.scenarios.empty()) {
    std::fprintf(stderr, "relplane-accuracy: give a scenario, or --generated N (see --help)\n");
    return cli::kExitConfig;
  }
  const std::map<std::string, std::string> kinds = {{"observable", "observable"},
                                                    {"short", "unobservable < 1 s"},
                                                    {"long", "unobservable >= 1 s"}};
  if (!f.world_kind.empty() && kinds.count(f.world_kind) == 0) {
    std::fprintf(stderr, "relplane-accuracy: --world-kind %s: expected observable, short or long\n",
                 f.world_kind.c_str());
    return cli::kExitConfig;
  }

  // Everything is checked before the first run: a typo fails now, not after minutes.
  std::vector<uint64_t> seeds = {0};
  std::vector<std::string> base_overrides = f.overrides;
  std::vector<RunSpec> specs;
  std::vector<SweepRun> runs;
  std::vector<BaselineRun> baseline;
  try {
    if (!f.baseline.empty()) baseline = ReadBaseline(f.baseline);
    if (!f.seeds.empty()) seeds = ParseSeeds(f.seeds);
    std::vector<uint64_t> worlds = {0};  // 0: the scenario's own world
    if (!f.world_seeds.empty()) worlds = ParseSeeds(f.world_seeds);
    if (f.sigma >= 0.0)
      base_overrides.push_back("sim.sensor.noise_sigma=" + std::to_string(f.sigma));
    if (f.laps > 0) base_overrides.push_back("sim.trajectory.laps=" + std::to_string(f.laps));
    for (const std::string& name : f.scenarios) {
      const std::string file = launch::ResolveScenarioFile(name, kScenariosDir);
      for (uint64_t world : worlds) {
        for (uint64_t seed : seeds) {
          RunSpec spec;
          spec.file = file;
          spec.overrides = base_overrides;
          if (world > 0) {
            spec.overrides.push_back("sim.world.generators[0].seed=" + std::to_string(world));
          }
          if (seed > 0) spec.overrides.push_back("sim.sensor.seed=" + std::to_string(seed));
          spec.min_wall_length_m = f.min_wall_length_m;
          spec.plane_errors = !f.planes_dir.empty();
          specs.push_back(spec);
          SweepRun run;
          run.scenario = StemOf(file) + (world > 0 ? "-w" + std::to_string(world) : "");
          run.seed = seed;
          runs.push_back(run);
        }
      }
    }
    // Every run's options are read now, so a bad key or value is reported before any work.
    for (const RunSpec& spec : specs) CheckScenario(spec);
    for (const std::string& dir : {f.frames_dir, f.planes_dir}) {
      if (dir.empty()) continue;
      std::error_code error;
      std::filesystem::create_directories(dir, error);
      if (error) throw std::runtime_error(dir + ": " + error.message());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "relplane-accuracy: %s\n", e.what());
    return cli::kExitConfig;
  }

  if (!f.world_kind.empty()) {
    const size_t before = specs.size();
    try {
      KeepKind(kinds.at(f.world_kind), f.jobs, &specs, &runs);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "relplane-accuracy: %s\n", e.what());
      return cli::kExitConfig;
    }
    std::printf("relplane-accuracy: %zu of %zu runs are in %s worlds\n", specs.size(), before,
                kinds.at(f.world_kind).c_str());
    if (specs.empty()) return 0;
  }
  const int jobs =
      std::max(1, std::min<int>(f.jobs > 0 ? f.jobs : std::thread::hardware_concurrency(),
                                static_cast<int>(specs.size())));
  std::printf("relplane-accuracy: %zu runs on %d thread%s\n", specs.size(), jobs,
              jobs > 1 ? "s" : "");
  std::fflush(stdout);
  std::atomic<size_t> done{0};
  std::mutex print;
  std::vector<std::string> errors(specs.size());
  OnThreads(specs.size(), jobs, [&](size_t i) {
    const auto start = std::chrono::steady_clock::now();
    try {
      runs[i].result = RunScenario(specs[i]);
      runs[i].misses = Misses(runs[i].result, f.targets);
    } catch (const std::exception& e) {
      errors[i] = e.what();
    }
    const std::string stem = runs[i].scenario + "-seed" + std::to_string(runs[i].seed);
    if (errors[i].empty() && !f.frames_dir.empty()) {
      errors[i] = WriteFile(f.frames_dir + "/" + stem + ".csv", FramesCsv(runs[i].result));
    }
    if (errors[i].empty() && !f.planes_dir.empty()) {
      errors[i] = WriteFile(f.planes_dir + "/" + stem + "-planes.csv",
                            PlaneErrorsCsv(runs[i].result.plane_errors));
    }
    runs[i].seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::lock_guard<std::mutex> lock(print);
    const size_t n = ++done;
    if (errors[i].empty()) {
      std::printf("[%zu/%zu] %s (%.1f s)\n", n, specs.size(), RunLine(runs[i]).c_str(),
                  runs[i].seconds);
    } else {
      std::printf("[%zu/%zu] %s seed %llu: failed: %s\n", n, specs.size(), runs[i].scenario.c_str(),
                  static_cast<unsigned long long>(runs[i].seed), errors[i].c_str());
    }
    std::fflush(stdout);
  });

  bool all_met = true;
  for (size_t i = 0; i < runs.size(); ++i) {
    if (!errors[i].empty()) runs[i].misses.push_back("failed: " + errors[i]);
    all_met = all_met && runs[i].misses.empty();
  }
  std::printf("\n%-24s %9s %11s %11s  %s\n", "scenario", "meeting", "ATE sum", "ATE worst",
              "failing seeds");
  int meeting = 0;
  double ate_sum = 0.0;
  for (const ScenarioSummary& s : Summarise(runs)) {
    std::string failing;
    for (uint64_t seed : s.failing_seeds) {
      failing += (failing.empty() ? "" : ",") + (seed > 0 ? std::to_string(seed) : "own");
    }
    std::printf("%-24s %4d of %-2d %9.3f m %9.3f m  %s\n", s.scenario.c_str(), s.meeting, s.runs,
                s.ate_sum_m, s.ate_worst_m, failing.c_str());
    meeting += s.meeting;
    ate_sum += s.ate_sum_m;
  }
  std::printf("%-24s %4d of %-2zu %9.3f m\n", "all", meeting, runs.size(), ate_sum);
  if (!f.world_seeds.empty()) {
    std::printf("\n%s", KindTable(SummariseByKind(runs, f.targets), f.targets, f.sigma).c_str());
  }
  if (!f.baseline.empty()) {
    std::printf("\n%s", ComparisonText(CompareWithBaseline(baseline, runs), f.baseline).c_str());
  }
  if (!f.json.empty()) {
    std::ofstream out(f.json);
    out << SweepJson(runs, f.targets, base_overrides);
    if (!out) {
      std::fprintf(stderr, "relplane-accuracy: cannot write %s\n", f.json.c_str());
      return 1;
    }
  }
  return f.check && !all_met ? 1 : 0;
}

}  // namespace
}  // namespace relplane::accuracy

int main(int argc, char** argv) { return relplane::accuracy::Main(argc, argv); }
