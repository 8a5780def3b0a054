#include "relplane/accuracy/world_kind.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "relplane/mapper/observability.hpp"

namespace relplane::accuracy {
namespace {

using Eigen::Vector2d;

constexpr double kSigma = 0.01;     // m: a wall's line or end, as seen
constexpr double kEndReach = 0.15;  // m: a hit this close to a wall's end shows the end
constexpr double kMinHits = 3;      // rays on a wall for it to count

struct Wall {
  Vector2d a, b;
};

Vector2d Perp(const Vector2d& v) { return {-v.y(), v.x()}; }

// The walls at the sensor's height, seen from above.
std::vector<Wall> WallsAtHeight(const sim::World& world, double height) {
  std::vector<Wall> out;
  for (const sim::Rect& r : world.rects) {
    if (std::abs(r.Normal().z()) > 0.1) continue;  // floor, ceiling
    const double z0 = std::min(r.origin.z(), (r.origin + r.v).z());
    const double z1 = std::max(r.origin.z(), (r.origin + r.v).z());
    if (height < z0 || height > z1) continue;
    out.push_back({r.origin.head<2>(), (r.origin + r.u).head<2>()});
  }
  return out;
}

// Distance along the ray p + s d to the segment, or infinity.
double RayHit(const Vector2d& p, const Vector2d& d, const Wall& w) {
  const Vector2d e = w.b - w.a;
  const double denom = d.x() * e.y() - d.y() * e.x();
  if (std::abs(denom) < 1e-12) return std::numeric_limits<double>::infinity();
  const Vector2d ap = w.a - p;
  const double s = (ap.x() * e.y() - ap.y() * e.x()) / denom;
  const double u = (ap.x() * d.y() - ap.y() * d.x()) / denom;
  if (s <= 0.0 || u < 0.0 || u > 1.0) return std::numeric_limits<double>::infinity();
  return s;
}

bool FrameObservable(const std::vector<Wall>& walls, const geometry::Pose2& pose,
                     const sim::SensorOptions& sensor) {
  const Vector2d p = pose.Translation();
  const double half_fov = 0.5 * sensor.hfov_deg * M_PI / 180.0;
  const int rays = std::max(2, static_cast<int>(std::ceil(sensor.hfov_deg)));
  std::vector<std::vector<Vector2d>> hits(walls.size());
  for (int k = 0; k <= rays; ++k) {
    const double bearing = pose.yaw - half_fov + 2.0 * half_fov * k / rays;
    const Vector2d d(std::cos(bearing), std::sin(bearing));
    double best = sensor.max_range;
    int hit = -1;
    for (size_t w = 0; w < walls.size(); ++w) {
      const double s = RayHit(p, d, walls[w]);
      if (s < best) best = s, hit = static_cast<int>(w);
    }
    if (hit >= 0) hits[static_cast<size_t>(hit)].push_back(p + best * d);
  }
  std::vector<mapper::PoseConstraint> constraints;
  for (size_t w = 0; w < walls.size(); ++w) {
    if (hits[w].size() < kMinHits) continue;
    const Vector2d t = (walls[w].b - walls[w].a).normalized();
    const Vector2d n = Perp(t);
    Vector2d mid = Vector2d::Zero();
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Vector2d& h : hits[w]) {
      mid += h / static_cast<double>(hits[w].size());
      const double s = t.dot(h - walls[w].a);
      lo = std::min(lo, s), hi = std::max(hi, s);
    }
    // The line: n . (p + R m) = n . P, levered in yaw by where it is seen.
    constraints.push_back({{n.x(), n.y(), n.dot(Perp(mid - p))}, kSigma});
    // Its orientation: a line fitted over length L through k points (slope variance
    // 12 sigma^2 / (k L^2)).
    const double length = std::max(hi - lo, 1e-3);
    const double sigma_yaw =
        kSigma * std::sqrt(12.0 / static_cast<double>(hits[w].size())) / length;
    constraints.push_back({Eigen::Vector3d::UnitZ(), std::max(sigma_yaw, 1e-3)});
    // Its ends, where a hit lies close to one.
    const double wall_length = (walls[w].b - walls[w].a).norm();
    for (const auto& [end, at] : {std::pair{walls[w].a, 0.0}, std::pair{walls[w].b, wall_length}}) {
      if (std::min(std::abs(lo - at), std::abs(hi - at)) > kEndReach) continue;
      constraints.push_back({{t.x(), t.y(), t.dot(Perp(end - p))}, kSigma});
    }
  }
  return mapper::AnalyseObservability(constraints).FullyConstrained();
}

}  // namespace

WorldKind ClassifyWorld(const sim::Simulation& simulation) {
  const sim::SensorOptions& sensor = simulation.Options().sensor;
  const std::vector<Wall> walls = WallsAtHeight(simulation.GetWorld(), sensor.mount_height);
  WorldKind kind;
  int64_t stretch = 0;
  for (int64_t k = 0; k < simulation.NumIterations(); ++k) {
    ++kind.frames;
    if (FrameObservable(walls, simulation.PlanarPose(k), sensor)) {
      stretch = 0;
      continue;
    }
    ++kind.unobservable_frames;
    kind.unobservable.push_back(k);
    kind.longest_stretch = std::max(kind.longest_stretch, ++stretch);
  }
  kind.longest_stretch_s = static_cast<double>(kind.longest_stretch) / simulation.Options().rate_hz;
  return kind;
}

}  // namespace relplane::accuracy
