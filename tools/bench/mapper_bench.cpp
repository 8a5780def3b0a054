// Mapper speed targets (issue 4): <= 1 ms per iteration with 30 visible planes, and the same
// with a 2,000-plane map. Plane sets are made beforehand by the ideal segmenter so only the
// mapper is timed. Run by hand: relplane-bench-mapper.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "ideal_segmenter.hpp"

namespace {

using relplane::geometry::Pose2;
using relplane::mapper::Mapper;
using relplane::mapper::PlaneInput;
using namespace relplane::mapper::testing;

// 30 short walls on two arcs ahead of the sensor, none hiding another.
World ThirtyWalls() {
  World w{"thirty_walls", {}};
  for (int i = 0; i < 30; ++i) {
    const double angle = (-38.0 + 76.0 * i / 29.0) * M_PI / 180.0;
    const double r = 4.0 + 0.6 * (i % 2);
    const Eigen::Vector2d c(r * std::cos(angle), r * std::sin(angle));
    const Eigen::Vector2d t(-std::sin(angle), std::cos(angle));
    w.walls.push_back({c - 0.09 * t, c + 0.09 * t});
  }
  return w;
}

std::vector<std::vector<PlaneInput>> Frames(IdealSegmenter& segmenter,
                                            const std::vector<Pose2>& poses) {
  std::vector<std::vector<PlaneInput>> frames;
  for (const auto& pose : poses) frames.push_back(segmenter.Planes(pose));
  return frames;
}

void BM_Iteration30VisiblePlanes(benchmark::State& state) {
  IdealSegmenter segmenter(ThirtyWalls(), {});
  // Sway back and forth so the walls stay in view; warm up for 300 iterations first.
  std::vector<Pose2> poses;
  for (int k = 0; k < 2000; ++k) {
    poses.push_back({0.4 * std::sin(k * 0.01), 0.2 * std::sin(k * 0.013), 0.05 * std::sin(k * 0.02)});
  }
  const auto frames = Frames(segmenter, poses);
  Mapper mapper;
  int64_t k = 0;
  for (; k < 300; ++k) mapper.Process(k, frames[k]);
  size_t visible = 0;
  for (auto _ : state) {
    const auto est = mapper.Process(k, frames[k % frames.size()]);
    benchmark::DoNotOptimize(est);
    visible += frames[k % frames.size()].size();
    ++k;
  }
  state.counters["visible"] = static_cast<double>(visible) / state.iterations();
  state.counters["map"] = static_cast<double>(mapper.Stats().map_planes);
  state.counters["groups"] = static_cast<double>(mapper.Stats().groups);
}
BENCHMARK(BM_Iteration30VisiblePlanes)->Unit(benchmark::kMicrosecond)->Iterations(1000)
    ->Repetitions(5)->ReportAggregatesOnly(true);

// A 1.5 km hallway with doors every 3 m on both sides, driven end to end but for the last
// 1500 frames (kept in `tail`), built once for the benchmarks that use it.
struct LargeMap {
  Mapper* mapper = nullptr;
  std::vector<std::vector<PlaneInput>> tail;
  int64_t next = 0;  // the next iteration
  int64_t base = 0;  // the iteration of tail[0]
};

LargeMap& BuildLargeMap() {
  static LargeMap large;
  if (large.mapper == nullptr) {
    IdealSegmenter segmenter(HallwayWithDoors(1560.0), {});
    const auto poses = Drive({{0, 0}, {1550, 0}}, 1.2, 0.8);
    large.mapper = new Mapper();
    const size_t timed = 1500;
    for (; large.next < static_cast<int64_t>(poses.size() - timed); ++large.next) {
      large.mapper->Process(large.next, segmenter.Planes(poses[large.next]));
    }
    large.tail = Frames(segmenter, {poses.end() - timed, poses.end()});
    large.base = large.next;
  }
  return large;
}

void BM_IterationWith2000PlaneMap(benchmark::State& state) {
  // The last 300 iterations of the large map's drive are timed.
  LargeMap& large = BuildLargeMap();
  Mapper* mapper = large.mapper;
  const auto& tail = large.tail;
  int64_t& k = large.next;
  const int64_t base = large.base;
  const int64_t start = static_cast<int64_t>(mapper->Stats().map_planes);
  for (auto _ : state) {
    const size_t i = static_cast<size_t>(k - base) % tail.size();
    const auto est = mapper->Process(k, tail[i]);
    benchmark::DoNotOptimize(est);
    ++k;
  }
  state.counters["map"] = static_cast<double>(start);
  state.counters["groups"] = static_cast<double>(mapper->Stats().groups);
  state.counters["graph_solves"] = static_cast<double>(mapper->Stats().graph_solves);
}
BENCHMARK(BM_IterationWith2000PlaneMap)->Unit(benchmark::kMicrosecond)->Iterations(300)
    ->Repetitions(5)->ReportAggregatesOnly(true);

// The published map (MAP, at most 10 Hz) of the large map: duplicate merging and corner
// snapping look at every pair of walls.
void BM_MapSnapshotOf2000PlaneMap(benchmark::State& state) {
  const Mapper& mapper = *BuildLargeMap().mapper;
  size_t walls = 0;
  for (auto _ : state) {
    const auto snapshot = mapper.Map();
    walls = snapshot.planes.size();
    benchmark::DoNotOptimize(walls);
  }
  state.counters["walls"] = static_cast<double>(walls);
}
BENCHMARK(BM_MapSnapshotOf2000PlaneMap)->Unit(benchmark::kMillisecond)->Iterations(10)
    ->Repetitions(5)->ReportAggregatesOnly(true);

// Issue 5: the time per iteration while loops close. The 3-lap loop with door recesses at
// sigma = 1 cm plane noise (the mapper_scenarios_test fixture); laps 2 and 3 re-see the first
// lap's walls, close the loop and run the pose graph over the groups. Every iteration of laps
// 2-3 is timed; the counters give its median and 99th percentile (microseconds).
void BM_IterationWhileLoopsClose(benchmark::State& state) {
  IdealSegmenter segmenter(HallwayLoop(10, 8, 2, 3), {}, {0.003, 0.003, 0.015, 7});
  const auto poses = Drive({{0, 0}, {8, 0}, {8, 6}, {0, 6}}, 1.0, 0.8, 30.0, 3);
  const auto frames = Frames(segmenter, poses);
  const size_t lap = frames.size() / 3;
  std::vector<double> times;
  for (auto _ : state) {
    state.PauseTiming();
    Mapper mapper;
    size_t k = 0;
    for (; k < lap; ++k) mapper.Process(static_cast<int64_t>(k), frames[k]);
    state.ResumeTiming();
    for (; k < frames.size(); ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      const auto est = mapper.Process(static_cast<int64_t>(k), frames[k]);
      const auto t1 = std::chrono::steady_clock::now();
      benchmark::DoNotOptimize(est);
      times.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    }
  }
  std::sort(times.begin(), times.end());
  state.counters["p50_us"] = times[times.size() / 2];
  state.counters["p99_us"] = times[times.size() * 99 / 100];
  state.counters["max_us"] = times.back();
  state.counters["iterations_timed"] = static_cast<double>(times.size());
}
BENCHMARK(BM_IterationWhileLoopsClose)->Unit(benchmark::kMillisecond)->Iterations(1)
    ->Repetitions(3);

}  // namespace

BENCHMARK_MAIN();
