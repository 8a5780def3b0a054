// Ray-casting speed (issue 2: a 640x480 frame against 200 rectangles in under 10 ms on one
// core), and the default 160x120 sensor in the hallway loop. Reports the median over
// repetitions. Brute force is measured beside the index for comparison.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "relplane/sim/generators.hpp"
#include "relplane/sim/ray_caster.hpp"
#include "relplane/sim/world.hpp"

namespace {

using relplane::sim::Hit;
using relplane::sim::RayCaster;
using relplane::sim::RayGrid;
using relplane::sim::Rect;
using relplane::sim::World;

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// 198 random walls of all lengths, heights and orientations in a 24 m square, plus floor and
// ceiling: 200 rectangles.
World Clutter200() {
  World world;
  relplane::sim::AddRandomClutter(198, 0, 24.0, 42, &world.rects);
  world.rects.push_back(Rect{{-12, -12, 0}, {24, 0, 0}, {0, 24, 0}});
  world.rects.push_back(Rect{{-12, -12, 2.5}, {0, 24, 0}, {24, 0, 0}});
  return world;
}

World HallwayLoop() {
  relplane::sim::WorldOptions options;
  options.generators = {relplane::sim::HallwayLoopParams{}};
  return relplane::sim::BuildWorld(options);
}

// Poses cycle through a fixed list so every iteration casts a different view.
template <bool kBruteForce>
void CastFrames(benchmark::State& state, const World& world, const RayGrid& grid,
                const std::vector<Eigen::Vector3d>& poses) {
  RayCaster caster(world);
  std::vector<Hit> hits;
  size_t i = 0;
  int64_t hit_count = 0;
  for (auto _ : state) {
    const Eigen::Vector3d& p = poses[i++ % poses.size()];
    if (kBruteForce) {
      caster.CastBruteForce({p.x(), p.y(), 1.0}, p.z(), grid, 8.0, &hits);
    } else {
      caster.Cast({p.x(), p.y(), 1.0}, p.z(), grid, 8.0, &hits);
    }
    for (const Hit& h : hits) hit_count += h.rect >= 0 ? 1 : 0;
    benchmark::DoNotOptimize(hits.data());
  }
  state.counters["hits/frame"] =
      benchmark::Counter(static_cast<double>(hit_count) / static_cast<double>(state.iterations()));
  state.counters["rays/frame"] = static_cast<double>(grid.directions.size());
}

std::vector<Eigen::Vector3d> RandomPoses(double half_extent, int n) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> pos(-half_extent, half_extent);
  std::uniform_real_distribution<double> yaw(-3.14159, 3.14159);
  std::vector<Eigen::Vector3d> poses;
  for (int i = 0; i < n; ++i) poses.emplace_back(pos(rng), pos(rng), yaw(rng));
  return poses;
}

// Along the loop's centre line, including the corners.
std::vector<Eigen::Vector3d> LoopPoses() {
  std::vector<Eigen::Vector3d> poses;
  for (int i = 0; i <= 14; ++i) poses.emplace_back(i, 0.0, 0.0);
  for (int i = 0; i <= 8; ++i) poses.emplace_back(14.0, i, 90 * kDeg);
  for (int i = 14; i >= 0; --i) poses.emplace_back(i, 8.0, 180 * kDeg);
  return poses;
}

void BM_Cast640x480Clutter200(benchmark::State& state) {
  static const World world = Clutter200();
  static const RayGrid grid = RayGrid::Pinhole(640, 480, 90 * kDeg, 60 * kDeg);
  CastFrames<false>(state, world, grid, RandomPoses(10.0, 32));
}

void BM_Cast640x480Clutter200BruteForce(benchmark::State& state) {
  static const World world = Clutter200();
  static const RayGrid grid = RayGrid::Pinhole(640, 480, 90 * kDeg, 60 * kDeg);
  CastFrames<true>(state, world, grid, RandomPoses(10.0, 32));
}

void BM_Cast160x120HallwayLoop(benchmark::State& state) {
  static const World world = HallwayLoop();
  static const RayGrid grid = RayGrid::Pinhole(160, 120, 90 * kDeg, 60 * kDeg);
  CastFrames<false>(state, world, grid, LoopPoses());
}

}  // namespace

BENCHMARK(BM_Cast640x480Clutter200)
    ->Unit(benchmark::kMillisecond)
    ->Repetitions(9)
    ->ReportAggregatesOnly(true)
    ->ComputeStatistics("max", [](const std::vector<double>& v) {
      return *std::max_element(v.begin(), v.end());
    });
BENCHMARK(BM_Cast640x480Clutter200BruteForce)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true);
BENCHMARK(BM_Cast160x120HallwayLoop)
    ->Unit(benchmark::kMillisecond)
    ->Repetitions(9)
    ->ReportAggregatesOnly(true);

BENCHMARK_MAIN();
