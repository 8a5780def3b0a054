#include "relplane/plane_truth/sim_truth.hpp"

#include <cmath>
#include <utility>

namespace relplane::plane_truth {
namespace {

constexpr int kMinPoints = 300;
constexpr double kMaxAngleDeg = 5.0;
constexpr double kMaxOffset = 0.1;
constexpr double kMargin = 0.05;  // overlaps must be deeper than this

// Angle (degrees) and offset between a detection (sensor frame) and a true plane (world
// frame); true when they match.
bool Match(const segmenter::DetectedPlane& p, const sim::TruePlane& t,
           const Eigen::Isometry3d& pose, double* angle, double* offset) {
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

// What the camera resolves along a detection's normal at its centroid: the depth noise moves a
// point along its ray, by the depth's change over the ray's depth per unit length.
double CameraNoiseAlongNormal(const camera::DepthCameraModel& camera,
                              const segmenter::DetectedPlane& p) {
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

}  // namespace

// A wall with a door and a lintel is one connected surface, seen as one plane that covers three
// true rectangles: overlapping, not containing, is the test.
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

segmenter::Cloud CloudOf(const sim::Scan& scan) {
  segmenter::Cloud cloud;
  cloud.Reserve(scan.points.size());
  for (const auto& p : scan.points) cloud.Add(p);
  return cloud;
}

SimScorer::SimScorer(std::vector<sim::TruePlane> truth, camera::DepthCameraModel camera)
    : truth_(std::move(truth)), camera_(std::move(camera)) {}

void SimScorer::AddFrame(const sim::Scan& scan, const Eigen::Isometry3d& pose,
                         const std::vector<segmenter::DetectedPlane>& planes,
                         AccuracyTally* tally) const {
  tally->AddFrame();
  int correct = 0;
  for (const auto& p : planes) {
    const double floor = CameraNoiseAlongNormal(camera_, p);
    if (floor > 0.0) tally->AddRmsToCamera(p.rms / floor);
    const Eigen::Vector3d normal = p.normal.cast<double>(), centroid = p.centroid.cast<double>();
    if (centroid.norm() > 0.0) {
      tally->AddIncidence(std::acos(std::min(1.0, std::fabs(normal.dot(centroid.normalized())))) *
                          180.0 / M_PI);
    }
    double a, o;
    for (const auto& t : truth_) {
      if (Match(p, t, pose, &a, &o)) {
        ++correct;
        break;
      }
    }
  }
  tally->AddDetections(static_cast<int>(planes.size()), correct);
  std::vector<int> hits(truth_.size(), 0);
  for (size_t i = 0; i < scan.rects.size(); ++i) {
    const int r = scan.rects[i];
    if (r < 0 || r >= static_cast<int>(hits.size())) continue;
    // A camera's noise brings back some samples of a surface beyond its range: in view is
    // what lies within it.
    if (InView(camera_, truth_[static_cast<size_t>(r)], pose, scan.points[i])) ++hits[r];
  }
  for (size_t t = 0; t < truth_.size(); ++t) {
    if (hits[t] < kMinPoints) continue;
    bool recalled = false;
    for (const auto& p : planes) {
      double a, o;
      if (Match(p, truth_[t], pose, &a, &o)) {
        tally->AddRecalled(a, o);
        recalled = true;
        break;
      }
    }
    if (!recalled) tally->AddMissed();
  }
}

}  // namespace relplane::plane_truth
