#include "scenario_accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "options_yaml.hpp"  // services/sim: the scenario's `sim` section
#include "relplane/plane_truth/sim_truth.hpp"
#include "relplane/segmenter/segmenter.hpp"
#include "relplane/sim/simulation.hpp"

namespace relplane::segmenter::testing {
namespace {

constexpr int kMinPoints = 300;  // as plane_truth::SimScorer counts a rectangle in view
// WallSightingErrorsDeg: a detection's centroid this close to the wall's plane, its normal within
// this angle of the wall's, is a sighting of it.
constexpr double kMaxCentroidOffset = 0.05;
constexpr double kMaxWallAngleDeg = 20.0;

ScenarioAccuracy Measure(const sim::SimOptions& sim_options, const Options& segmenter_options,
                         int step) {
  sim::Simulation simulation(sim_options);
  const plane_truth::SimScorer scorer(simulation.TruePlanes(), sim_options.sensor.camera);
  plane_truth::AccuracyTally tally;
  Segmenter segmenter(segmenter_options);
  for (int64_t k = 0; k < simulation.NumIterations(); k += step) {
    const sim::Scan scan = simulation.Frame(k);
    scorer.AddFrame(scan, simulation.SensorPose(k),
                    segmenter.Segment(plane_truth::CloudOf(scan)).planes, &tally);
  }
  return tally.Summary();
}

}  // namespace

ScenarioAccuracy MeasureScenario(const std::string& scenario_file, double noise_sigma, int step) {
  sim::ServiceOptions options = sim::LoadServiceOptions(scenario_file);
  options.sim.sensor.noise_sigma = noise_sigma;
  return Measure(options.sim, Options{}, step);
}

ScenarioAccuracy MeasureCameraScenario(const std::string& scenario_file, const Options& options,
                                       int step) {
  return Measure(sim::LoadServiceOptions(scenario_file).sim, options, step);
}

int FramesWithAWallTwice(const std::string& scenario_file, double noise_sigma, uint32_t seed,
                         int64_t first, int64_t last, const Options& options) {
  sim::ServiceOptions sim_options = sim::LoadServiceOptions(scenario_file);
  sim_options.sim.sensor.noise_sigma = noise_sigma;
  sim_options.sim.sensor.seed = seed;
  sim::Simulation simulation(sim_options.sim);
  Segmenter segmenter(options);
  const double cos_max = std::cos(20.0 * M_PI / 180.0);
  int frames = 0;
  for (int64_t k = first; k <= last && k < simulation.NumIterations(); ++k) {
    const sim::Scan scan = simulation.Frame(k);
    const Cloud cloud = plane_truth::CloudOf(scan);
    std::vector<DetectedPlane> walls;
    for (const DetectedPlane& p : segmenter.Segment(cloud).planes) {
      if (std::fabs(p.normal.z()) < 0.1f) walls.push_back(p);
    }
    bool twice = false;
    for (size_t i = 0; i < walls.size() && !twice; ++i) {
      for (size_t j = i + 1; j < walls.size() && !twice; ++j) {
        twice = walls[i].normal.dot(walls[j].normal) > cos_max &&
                (walls[i].centroid - walls[j].centroid).norm() < 0.1f;
      }
    }
    frames += twice;
  }
  return frames;
}

std::vector<WallSighting> WallSightings(const std::string& scenario_file, double noise_sigma,
                                        uint32_t seed, int64_t first, int64_t last,
                                        const Options& options, const Eigen::Vector2d& centroid) {
  sim::ServiceOptions sim_options = sim::LoadServiceOptions(scenario_file);
  sim_options.sim.sensor.noise_sigma = noise_sigma;
  sim_options.sim.sensor.seed = seed;
  sim::Simulation simulation(sim_options.sim);
  const std::vector<sim::TruePlane> truth = simulation.TruePlanes();
  const sim::TruePlane* wall = nullptr;
  for (const sim::TruePlane& t : truth) {
    if ((t.centroid.head<2>() - centroid).norm() < 0.05) wall = &t;
  }
  std::vector<WallSighting> sightings;
  if (wall == nullptr) return sightings;
  Segmenter segmenter(options);
  for (int64_t k = 0; k <= last && k < simulation.NumIterations(); ++k) {
    const sim::Scan scan = simulation.Frame(k);
    const Eigen::Isometry3d pose = simulation.SensorPose(k);
    const Cloud cloud = plane_truth::CloudOf(scan);
    const Result result = segmenter.Segment(cloud);
    if (k < first) continue;
    const auto index = static_cast<int>(wall - truth.data());
    if (std::count(scan.rects.begin(), scan.rects.end(), index) < kMinPoints / 2) continue;
    // The detection with its centroid on the wall: a leaning fit still passes through the
    // wall's samples, but its plane may pass the sensor 0.1 m or more off the wall's (Match).
    WallSighting sighting{std::numeric_limits<double>::infinity(), 0.0};
    for (const DetectedPlane& p : result.planes) {
      const Eigen::Vector3d n = pose.rotation() * p.normal.cast<double>();
      const Eigen::Vector3d c = pose * p.centroid.cast<double>();
      std::vector<Eigen::Vector3d> extent;
      for (const auto& v : p.vertices) extent.push_back(pose * v.cast<double>());
      if (std::abs(wall->normal.dot(c) + wall->d) > kMaxCentroidOffset ||
          std::abs(n.dot(wall->normal)) < std::cos(kMaxWallAngleDeg * M_PI / 180.0) ||
          !plane_truth::Overlaps(*wall, extent)) {
        continue;
      }
      sighting.angle_deg =
          std::atan2(wall->normal.cross(n).norm(), std::abs(wall->normal.dot(n))) * 180.0 / M_PI;
      const Eigen::Vector3d along = (wall->corners[1] - wall->corners[0]).normalized();
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (const auto& v : extent) {
        lo = std::min(lo, along.dot(v));
        hi = std::max(hi, along.dot(v));
      }
      sighting.length_m = hi - lo;
      break;
    }
    sightings.push_back(sighting);
  }
  return sightings;
}

}  // namespace relplane::segmenter::testing
