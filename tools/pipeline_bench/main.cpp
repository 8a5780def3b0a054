// relplane-bench: the whole pipeline (segmenter + mapper as real processes on a private bus)
// fed with simulated clouds at rising rates; latency per stage and end to end, matched by seq
// on this host's monotonic clock (issue "Benchmark"). Clouds are made before each run so the
// simulator's own cost is not in the figures.

#include <sys/utsname.h>
#include <unistd.h>

#include <relplane/point_cloud_t.hpp>

#include <chrono>
#include <csignal>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <thread>

#include "convert.hpp"
#include "latency_table.hpp"
#include "options_yaml.hpp"
#include "pipeline_run.hpp"
#include "relplane/common/bus.hpp"
#include "relplane/common/cli.hpp"
#include "relplane/common/service_runtime.hpp"
#include "report.hpp"
#include "stage_profile.hpp"

namespace fs = std::filesystem;
using namespace relplane;
using namespace relplane::bench;

namespace {

std::string MachineName() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  }
  return model + ", " + std::to_string(std::thread::hardware_concurrency()) + " cores";
}

// The clouds of the first `count` iterations of the scenario at `width` x `height`, encoded.
std::vector<std::vector<uint8_t>> MakeClouds(sim::SimOptions options, int width, int height,
                                             int count, int* points_per_frame) {
  options.sensor.width = width;
  options.sensor.height = height;
  sim::Simulation simulation(options);
  count = static_cast<int>(std::min<int64_t>(count, simulation.NumIterations()));
  std::vector<std::vector<uint8_t>> clouds;
  int64_t points = 0;
  for (int k = 0; k < count; ++k) {
    const point_cloud_t cloud = sim::ToPointCloud(simulation.Frame(k), k, simulation.Utime(k));
    points += cloud.num_points;
    std::vector<uint8_t> bytes(cloud.getEncodedSize());
    cloud.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    clouds.push_back(std::move(bytes));
  }
  *points_per_frame = count > 0 ? static_cast<int>(points / count) : 0;
  return clouds;
}

}  // namespace

int main(int argc, char** argv) {
  Flags flags;
  cli::Parser parser{
      "Pipeline latency and throughput against the 30 it/s budget: relplane-segmenter "
      "and relplane-mapper fed with simulated clouds at rising rates.",
      "relplane-bench"};
  parser.Add("scenario", &flags.scenario, "Scenario YAML (its sim section makes the clouds)")
      .ExistingFile()
      .Required();
  parser.Add("--out", &flags.out, "Folder for bench.json and latency.svg").Required();
  parser.Add("--rates", &flags.rates, "Sensor rates for 160x120 clouds, Hz; 0 = unpaced")
      .Delimiter(',')
      .ShowDefault();
  parser.Add("--large-rates", &flags.large_rates, "Sensor rates for 640x480 clouds, Hz")
      .Delimiter(',')
      .ShowDefault();
  parser.Add("--frames", &flags.frames, "Frames per 160x120 run").ShowDefault();
  parser.Add("--large-frames", &flags.large_frames, "Frames per 640x480 run").ShowDefault();
  parser.Add("--warmup-frames", &flags.warmup_frames,
             "Frames sent to each fresh pipeline before the timed ones, one at a time (their "
             "latencies are in bench.json as warmup_ms, not in the figures)")
      .NonNegative()
      .ShowDefault();
  parser.Add("--floor-pings", &flags.floor_pings,
             "Round trips per message size for the bus floor").Positive().ShowDefault();
  parser.AddFlag("--skip-large", &flags.skip_large, "Only 160x120 clouds");
  parser.AddFlag("--one-bus", &flags.one_bus,
                 "Clouds on the main bus, as before issue 54 (default: a bus of their own)");
  parser.AddFlag("--verbose", &flags.verbose, "Show the services' output");
  if (const auto code = parser.Parse(argc, argv)) return *code;
  InstallStopHandlers();

  sim::SimOptions sim_options;
  try {
    sim_options = sim::LoadServiceOptions(flags.scenario).sim;
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return cli::kExitConfig;
  }
  const std::string bin_dir = fs::canonical("/proc/self/exe").parent_path().string();

  BenchReport report;
  report.scenario = flags.scenario;
  report.machine = MachineName();
  report.buses = flags.one_bus ? "one bus for everything" : "clouds on a bus of their own";
  report.date = [] {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%d %H:%M UTC", &utc);
    return std::string(text);
  }();
  struct Size {
    const char* name;
    int width, height, frames;
    std::vector<double> rates;
  };
  std::vector<Size> sizes = {{"160x120", 160, 120, flags.frames, flags.rates}};
  if (!flags.skip_large) sizes.push_back({"640x480", 640, 480, flags.large_frames, flags.large_rates});
  try {
    for (const Size& size : sizes) {
      ResolutionResult res;
      res.name = size.name;
      std::cerr << "making " << size.frames << " " << size.name << " clouds...\n";
      const auto clouds = MakeClouds(sim_options, size.width, size.height,
                                     size.frames + flags.warmup_frames, &res.points_per_frame);
      std::cerr << "timing the segmenter and mapper alone on them...\n";
      std::vector<std::vector<uint8_t>> plane_sets;
      res.segmenter_compute = Summarise(ProfileSegmenter(flags.scenario, clouds, &plane_sets));
      res.mapper_compute = Summarise(ProfileMapper(flags.scenario, plane_sets));
      std::cerr << "  segmenter alone p50 " << res.segmenter_compute.p50_ms << " ms, mapper alone p50 "
                << res.mapper_compute.p50_ms << " ms\n";
      std::cerr << "measuring the bus floor (" << flags.floor_pings
                << " round trips per message size)...\n";
      res.floor = MeasureFloor(flags, bin_dir, clouds.empty() ? 0 : clouds.front().size());
      std::cerr << "  bus floor " << res.floor.PipelineFloorMs() << " ms (round trips p50: cloud "
                << res.floor.cloud_round_trip.p50_ms << ", pose "
                << res.floor.pose_round_trip.p50_ms << " ms)\n";
      for (double rate : size.rates) {
        if (StopRequested()) break;
        std::vector<double> e2e;
        res.rates.push_back(RunAtRate(flags, bin_dir, clouds, rate, &e2e));
        std::cerr << "  " << ProgressLine(size.name, res.rates.back(), res.floor) << "\n";
        if (rate == 30.0) res.e2e_ms_at_30hz = e2e;
      }
      report.resolutions.push_back(std::move(res));
    }
  } catch (const std::exception& e) {
    std::cerr << "relplane-bench: " << e.what() << "\n";
    return 1;
  }

  const Verdict verdict = Judge(report);
  fs::create_directories(flags.out);
  std::ofstream(flags.out + "/bench.json") << [&] {
    std::ostringstream s;
    WriteJson(report, verdict, s);
    return s.str();
  }();
  std::ofstream svg(flags.out + "/latency.svg");
  WriteHistogramSvg(report, svg);
  PrintTable(report, verdict, std::cout);
  std::cout << "wrote " << flags.out << "/bench.json and " << flags.out << "/latency.svg\n";
  return verdict.pass ? 0 : 3;
}
