#include "scenario_accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "options_yaml.hpp"  // services/sim: the scenario's `sim` section
#include "relplane/segmenter/segmenter.hpp"
#include "relplane/sim/simulation.hpp"

namespace relplane::segmenter::testing {
namespace {

constexpr int kMinPoints = 300;
constexpr double kMaxAngleDeg = 5.0;
constexpr double kMaxOffset = 0.1;
constexpr double kMargin = 0.05;  // overlaps must be deeper than this
// WallSightingErrorsDeg: a detection's centroid this close to the wall's plane, its normal within
// this angle of the wall's, is a sighting of it.
constexpr double kMaxCentroidOffset = 0.05;
constexpr double kMaxWallAngleDeg = 20.0;

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Whether the detection's extent (world frame) overlaps the rectangle: a wall with a door and
// a lintel is one connected surface, seen as one plane that covers three true rectangles.
bool Overlaps(const sim::TruePlane& t, const std::vector<Eigen::Vector3d>& extent) {
  if (extent.empty()) return false;
  const Eigen::Vector3d u = (t.corners[1] - t.corners[0]).normalized();
  const Eigen::Vector3d v = (t.corners[3] - t.corners[0]).normalized();
  const double lu = (t.corners[1] - t.corners[0]).norm();
  const double lv = (t.corners[3] - t.corners[0]).norm();
  double s_lo = 1e9, s_hi = -1e9, r_lo = 1e9, r_hi = -1e9;
  for (const auto& p : extent) {
    const double s = (p - t.corners[0]).dot(u), r = (p - t.corners[0]).dot(v);
    s_lo = std::min(s_lo, s);
    s_hi = std::max(s_hi, s);
    r_lo = std::min(r_lo, r);
    r_hi = std::max(r_hi, r);
  }
  return s_hi > kMargin && s_lo < lu - kMargin && r_hi > kMargin && r_lo < lv - kMargin;
}

// Angle (degrees) and offset between a detection (sensor frame) and a true plane (world
// frame); true when they match.
bool Match(const DetectedPlane& p, const sim::TruePlane& t, const Eigen::Isometry3d& pose,
           double* angle, double* offset) {
  const Eigen::Vector3d n_world = pose.rotation() * p.normal.cast<double>();
  const Eigen::Vector3d c_world = pose * p.centroid.cast<double>();
  std::vector<Eigen::Vector3d> extent;
  for (const auto& v : p.vertices) extent.push_back(pose * v.cast<double>());
  const double d_world = -n_world.dot(c_world);
  // Compare in the sensor frame: the true plane's normal oriented like the detection.
  Eigen::Vector3d tn = t.normal;
  double td = t.d;
  if (tn.dot(n_world) < 0) {
    tn = -tn;
    td = -td;
  }
  // atan2 of sine and cosine: acos loses angles below ~0.01 degrees to rounding.
  *angle = std::atan2(tn.cross(n_world).norm(), tn.dot(n_world)) * 180.0 / M_PI;
  // The offset seen from the sensor: distance of the sensor to each plane.
  const Eigen::Vector3d o = pose.translation();
  *offset = std::fabs((tn.dot(o) + td) - (n_world.dot(o) + d_world));
  return *angle < kMaxAngleDeg && *offset < kMaxOffset && Overlaps(t, extent);
}

Cloud CloudOf(const sim::Scan& scan) {
  Cloud cloud;
  cloud.Reserve(scan.points.size());
  for (const auto& p : scan.points) cloud.Add(p);
  return cloud;
}

// What the camera resolves along a detection's normal at its centroid: the depth noise moves a
// point along its ray, by the depth's change over the ray's depth per unit length.
double CameraNoiseAlongNormal(const camera::DepthCameraModel& camera, const DetectedPlane& p) {
  const Eigen::Vector3d c = p.centroid.cast<double>();
  if (!(c.x() > 0.0)) return 0.0;
  return camera.ResolvedSigma(c.x()) * std::abs(p.normal.cast<double>().dot(c / c.x()));
}

// Whether the true surface `t` lies within the camera's depth range on the ray of the point
// `p` (sensor frame) measured on it; always with the Gaussian sensor.
bool InView(const camera::DepthCameraModel& camera, const sim::TruePlane& t,
            const Eigen::Isometry3d& pose, const Eigen::Vector3f& p) {
  if (camera.name == "gaussian" || !(p.x() > 0.0f)) return true;
  const Eigen::Vector3d pixel = p.cast<double>() / static_cast<double>(p.x());
  const Eigen::Vector3d n = pose.rotation().transpose() * t.normal;
  const double d = t.normal.dot(pose.translation()) + t.d;
  const double depth = -d / n.dot(pixel);
  return depth >= camera.min_depth && depth <= camera.max_depth;
}

ScenarioAccuracy Measure(const sim::SimOptions& sim_options, const Options& segmenter_options,
                         int step) {
  sim::Simulation simulation(sim_options);
  const std::vector<sim::TruePlane> truth = simulation.TruePlanes();
  const camera::DepthCameraModel& camera = sim_options.sensor.camera;
  Segmenter segmenter(segmenter_options);
  ScenarioAccuracy acc;
  std::vector<double> floor_ratios;
  std::vector<double> angles, offsets;
  for (int64_t k = 0; k < simulation.NumIterations(); k += step) {
    const sim::Scan scan = simulation.Frame(k);
    const Eigen::Isometry3d pose = simulation.SensorPose(k);
    const Cloud cloud = CloudOf(scan);
    const Result result = segmenter.Segment(cloud);
    ++acc.frames;
    acc.detected += static_cast<int>(result.planes.size());
    for (const auto& p : result.planes) {
      const double floor = CameraNoiseAlongNormal(camera, p);
      if (floor > 0.0) floor_ratios.push_back(p.rms / floor);
      double a, o;
      for (const auto& t : truth) {
        if (Match(p, t, pose, &a, &o)) {
          ++acc.correct;
          break;
        }
      }
    }
    std::vector<int> hits(truth.size(), 0);
    for (size_t i = 0; i < scan.rects.size(); ++i) {
      const int r = scan.rects[i];
      if (r < 0 || r >= static_cast<int>(hits.size())) continue;
      // A camera's noise brings back some samples of a surface beyond its range: in view is
      // what lies within it.
      if (InView(camera, truth[static_cast<size_t>(r)], pose, scan.points[i])) ++hits[r];
    }
    for (size_t t = 0; t < truth.size(); ++t) {
      if (hits[t] < kMinPoints) continue;
      ++acc.true_planes;
      for (const auto& p : result.planes) {  // decreasing support: the best-supported match
        double a, o;
        if (Match(p, truth[t], pose, &a, &o)) {
          ++acc.recalled;
          angles.push_back(a);
          offsets.push_back(o);
          break;
        }
      }
    }
  }
  acc.median_angle_deg = Median(angles);
  acc.median_offset_m = Median(offsets);
  if (!floor_ratios.empty()) {
    acc.min_rms_to_camera = *std::min_element(floor_ratios.begin(), floor_ratios.end());
  }
  return acc;
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
    const Cloud cloud = CloudOf(scan);
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
    const Cloud cloud = CloudOf(scan);
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
          !Overlaps(*wall, extent)) {
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
