#include "ideal_segmenter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace relplane::mapper::testing {
namespace {

using Eigen::Vector2d;

double Cross(const Vector2d& u, const Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

// Clips s in [lo, hi] to f0 + s (f1 - f0) <= 0.
void ClipLinear(double f0, double f1, double* lo, double* hi) {
  if (f0 <= 0 && f1 <= 0) return;
  if (f0 > 0 && f1 > 0) {
    *lo = 1, *hi = 0;
    return;
  }
  const double s = f0 / (f0 - f1);
  if (f0 > 0)
    *lo = std::max(*lo, s);
  else
    *hi = std::min(*hi, s);
}

// Does the segment from the origin to p cross wall w (sensor frame) before p?
bool Blocked(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
  const Vector2d r = p, s = b - a;
  const double den = Cross(r, s);
  if (std::abs(den) < 1e-12) return false;
  const double t = Cross(a, s) / den;  // along the ray
  const double u = Cross(a, r) / den;  // along the wall
  return t > 1e-6 && t < 1.0 - 1e-6 && u >= 0.0 && u <= 1.0;
}

// The rays of the frustum's grid that hit the wall from p0 to p1 between heights z0 and z1
// (sensor frame): what a depth sensor's plane would count as its support.
int RaysOnWall(const Frustum& f, const Vector2d& p0, const Vector2d& p1, double z0, double z1) {
  const double az_step = f.hfov / f.columns, el_step = f.vfov / f.rows;
  const Vector2d s = p1 - p0;
  int rays = 0;
  for (int k = 0; k < f.columns; ++k) {
    const double az = -0.5 * f.hfov + (k + 0.5) * az_step;
    const Vector2d u(std::cos(az), std::sin(az));
    const double den = Cross(u, s);
    if (std::abs(den) < 1e-12) continue;
    const double r = Cross(p0, s) / den;  // horizontal range along the ray
    const double along = Cross(p0, u) / den;
    if (r <= 0.0 || along < 0.0 || along > 1.0) continue;
    // Rows whose elevation, at the grid's centres, lies between the wall's bottom and top.
    const double lo = (std::atan2(z0, r) + 0.5 * f.vfov) / el_step - 0.5;
    const double hi = (std::atan2(z1, r) + 0.5 * f.vfov) / el_step - 0.5;
    const int first = std::max(0, static_cast<int>(std::ceil(lo)));
    const int last = std::min(f.rows - 1, static_cast<int>(std::floor(hi)));
    rays += std::max(0, last - first + 1);
  }
  return rays;
}

}  // namespace

PlaneInput WallSeen(const Vector2d& p0, const Vector2d& p1) {
  PlaneInput in;
  Vector2d n(-(p1 - p0).y(), (p1 - p0).x());
  n.normalize();
  if (n.dot(p0) > 0) n = -n;
  in.normal = Eigen::Vector3d(n.x(), n.y(), 0);
  in.d = -n.dot(p0);
  in.centroid = Eigen::Vector3d(0.5 * (p0 + p1).x(), 0.5 * (p0 + p1).y(), 0);
  in.vertices = {
      {p0.x(), p0.y(), -1}, {p1.x(), p1.y(), -1}, {p1.x(), p1.y(), 1}, {p0.x(), p0.y(), 1}};
  return in;
}

IdealSegmenter::IdealSegmenter(World world, Frustum frustum, Noise noise)
    : world_(std::move(world)), frustum_(frustum), noise_(noise), rng_(noise.seed) {}

std::vector<PlaneInput> IdealSegmenter::Planes(const geometry::Pose2& pose) {
  std::vector<PlaneInput> out;
  for (auto& s : Observe(pose)) out.push_back(std::move(s.plane));
  return out;
}

std::vector<Seen> IdealSegmenter::Observe(const geometry::Pose2& pose) {
  const geometry::Pose2 inv = pose.Inverse();
  std::vector<std::pair<Vector2d, Vector2d>> local;
  for (const Wall& w : world_.walls) local.emplace_back(inv * w.a, inv * w.b);
  const double h = frustum_.hfov / 2.0;
  const Vector2d left(std::cos(h), std::sin(h)), right(std::cos(h), -std::sin(h));
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<Seen> seen;
  for (size_t i = 0; i < local.size(); ++i) {
    const Vector2d pa = local[i].first, pb = local[i].second, dir = pb - pa;
    double lo = 0.0, hi = 1.0;
    // Horizontal field of view: right of the left edge, left of the right edge.
    ClipLinear(Cross(left, pa), Cross(left, pb), &lo, &hi);
    ClipLinear(-Cross(right, pa), -Cross(right, pb), &lo, &hi);
    // Range: |pa + s dir|^2 <= r^2.
    const double qa = dir.squaredNorm(), qb = 2.0 * pa.dot(dir),
                 qc = pa.squaredNorm() - frustum_.range * frustum_.range;
    const double disc = qb * qb - 4 * qa * qc;
    if (disc <= 0) continue;
    lo = std::max(lo, (-qb - std::sqrt(disc)) / (2 * qa));
    hi = std::min(hi, (-qb + std::sqrt(disc)) / (2 * qa));
    if ((hi - lo) * std::sqrt(qa) < frustum_.min_length) continue;
    // Coarse occlusion: keep the longest unoccluded run of samples, refined by bisection.
    auto visible = [&](double s) {
      const Vector2d p = pa + s * dir;
      for (size_t j = 0; j < local.size(); ++j) {
        if (j != i && Blocked(p, local[j].first, local[j].second)) return false;
      }
      return true;
    };
    constexpr int kSamples = 64;
    int best_a = -1, best_b = -1, run_a = -1;
    for (int k = 0; k <= kSamples; ++k) {
      const bool v = visible(lo + (hi - lo) * k / kSamples);
      if (v && run_a < 0) run_a = k;
      if ((!v || k == kSamples) && run_a >= 0) {
        const int run_b = v ? k : k - 1;
        if (run_b - run_a > best_b - best_a) best_a = run_a, best_b = run_b;
        run_a = -1;
      }
    }
    if (best_a < 0) continue;
    auto refine = [&](double in, double out) {
      for (int it = 0; it < 40; ++it) {
        const double mid = 0.5 * (in + out);
        (visible(mid) ? in : out) = mid;
      }
      return in;
    };
    double s0 = lo + (hi - lo) * best_a / kSamples, s1 = lo + (hi - lo) * best_b / kSamples;
    if (best_a > 0) s0 = refine(s0, lo + (hi - lo) * (best_a - 1) / kSamples);
    if (best_b < kSamples) s1 = refine(s1, lo + (hi - lo) * (best_b + 1) / kSamples);
    const double len = (s1 - s0) * std::sqrt(qa);
    if (len < frustum_.min_length) continue;
    // The visible segment, with noise on the plane and its edges.
    Vector2d t = dir.normalized();
    Vector2d mid = pa + 0.5 * (s0 + s1) * dir;
    double l0 = -0.5 * len, l1 = 0.5 * len;
    if (noise_.angle > 0 || noise_.offset > 0 || noise_.edge > 0) {
      t = Eigen::Rotation2Dd(noise_.angle * gauss(rng_)) * t;
      Vector2d n(-t.y(), t.x());
      mid += noise_.offset * gauss(rng_) * n;
      l0 += noise_.edge * gauss(rng_);
      l1 += noise_.edge * gauss(rng_);
    }
    Vector2d n(-t.y(), t.x());
    if (n.dot(mid) > 0) n = -n;  // towards the sensor: n . 0 + d > 0 with d = -n . mid
    const Vector2d e0 = mid + l0 * t, e1 = mid + l1 * t;
    const double z0 = world_.walls[i].z0 - frustum_.height,
                 z1 = world_.walls[i].z1 - frustum_.height;
    Seen s;
    s.wall = static_cast<int>(i);
    s.plane.normal = Eigen::Vector3d(n.x(), n.y(), 0.0);
    s.plane.d = -n.dot(mid);
    s.plane.centroid = Eigen::Vector3d(mid.x(), mid.y(), 0.5 * (z0 + z1));
    s.plane.vertices = {
        {e0.x(), e0.y(), z0}, {e1.x(), e1.y(), z0}, {e1.x(), e1.y(), z1}, {e0.x(), e0.y(), z1}};
    s.plane.support = RaysOnWall(frustum_, pa + s0 * dir, pa + s1 * dir, z0, z1);
    s.plane.rms = noise_.offset;
    seen.push_back(std::move(s));
  }
  return seen;
}

std::vector<geometry::Pose2> Drive(const std::vector<Vector2d>& waypoints, double speed,
                                   double turn_rate, double rate_hz, int laps) {
  std::vector<Vector2d> route;
  for (int lap = 0; lap < laps; ++lap) {
    route.insert(route.end(), waypoints.begin(), waypoints.end());
  }
  if (laps > 1 || (laps == 1 && waypoints.size() > 2 &&
                   (waypoints.front() - waypoints.back()).norm() > 1e-9 && false)) {
  }
  if (laps >= 1 && waypoints.size() > 2) route.push_back(waypoints.front());
  std::vector<geometry::Pose2> poses;
  const double dt = 1.0 / rate_hz;
  Vector2d p = route.front();
  Vector2d d0 = route[1] - route[0];
  double yaw = std::atan2(d0.y(), d0.x());
  poses.push_back({p.x(), p.y(), yaw});
  for (size_t k = 1; k < route.size(); ++k) {
    const Vector2d d = route[k] - p;
    if (d.norm() < 1e-9) continue;
    const double target = std::atan2(d.y(), d.x());
    double turn = geometry::WrapAngle(target - yaw);
    while (std::abs(turn) > 1e-9) {
      const double step = std::clamp(turn, -turn_rate * dt, turn_rate * dt);
      yaw = geometry::WrapAngle(yaw + step);
      turn -= step;
      poses.push_back({p.x(), p.y(), yaw});
    }
    yaw = target;
    const double dist = d.norm();
    const int steps = std::max(1, static_cast<int>(std::ceil(dist / (speed * dt))));
    const Vector2d start = p;
    for (int s = 1; s <= steps; ++s) {
      p = start + d * (static_cast<double>(s) / steps);
      poses.push_back({p.x(), p.y(), yaw});
    }
  }
  return poses;
}

World StraightHallway(double length, double width) {
  const double x0 = -1.0, x1 = x0 + length, y = width / 2;
  return {"straight_hallway",
          {{{x0, y}, {x1, y}}, {{x0, -y}, {x1, -y}}, {{x1, -y}, {x1, y}}, {{x0, -y}, {x0, y}}}};
}

World HallwayWithDoors(double length, double width) {
  // Doors (1 m gaps) every 3 m on both sides, staggered; recessed 0.3 m by door jambs.
  World w{"hallway_doors", {}};
  const double x0 = -1.0, x1 = x0 + length, y = width / 2;
  for (int side = -1; side <= 1; side += 2) {
    double x = x0;
    const double offset = side > 0 ? 2.0 : 3.5;
    for (double door = x0 + offset; door + 1.0 < x1; door += 3.0) {
      w.walls.push_back({{x, side * y}, {door, side * y}});
      w.walls.push_back({{door, side * y}, {door, side * (y + 0.3)}});  // jamb
      w.walls.push_back({{door + 1.0, side * y}, {door + 1.0, side * (y + 0.3)}});
      x = door + 1.0;
    }
    w.walls.push_back({{x, side * y}, {x1, side * y}});
  }
  w.walls.push_back({{x1, -y}, {x1, y}});
  w.walls.push_back({{x0, -y}, {x0, y}});
  return w;
}

World Office() {
  // Two rooms side by side (6 m x 5 m each) and a third above the first, joined by 1.2 m doors
  // with 0.1 m jambs. Room A centred on the origin.
  World w{"office", {}};
  auto wall = [&](double ax, double ay, double bx, double by) {
    w.walls.push_back({{ax, ay}, {bx, by}});
  };
  // Outer walls, split where inner walls meet them (each piece is one room's wall).
  wall(-3, -2.5, 3, -2.5);
  wall(3, -2.5, 9, -2.5);
  wall(9, -2.5, 9, 2.5);
  wall(9, 2.5, 3, 2.5);
  wall(3, 2.5, 3, 7.5);
  wall(3, 7.5, -3, 7.5);
  wall(-3, 7.5, -3, 2.5);
  wall(-3, 2.5, -3, -2.5);
  // Wall between A and B (x = 3) with a door at y in [-0.6, 0.6].
  wall(3, -2.5, 3, -0.6);
  wall(3, 0.6, 3, 2.5);
  wall(2.9, -0.6, 3.1, -0.6);
  wall(2.9, 0.6, 3.1, 0.6);
  // Wall between A and C (y = 2.5) with a door at x in [-0.6, 0.6].
  wall(-3, 2.5, -0.6, 2.5);
  wall(0.6, 2.5, 3, 2.5);
  wall(-0.6, 2.4, -0.6, 2.6);
  wall(0.6, 2.4, 0.6, 2.6);
  return w;
}

// Appends the wall a -> b with door recesses (1 m wide, 0.3 m deep, on the side away from
// `inside`) every `spacing` metres; spacing <= 0: a plain wall.
void AddWallWithRecesses(const Vector2d& a, const Vector2d& b, const Vector2d& inside,
                         double spacing, World* w) {
  const double length = (b - a).norm();
  const Vector2d t = (b - a) / length;
  Vector2d out(-t.y(), t.x());
  if (out.dot(inside - a) > 0) out = -out;
  if (spacing <= 0 || length < spacing + 1.0) {
    w->walls.push_back({a, b});
    return;
  }
  double s = 0.0;
  for (double door = spacing; door + 1.0 < length - 0.5; door += spacing) {
    const Vector2d d0 = a + door * t, d1 = a + (door + 1.0) * t;
    w->walls.push_back({a + s * t, d0});
    w->walls.push_back({d0, d0 + 0.3 * out});
    w->walls.push_back({d0 + 0.3 * out, d1 + 0.3 * out});
    w->walls.push_back({d1 + 0.3 * out, d1});
    s = door + 1.0;
  }
  w->walls.push_back({a + s * t, b});
}

World HallwayLoop(double sx, double sy, double width, double recess_spacing) {
  // Outer rectangle from (-w/2, -w/2) to (sx - w/2, sy - w/2); inner from (w/2, w/2).
  const double a = width / 2;
  const double ox0 = -a, oy0 = -a, ox1 = sx - a, oy1 = sy - a;
  const double ix0 = a, iy0 = a, ix1 = sx - 3 * a, iy1 = sy - 3 * a;
  World w{recess_spacing > 0 ? "hallway_loop_recesses" : "hallway_loop", {}};
  const Vector2d centre(0.5 * (ox0 + ox1), 0.5 * (oy0 + oy1));
  const Vector2d o[4] = {{ox0, oy0}, {ox1, oy0}, {ox1, oy1}, {ox0, oy1}};
  for (int k = 0; k < 4; ++k) AddWallWithRecesses(o[k], o[(k + 1) % 4], centre, recess_spacing, &w);
  const Vector2d i[4] = {{ix0, iy0}, {ix1, iy0}, {ix1, iy1}, {ix0, iy1}};
  for (int k = 0; k < 4; ++k) w.walls.push_back({i[k], i[(k + 1) % 4]});
  return w;
}

RunResult Run(Mapper& mapper, IdealSegmenter& segmenter, const std::vector<geometry::Pose2>& poses,
              const OdometryFn& odometry) {
  RunResult r;
  double sum = 0.0, sum_yaw = 0.0;
  for (size_t k = 0; k < poses.size(); ++k) {
    const std::optional<OdometryIncrement> increment =
        odometry && k > 0 ? odometry(k) : std::nullopt;
    const PoseEstimate est =
        mapper.Process(static_cast<int64_t>(k), segmenter.Planes(poses[k]), increment);
    const double e = (est.pose.Translation() - poses[k].Translation()).norm();
    sum += e * e;
    const double ey = geometry::WrapAngle(est.pose.yaw - poses[k].yaw);
    sum_yaw += ey * ey;
    r.max_error = std::max(r.max_error, e);
    if (est.status == PoseStatus::kMotionModel) ++r.motion_model;
    if (est.status == PoseStatus::kLost) ++r.lost;
  }
  r.ate_rmse = std::sqrt(sum / poses.size());
  r.yaw_rmse = std::sqrt(sum_yaw / poses.size());
  // Map error: each mapped wall against the true wall it lies on.
  const World& world = segmenter.GetWorld();
  std::vector<std::vector<int>> per_wall(world.walls.size() * 2);
  for (const MappedPlane& m : mapper.Map().planes) {
    ++r.mapped;
    const Vector2d m0 = m.vertices[0].head<2>(), m1 = m.vertices[1].head<2>();
    int best = -1;
    double best_dist = 0.3;
    double best_angle = 0.0;
    for (size_t w = 0; w < world.walls.size(); ++w) {
      const geometry::Segment2 seg{world.walls[w].a, world.walls[w].b};
      const double angle = std::abs(
          std::asin(std::clamp(Cross(seg.Direction(), (m1 - m0).normalized()), -1.0, 1.0)));
      if (angle > 0.2) continue;
      const Vector2d n = seg.Normal();
      const double dist = std::max(std::abs(n.dot(m0 - seg.a)), std::abs(n.dot(m1 - seg.a)));
      // The mapped wall's middle must lie on the true wall (coplanar walls are distinct).
      if (seg.DistanceTo(0.5 * (m0 + m1)) > 0.3) continue;
      if (dist < best_dist) best = static_cast<int>(w), best_dist = dist, best_angle = angle;
    }
    if (best < 0) {
      ++r.unmatched;
      continue;
    }
    const geometry::Segment2 seg{world.walls[best].a, world.walls[best].b};
    const int side = seg.Normal().dot(m.normal.head<2>()) > 0 ? 1 : 0;
    per_wall[2 * best + side].push_back(static_cast<int>(m.id));
    r.angle_error = std::max(r.angle_error, best_angle);
    r.end_error = std::max(r.end_error, best_dist);  // perpendicular part
    // Ends the mapper claims (static edges seen) must be true wall ends.
    for (int e = 0; e < 2; ++e) {
      if (!m.end_known[e]) continue;
      const Vector2d end = e == 0 ? m0 : m1;
      const double de = std::min((end - seg.a).norm(), (end - seg.b).norm());
      r.end_error_any = std::max(r.end_error_any, de);
    }
  }
  for (size_t w = 0; w < per_wall.size(); ++w) {
    const auto& v = per_wall[w];
    if (v.size() < 2) continue;
    r.duplicates += static_cast<int>(v.size()) - 1;
    r.duplicate_ids += " wall " + std::to_string(w / 2) + ":";
    for (int id : v) r.duplicate_ids += " " + std::to_string(id);
  }
  return r;
}

std::string Describe(const RunResult& r) {
  char buf[400];
  std::snprintf(buf, sizeof(buf),
                "ATE %.4f m (max %.3f), yaw %.4f rad, walls %d (dup %d, unmatched %d), line err "
                "%.4f m, end err %.4f m, angle %.4f rad, motion model %d, lost %d",
                r.ate_rmse, r.max_error, r.yaw_rmse, r.mapped, r.duplicates, r.unmatched,
                r.end_error, r.end_error_any, r.angle_error, r.motion_model, r.lost);
  if (r.duplicates > 0) return buf + std::string(";") + r.duplicate_ids;
  return buf;
}

}  // namespace relplane::mapper::testing
