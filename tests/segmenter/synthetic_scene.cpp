#include "synthetic_scene.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace relplane::segmenter::testing {
namespace {

Rect Box(Eigen::Vector3d corner, Eigen::Vector3d u, Eigen::Vector3d v) { return {corner, u, v}; }

double Gaussian(std::mt19937* rng) {  // Box-Muller: the same numbers on every platform
  const double u1 = ((*rng)() + 1.0) / 4294967297.0;
  const double u2 = (*rng)() / 4294967296.0;
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

bool OnRect(const Rect& r, const Eigen::Vector3d& p, double margin) {
  const Eigen::Vector3d q = p - r.corner;
  const double s = q.dot(r.edge_u) / r.edge_u.norm();
  const double t = q.dot(r.edge_v) / r.edge_v.norm();
  return s > -margin && s < r.edge_u.norm() + margin && t > -margin && t < r.edge_v.norm() + margin;
}

}  // namespace

Scan Render(const std::vector<Rect>& world, const Sensor& sensor) {
  Scan scan;
  std::mt19937 rng(sensor.seed);
  const double f = 0.5 * sensor.width / std::tan(0.5 * sensor.hfov_deg * M_PI / 180.0);
  const Eigen::Vector3d origin = sensor.world_from_sensor.translation();
  const Eigen::Matrix3d rot = sensor.world_from_sensor.rotation();
  for (int r = 0; r < sensor.height; ++r) {
    for (int c = 0; c < sensor.width; ++c) {
      const Eigen::Vector3d ray_s = Eigen::Vector3d(1.0, -(c + 0.5 - 0.5 * sensor.width) / f,
                                                    -(r + 0.5 - 0.5 * sensor.height) / f)
                                        .normalized();
      const Eigen::Vector3d ray = rot * ray_s;
      double best = sensor.max_range;
      int hit = -1;
      for (size_t k = 0; k < world.size(); ++k) {
        const Rect& rect = world[k];
        const Eigen::Vector3d n = rect.edge_u.cross(rect.edge_v);
        const double denom = n.dot(ray);
        if (std::fabs(denom) < 1e-12) continue;
        const double t = n.dot(rect.corner - origin) / denom;
        if (t <= 0.05 || t >= best) continue;
        const Eigen::Vector3d q = origin + t * ray - rect.corner;
        const double s = q.dot(rect.edge_u) / rect.edge_u.squaredNorm();
        const double v = q.dot(rect.edge_v) / rect.edge_v.squaredNorm();
        if (s < 0 || s > 1 || v < 0 || v > 1) continue;
        best = t;
        hit = static_cast<int>(k);
      }
      if (hit < 0) continue;
      const double range = best + (sensor.sigma > 0 ? sensor.sigma * Gaussian(&rng) : 0.0);
      scan.cloud.Add((range * ray_s).cast<float>());
      scan.hit.push_back(hit);
    }
  }
  return scan;
}

Scan RenderUnorganized(const std::vector<Rect>& world, const Sensor& sensor) {
  const Scan ordered = Render(world, sensor);
  std::vector<size_t> order(ordered.hit.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::mt19937 rng(sensor.seed + 1);
  for (size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[rng() % i]);
  Scan scan;
  for (size_t i : order) {
    scan.cloud.Add(ordered.cloud.Point(i));
    scan.hit.push_back(ordered.hit[i]);
  }
  return scan;
}

std::vector<Rect> Hallway() {
  const double l = 12.0, w = 2.0, h = 2.5;
  return {
      Box({-1, -w / 2, 0}, {l, 0, 0}, {0, w, 0}),        // floor
      Box({-1, -w / 2, h}, {0, w, 0}, {l, 0, 0}),        // ceiling
      Box({-1, -w / 2, 0}, {0, 0, h}, {l, 0, 0}),        // right wall (y = -1)
      Box({-1, w / 2, 0}, {3.5, 0, 0}, {0, 0, h}),       // left wall before the door
      Box({3.4, w / 2, 0}, {l - 4.4, 0, 0}, {0, 0, h}),  // left wall after a 0.9 m door
      Box({l - 1, -w / 2, 0}, {0, w, 0}, {0, 0, h}),     // end wall
  };
}

std::vector<Rect> Office() {
  return {
      Box({-1, -2.5, 0}, {6, 0, 0}, {0, 5, 0}),         // floor
      Box({-1, -2.5, 2.6}, {0, 5, 0}, {6, 0, 0}),       // ceiling
      Box({5, -2.5, 0}, {0, 5, 0}, {0, 0, 2.6}),        // front wall
      Box({-1, 2.5, 0}, {6, 0, 0}, {0, 0, 2.6}),        // left wall
      Box({-1, -2.5, 0}, {0, 0, 2.6}, {6, 0, 0}),       // right wall
      Box({3.0, -0.5, 0}, {0, 1.0, 0}, {0, 0, 0.9}),    // cabinet front
      Box({3.0, -0.5, 0.9}, {0, 1.0, 0}, {0.8, 0, 0}),  // cabinet top
      Box({3.0, 0.5, 0}, {0.8, 0, 0}, {0, 0, 0.9}),     // cabinet left side
  };
}

void TruePlane(const Rect& rect, const Eigen::Isometry3d& world_from_sensor,
               Eigen::Vector3d* normal, double* d) {
  const Eigen::Isometry3d sensor_from_world = world_from_sensor.inverse();
  Eigen::Vector3d n = sensor_from_world.rotation() * rect.edge_u.cross(rect.edge_v).normalized();
  const Eigen::Vector3d p = sensor_from_world * rect.corner;
  double offset = -n.dot(p);
  if (offset < 0) {
    n = -n;
    offset = -offset;
  }
  *normal = n;
  *d = offset;
}

Score Evaluate(const std::vector<DetectedPlane>& planes, const std::vector<Rect>& world,
               const Scan& scan, const Sensor& sensor, int min_points) {
  Score score;
  score.detected = static_cast<int>(planes.size());
  std::vector<int> hits(world.size(), 0);
  for (int h : scan.hit) ++hits[h];
  auto matches = [&](const DetectedPlane& p, size_t k, double* angle, double* offset) {
    Eigen::Vector3d n;
    double d;
    TruePlane(world[k], sensor.world_from_sensor, &n, &d);
    const Eigen::Vector3d pn = p.normal.cast<double>();
    *angle = std::atan2(n.cross(pn).norm(), n.dot(pn)) * 180.0 / M_PI;  // exact near 0
    *offset = std::fabs(d - p.d);
    const Eigen::Vector3d c = sensor.world_from_sensor * p.centroid.cast<double>();
    return *angle < 5.0 && *offset < 0.1 && OnRect(world[k], c, 0.2);
  };
  std::vector<double> angles, offsets;
  for (const DetectedPlane& p : planes) {
    for (size_t k = 0; k < world.size(); ++k) {
      double a, o;
      if (matches(p, k, &a, &o)) {
        ++score.correct;
        break;
      }
    }
  }
  for (size_t k = 0; k < world.size(); ++k) {
    if (hits[k] < min_points) continue;
    ++score.true_planes;
    for (const DetectedPlane& p : planes) {  // planes come in order of decreasing support
      double a, o;
      if (matches(p, k, &a, &o)) {
        ++score.recalled;
        angles.push_back(a);
        offsets.push_back(o);
        break;
      }
    }
  }
  score.median_angle_deg = Median(angles);
  score.median_offset_m = Median(offsets);
  return score;
}

}  // namespace relplane::segmenter::testing
