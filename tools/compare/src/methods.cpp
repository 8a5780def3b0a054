#include "relplane/compare/methods.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace relplane::compare {
namespace {

using Clock = std::chrono::steady_clock;

MethodRun RunRelplane(segmenter::Segmenter* segmenter, const segmenter::Cloud& cloud) {
  const Clock::time_point start = Clock::now();
  segmenter::Result result = segmenter->Segment(cloud);
  MethodRun run;
  run.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  run.detections.planes = std::move(result.planes);
  run.detections.labels = std::move(result.labels);
  return run;
}

MethodRun FromPcl(const OrganizedFrame& grid, PclResult result) {
  MethodRun run;
  run.seconds = result.seconds;
  run.detections = Describe(grid.points, std::move(result.planes));
  return run;
}

}  // namespace

Methods::Methods(const MethodsOptions& options)
    : options_(options), stream_(options.relplane), alone_(options.relplane) {}

std::vector<std::string> Methods::Names() const {
  std::vector<std::string> names = {"relplane (stream)", "relplane (frame alone)", "PCL organized"};
  if (options_.run_sac) names.push_back("PCL SAC");
  return names;
}

std::vector<MethodRun> Methods::Run(const segmenter::Cloud& cloud, const OrganizedFrame& grid) {
  std::vector<MethodRun> runs;
  runs.push_back(RunRelplane(&stream_, cloud));
  alone_.Reset();
  runs.push_back(RunRelplane(&alone_, cloud));
  runs.push_back(FromPcl(grid, SegmentOrganized(grid, options_.organized)));
  if (options_.run_sac) {
    SacParams sac = options_.sac;
    sac.distance_threshold = SacThreshold(options_.camera, grid);
    runs.push_back(FromPcl(grid, SegmentSac(grid, sac)));
  }
  return runs;
}

double SacThreshold(const camera::DepthCameraModel& camera, const OrganizedFrame& grid) {
  std::vector<float> depths;  // sensor frame: depth is x
  for (float x : grid.points.x) {
    if (std::isfinite(x)) depths.push_back(x);
  }
  if (depths.empty()) return 0.02;
  auto middle = depths.begin() + static_cast<std::ptrdiff_t>(depths.size() / 2);
  std::nth_element(depths.begin(), middle, depths.end());
  return std::max(0.02, 3.0 * camera.ResolvedSigma(*middle));
}

}  // namespace relplane::compare
