#include "relplane/accuracy/plane_errors.hpp"

#include <cmath>
#include <cstdio>

namespace relplane::accuracy {
namespace {

// A grazing face's fit can lean several degrees towards a crossing face (dominant_line.hpp):
// still its sighting.
constexpr double kMaxAngleDeg = 10.0;
constexpr double kMaxOffset = 0.12;  // m, centroid to the true plane
constexpr double kEndMargin = 0.1;   // m, centroid past the true wall's ends
constexpr double kVerticalNz = 0.3;  // |normal z| of a wall's fit

// A true wall's horizontal extent, seen from above: its first corner, the unit direction to the
// farthest one from it (the corners go round the rectangle, two at each end) and its length.
struct Extent {
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  Eigen::Vector2d along = Eigen::Vector2d::UnitX();
  double length = 0.0;
};

Extent ExtentOf(const sim::TruePlane& wall) {
  Extent e;
  e.start = wall.corners[0].head<2>();
  for (const Eigen::Vector3d& c : wall.corners) {
    const double d = (c.head<2>() - e.start).norm();
    if (d > e.length) {
      e.length = d;
      e.along = (c.head<2>() - e.start) / d;
    }
  }
  return e;
}

}  // namespace

std::vector<PlaneError> PlaneErrors(int64_t seq, const Eigen::Isometry3d& sensor,
                                    const std::vector<segmenter::DetectedPlane>& detections,
                                    const std::vector<sim::TruePlane>& walls) {
  std::vector<PlaneError> out;
  const double cos_max = std::cos(kMaxAngleDeg * M_PI / 180.0);
  const Eigen::Vector3d eye = sensor.translation();
  std::vector<Extent> extents;
  for (const sim::TruePlane& wall : walls) extents.push_back(ExtentOf(wall));
  for (const segmenter::DetectedPlane& detection : detections) {
    const Eigen::Vector3d normal = sensor.rotation() * detection.normal.cast<double>();
    const Eigen::Vector3d centroid = sensor * detection.centroid.cast<double>();
    if (std::abs(normal.z()) > kVerticalNz) continue;
    int best = -1;
    double best_offset = kMaxOffset;
    for (size_t k = 0; k < walls.size(); ++k) {
      const sim::TruePlane& wall = walls[k];
      if (std::abs(normal.dot(wall.normal)) < cos_max || extents[k].length <= 0.0) continue;
      const double offset = std::abs(wall.normal.dot(centroid) + wall.d);
      const double s = extents[k].along.dot(centroid.head<2>() - extents[k].start);
      if (offset >= best_offset || s < -kEndMargin || s > extents[k].length + kEndMargin) continue;
      best = static_cast<int>(k);
      best_offset = offset;
    }
    if (best < 0) continue;
    // The true plane's normal turned towards the sensor: positive distances are nearer to it.
    Eigen::Vector3d n = walls[best].normal;
    double d = walls[best].d;
    if (n.dot(eye) + d < 0.0) n = -n, d = -d;
    const Eigen::Vector3d foot = eye - (n.dot(eye) + d) * n;
    PlaneError e;
    e.seq = seq;
    e.true_id = walls[best].id;
    e.true_length_m = extents[best].length;
    e.range_m = (centroid - eye).head<2>().norm();
    e.points = detection.num_points;
    e.centroid_error_m = n.dot(centroid) + d;
    // Along n from the foot (on the true plane) to the fitted plane through the centroid:
    // normal . (foot + t n - centroid) = 0.
    const double mn = normal.dot(n);
    e.foot_error_m = normal.dot(centroid - foot) / mn;  // |mn| >= cos_max
    e.normal_error_deg = std::atan2(n.cross(normal).norm(), std::abs(mn)) * 180.0 / M_PI;
    e.rms_m = detection.rms;
    const Eigen::Vector2d across = Eigen::Vector2d(-normal.y(), normal.x()).normalized();
    double lo = 0.0, hi = 0.0;
    for (size_t v = 0; v < detection.vertices.size(); ++v) {
      const double s = across.dot((sensor * detection.vertices[v].cast<double>()).head<2>());
      lo = v == 0 ? s : std::min(lo, s);
      hi = v == 0 ? s : std::max(hi, s);
    }
    e.length_m = hi - lo;
    out.push_back(e);
  }
  return out;
}

std::string PlaneErrorsCsv(const std::vector<PlaneError>& errors) {
  std::string out =
      "seq,true_id,true_length_m,range_m,points,centroid_error_m,foot_error_m,normal_error_deg,"
      "rms_m,length_m\n";
  char line[200];
  for (const PlaneError& e : errors) {
    std::snprintf(line, sizeof line, "%lld,%d,%.3f,%.3f,%d,%.5f,%.5f,%.4f,%.5f,%.3f\n",
                  static_cast<long long>(e.seq), e.true_id, e.true_length_m, e.range_m, e.points,
                  e.centroid_error_m, e.foot_error_m, e.normal_error_deg, e.rms_m, e.length_m);
    out += line;
  }
  return out;
}

}  // namespace relplane::accuracy
