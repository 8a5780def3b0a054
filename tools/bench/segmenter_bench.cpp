// Speed of the EM segmenter (issue: 160x120 <= 1 ms, unorganized 640x480 <= 5 ms, one core;
// medians of 9 repetitions: the machine is shared).
// "Stream": one Segmenter over alternating frames, seeded by the previous one, as the service
// runs. "Cold": every frame from proposals alone.

#include <benchmark/benchmark.h>

#include <cmath>

#include "options_yaml.hpp"  // services/sim: the scenario's `sim` section
#include "relplane/pcd/pcd_reader.hpp"
#include "relplane/segmenter/segmenter.hpp"
#include "relplane/sim/simulation.hpp"
#include "synthetic_scene.hpp"

namespace {

using namespace relplane::segmenter;

// The office at σ = 1 cm seen from 1 m high, `shift` metres along x and turned `yaw` radians.
Cloud OfficeView(int width, int height, double shift, double yaw, bool unorganized) {
  testing::Sensor s;
  s.width = width;
  s.height = height;
  s.sigma = 0.01;
  s.world_from_sensor =
      Eigen::Translation3d(shift, 0, 1.0) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ());
  const auto world = testing::Office();
  return unorganized ? testing::RenderUnorganized(world, s).cloud : testing::Render(world, s).cloud;
}

// Two nearby views of the office, so a stream sees a moving sensor.
std::vector<Cloud> OfficeFrames(int width, int height, bool unorganized) {
  return {OfficeView(width, height, 0.0, 0.0, unorganized),
          OfficeView(width, height, 0.05, 0.02, unorganized)};
}

// A smooth path through the office at walking pace seen at 30 Hz (1 cm and 0.2 degrees a
// frame), there and back, so the stream never jumps: the sensor's views in order.
std::vector<Cloud> OfficePath(int width, int height) {
  constexpr int kSteps = 10;
  std::vector<Cloud> views;
  for (int k = 0; k < kSteps; ++k) {
    views.push_back(OfficeView(width, height, 0.01 * k, 0.0035 * k, false));
  }
  std::vector<Cloud> frames = views;
  for (int k = kSteps - 2; k > 0; --k) frames.push_back(views[k]);
  return frames;
}

void Run(benchmark::State& state, const std::vector<Cloud>& frames, const Options& options,
         bool cold) {
  Segmenter segmenter(options);
  size_t k = 0, planes = 0;
  for (auto _ : state) {
    if (cold) segmenter.Reset();
    const Result r = segmenter.Segment(frames[k++ % frames.size()]);
    planes = r.planes.size();
    benchmark::DoNotOptimize(planes);
  }
  state.counters["points"] = static_cast<double>(frames[0].size());
  state.counters["planes"] = static_cast<double>(planes);
}

void BM_Synthetic160x120Stream(benchmark::State& state) {
  static const auto frames = OfficeFrames(160, 120, false);
  Run(state, frames, Options{}, false);
}
// The same office along a smooth path: seeds from the previous frame hold, as in the service.
void BM_Synthetic160x120Path(benchmark::State& state) {
  static const auto frames = OfficePath(160, 120);
  Run(state, frames, Options{}, false);
}
void BM_Synthetic160x120Cold(benchmark::State& state) {
  static const auto frames = OfficeFrames(160, 120, false);
  Run(state, frames, Options{}, true);
}
void BM_Unorganized640x480Stream(benchmark::State& state) {
  static const auto frames = OfficeFrames(640, 480, true);
  Run(state, frames, Options{}, false);
}
void BM_Unorganized640x480Cold(benchmark::State& state) {
  static const auto frames = OfficeFrames(640, 480, true);
  Run(state, frames, Options{}, true);
}

// Between the two: the same office, organized 640x480 (image order kept) and unorganized
// 320x240.
void BM_Organized640x480Stream(benchmark::State& state) {
  static const auto frames = OfficeFrames(640, 480, false);
  Run(state, frames, Options{}, false);
}
void BM_Unorganized320x240Stream(benchmark::State& state) {
  static const auto frames = OfficeFrames(320, 240, true);
  Run(state, frames, Options{}, false);
}

std::vector<Cloud> KinectFrames() {
  std::vector<Cloud> frames;
  for (const char* name : {"frame_20121214T142255.814212.pcd", "frame_20121214T142256.068683.pcd",
                           "frame_20121214T142256.332395.pcd"}) {
    auto pcd = relplane::pcd::ReadPcd(std::string(RELPLANE_SHARED_DIR "/data/kinect/") + name);
    relplane::pcd::OpticalToSensor(&pcd);
    Cloud c;
    c.x = pcd.x;
    c.y = pcd.y;
    c.z = pcd.z;
    frames.push_back(std::move(c));
  }
  return frames;
}

Options KinectOptions() {  // as services/segmenter/kinect.yaml
  Options o;
  o.noise.sigma_max = 0.007f;
  o.noise.range_noise = 0.003f;
  return o;
}

void BM_Kinect640x480Stream(benchmark::State& state) {
  static const auto frames = KinectFrames();
  Run(state, frames, KinectOptions(), false);
}
void BM_Kinect640x480Cold(benchmark::State& state) {
  static const auto frames = KinectFrames();
  Run(state, frames, KinectOptions(), true);
}

// loop_other_sensor at σ = 1 cm (200 x 150, 70 degrees), noise seed 41, frames 40-80: a
// pilaster 4-3 m ahead whose front is seen at a grazing angle, a third of whose frames lean
// between the front and its side (DominantLineFit: the line fit, then the frame assigned and
// described again).
std::vector<Cloud> PilasterFrames() {
  relplane::sim::ServiceOptions options = relplane::sim::LoadServiceOptions(
      std::string(RELPLANE_SOURCE_DIR) + "/scenarios/loop_other_sensor.yaml");
  options.sim.sensor.noise_sigma = 0.01;
  options.sim.sensor.seed = 41;
  relplane::sim::Simulation simulation(options.sim);
  std::vector<Cloud> frames;
  for (int64_t k = 40; k <= 80; ++k) {
    Cloud c;
    for (const auto& p : simulation.Frame(k).points) c.Add(p);
    frames.push_back(std::move(c));
  }
  return frames;
}
void BM_Pilaster200x150Path(benchmark::State& state) {
  static const auto frames = PilasterFrames();
  Run(state, frames, Options{}, false);
}

// scenarios/office.yaml as the pipeline bench plays it (160x120, its own noise and route),
// frames 0-299 in order: what the segmenter service does per frame. `describes` is the mean
// number of assign-and-describe passes per frame (1 when no mixture plane is dropped or
// refitted after the first).
void BM_OfficeScenario160x120(benchmark::State& state) {
  static const auto frames = [] {
    const auto options = relplane::sim::LoadServiceOptions(std::string(RELPLANE_SOURCE_DIR) +
                                                           "/scenarios/office.yaml");
    relplane::sim::Simulation simulation(options.sim);
    std::vector<Cloud> out;
    for (int64_t k = 0; k < 300; ++k) {
      Cloud c;
      for (const auto& p : simulation.Frame(k).points) c.Add(p);
      out.push_back(std::move(c));
    }
    return out;
  }();
  Segmenter segmenter(Options{});
  size_t k = 0;
  double describes = 0, frames_run = 0;
  for (auto _ : state) {
    const Result r = segmenter.Segment(frames[k++ % frames.size()]);
    describes += 1 + (r.pieceless_planes > 0) + (r.line_refits > 0) + (r.layer_planes > 0);
    ++frames_run;
  }
  state.counters["points"] = static_cast<double>(frames[0].size());
  state.counters["describes"] = describes / std::max(1.0, frames_run);
}

#define SEGMENTER_BENCHMARK(fn) \
  BENCHMARK(fn)->Unit(benchmark::kMillisecond)->Repetitions(9)->ReportAggregatesOnly(true)
SEGMENTER_BENCHMARK(BM_Synthetic160x120Stream);
SEGMENTER_BENCHMARK(BM_Synthetic160x120Path);
SEGMENTER_BENCHMARK(BM_Synthetic160x120Cold);
SEGMENTER_BENCHMARK(BM_Unorganized640x480Stream);
SEGMENTER_BENCHMARK(BM_Unorganized640x480Cold);
SEGMENTER_BENCHMARK(BM_Organized640x480Stream);
SEGMENTER_BENCHMARK(BM_Unorganized320x240Stream);
SEGMENTER_BENCHMARK(BM_Kinect640x480Stream);
SEGMENTER_BENCHMARK(BM_Kinect640x480Cold);
SEGMENTER_BENCHMARK(BM_Pilaster200x150Path);
SEGMENTER_BENCHMARK(BM_OfficeScenario160x120);

}  // namespace

BENCHMARK_MAIN();
