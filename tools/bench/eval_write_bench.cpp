// How long the logger's periodic rewrite of the run folder takes (metrics + six files) as a run
// grows: it must stay well under the 1 s flush period.
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>

#include "relplane/eval/run_recorder.hpp"

namespace {

using namespace relplane::eval;

PlaneRecord Wall(int64_t id, Eigen::Vector2d a, Eigen::Vector2d b) {
  PlaneRecord p;
  p.id = id;
  const Eigen::Vector2d dir = (b - a).normalized();
  p.normal = Eigen::Vector3d(-dir.y(), dir.x(), 0.0);
  p.d = -p.normal.head<2>().dot(a);
  p.vertices = {{a.x(), a.y(), 0}, {b.x(), b.y(), 0}, {b.x(), b.y(), 2.5}, {a.x(), a.y(), 2.5}};
  return p;
}

// A corridor of 2 m wide, 20 walls per side of 2 m each, driven along its centre line.
void Fill(RunRecorder& recorder, int poses) {
  MapSnapshot world;
  for (int i = 0; i < 20; ++i) {
    world.planes.push_back(Wall(2 * i, {2.0 * i, -1}, {2.0 * i + 2, -1}));
    world.planes.push_back(Wall(2 * i + 1, {2.0 * i + 2, 1}, {2.0 * i, 1}));
  }
  MapSnapshot map = world;
  for (int g = 0; g < 10; ++g) map.groups.push_back({g, 4 * g, {4 * g, 4 * g + 1, 4 * g + 2}});
  recorder.OnWorld(world, 0);
  recorder.OnMap(map, 0);
  for (int i = 0; i < poses; ++i) {
    PoseSample t;
    t.seq = i;
    t.utime = i * 33333;
    t.position = {40.0 * i / poses, 0.1 * std::sin(0.01 * i), 1.0};
    recorder.OnTruth(t, i * 33333);
    t.position.x() += 0.01;
    recorder.OnPose(t, i * 33333 + 10000);
  }
}

void BM_RunFolderWrite(benchmark::State& state) {
  const std::string dir = (std::filesystem::temp_directory_path() / "relplane-eval-bench").string();
  std::filesystem::create_directories(dir);
  RunRecorder recorder(dir, EvalOptions{}, {}, "bench");
  Fill(recorder, static_cast<int>(state.range(0)));
  std::string reason;
  for (auto _ : state) {
    if (!recorder.Write(&reason)) state.SkipWithError(reason.c_str());
  }
  state.SetLabel(std::to_string(state.range(0)) + " poses, 40 walls");
}
BENCHMARK(BM_RunFolderWrite)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
