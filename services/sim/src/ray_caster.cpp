#include "relplane/sim/ray_caster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace relplane::sim {

namespace {

// Slack of the inside test in rectangle coordinates, so rays through the shared edge of two
// wall pieces never leak between them.
constexpr double kEdgeSlack = 1e-9;
// Absolute slack (metres) of the culling tests: far above rounding, far below any geometry.
constexpr double kCullSlack = 1e-6;
// Below this |sin| a column's ray counts as parallel to a wall's footprint.
constexpr double kMinSin = 1e-3;

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

double DistanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b) {
  const Eigen::Vector2d e = b - a;
  const double len2 = e.squaredNorm();
  const double f = len2 > 0.0 ? std::clamp((p - a).dot(e) / len2, 0.0, 1.0) : 0.0;
  return (a + f * e - p).norm();
}

}  // namespace

RayGrid RayGrid::Pinhole(int width, int height, double hfov, double vfov) {
  RayGrid grid;
  grid.width = width;
  grid.height = height;
  const double tan_h = std::tan(0.5 * hfov);
  const double tan_v = std::tan(0.5 * vfov);
  grid.column_directions.resize(width);
  for (int col = 0; col < width; ++col) {
    const double y = tan_h * (1.0 - (2.0 * col + 1.0) / width);  // leftmost column looks left
    grid.column_directions[col] = Eigen::Vector2d(1.0, y).normalized();
  }
  grid.directions.resize(static_cast<size_t>(width) * height);
  grid.horizontal.resize(grid.directions.size());
  for (int col = 0; col < width; ++col) {
    const double y = tan_h * (1.0 - (2.0 * col + 1.0) / width);
    for (int row = 0; row < height; ++row) {
      const double z = tan_v * (1.0 - (2.0 * row + 1.0) / height);  // top row looks up
      const size_t i = static_cast<size_t>(col) * height + row;
      grid.directions[i] = Eigen::Vector3d(1.0, y, z).normalized();
      grid.horizontal[i] = grid.directions[i].head<2>().norm();
    }
  }
  return grid;
}

RayCaster::RayCaster(const World& world) {
  rects_.reserve(world.rects.size());
  for (size_t i = 0; i < world.rects.size(); ++i) {
    const Rect& r = world.rects[i];
    Prepared p;
    p.normal = r.Normal();
    p.d = -p.normal.dot(r.origin);
    p.origin = r.origin;
    p.u_scaled = r.u / r.u.squaredNorm();
    p.v_scaled = r.v / r.v.squaredNorm();
    rects_.push_back(p);

    if (std::abs(p.normal.z()) >= 1e-9) {
      others_.push_back(static_cast<int>(i));
      continue;
    }
    // Seen from above a vertical rectangle is a segment along the plane's horizontal direction.
    const Eigen::Vector2d along = Eigen::Vector2d(-p.normal.y(), p.normal.x()).normalized();
    const std::vector<Eigen::Vector3d> corners = r.Corners();
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    Footprint f;
    f.rect = static_cast<int>(i);
    double thickness = 0.0;
    const Eigen::Vector2d base = corners[0].head<2>();
    for (const Eigen::Vector3d& c : corners) {
      const Eigen::Vector2d q = c.head<2>() - base;
      const double s = q.dot(along);
      if (s < lo) {
        lo = s;
        f.a = c.head<2>();
      }
      if (s > hi) {
        hi = s;
        f.b = c.head<2>();
      }
      thickness = std::max(thickness, std::abs(Cross(along, q)));
    }
    // The edge slack lets a hit lie up to kEdgeSlack * |u| (or |v|) past the edges.
    f.margin = kCullSlack + thickness + kEdgeSlack * (r.u.norm() + r.v.norm());
    f.z_min = std::numeric_limits<double>::infinity();
    f.z_max = -f.z_min;
    for (const Eigen::Vector3d& c : corners) {
      f.z_min = std::min(f.z_min, c.z() - f.margin);
      f.z_max = std::max(f.z_max, c.z() + f.margin);
    }
    walls_.push_back(f);
  }
}

// Inlined: it is the inner loop of both casting paths.
[[gnu::always_inline]] inline bool RayCaster::Intersect(const Prepared& r, const Eigen::Vector3d& o,
                                                        const Eigen::Vector3d& dir,
                                                        double max_range, double* t) {
  const double denom = r.normal.dot(dir);
  if (std::abs(denom) < 1e-12) return false;
  // Range checks before the division, which is the test's most expensive step:
  // 0 < num / denom <= max_range.
  const double num = -(r.normal.dot(o) + r.d);
  if (denom > 0.0 ? (num <= 0.0 || num > max_range * denom)
                  : (num >= 0.0 || num < max_range * denom)) {
    return false;
  }
  const double tt = num / denom;
  if (!(tt > 0.0 && tt <= max_range)) return false;
  const Eigen::Vector3d q = o + tt * dir - r.origin;
  const double a = q.dot(r.u_scaled);
  if (a < -kEdgeSlack || a > 1.0 + kEdgeSlack) return false;
  const double b = q.dot(r.v_scaled);
  if (b < -kEdgeSlack || b > 1.0 + kEdgeSlack) return false;
  *t = tt;
  return true;
}

// The tie rule: the nearer hit wins, and of two equally near the lower index.
[[gnu::always_inline]] inline void RayCaster::Consider(const Prepared& r, int index,
                                                       const Eigen::Vector3d& o,
                                                       const Eigen::Vector3d& dir, double max_range,
                                                       Hit* best) {
  double t;
  if (!Intersect(r, o, dir, max_range, &t)) return;
  if (best->rect < 0 || t < best->range || (t == best->range && index < best->rect)) {
    best->range = t;
    best->rect = index;
  }
}

Hit RayCaster::CastOneBruteForce(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                 double max_range) const {
  Hit best;
  for (size_t i = 0; i < rects_.size(); ++i) {
    Consider(rects_[i], static_cast<int>(i), origin, direction, max_range, &best);
  }
  return best;
}

void RayCaster::CastBruteForce(const Eigen::Vector3d& origin, double yaw, const RayGrid& grid,
                               double max_range, std::vector<Hit>* hits) const {
  const double cy = std::cos(yaw);
  const double sy = std::sin(yaw);
  hits->resize(grid.directions.size());
  for (size_t i = 0; i < grid.directions.size(); ++i) {
    (*hits)[i] = CastOneBruteForce(origin, RotateYaw(cy, sy, grid.directions[i]), max_range);
  }
}

void RayCaster::CullForFrame(const Eigen::Vector3d& origin, double yaw, const RayGrid& grid,
                             double max_range) {
  // Every ray of a grid whose directions all point forward (x > 0) hits only what lies in
  // front of the sensor.
  double min_forward = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& c : grid.column_directions)
    min_forward = std::min(min_forward, c.x());
  const bool forward_only = min_forward > 0.0;
  const Eigen::Vector2d o2 = origin.head<2>();
  const Eigen::Vector2d forward(std::cos(yaw), std::sin(yaw));

  frame_walls_.clear();
  for (const Footprint& f : walls_) {
    if (DistanceToSegment(o2, f.a, f.b) > max_range + f.margin) continue;
    if (forward_only && (f.a - o2).dot(forward) < -f.margin &&
        (f.b - o2).dot(forward) < -f.margin) {
      continue;
    }
    frame_walls_.push_back(&f);
  }
  frame_others_.clear();
  for (int i : others_) {
    // Distance from the origin to the rectangle: nothing further can be hit within range.
    const Prepared& r = rects_[i];
    const Eigen::Vector3d q = origin - r.origin;
    const double a = std::clamp(q.dot(r.u_scaled), 0.0, 1.0);
    const double b = std::clamp(q.dot(r.v_scaled), 0.0, 1.0);
    const Eigen::Vector3d u = r.u_scaled / r.u_scaled.squaredNorm();
    const Eigen::Vector3d v = r.v_scaled / r.v_scaled.squaredNorm();
    const Eigen::Vector3d nearest = r.origin + a * u + b * v;
    if ((nearest - origin).norm() > max_range + kCullSlack * (1.0 + max_range)) continue;
    frame_others_.push_back(i);
  }
}

void RayCaster::ColumnCandidates(const Eigen::Vector2d& o2, const Eigen::Vector2d& c) {
  column_.clear();
  for (const Footprint* f : frame_walls_) {
    const Eigen::Vector2d e = f->b - f->a;
    const double length = e.norm();
    const double den = Cross(c, e);
    if (std::abs(den) < kMinSin * length) {
      // Nearly parallel: fall back on the distance to the footprint as the lower bound.
      column_.push_back({std::max(0.0, DistanceToSegment(o2, f->a, f->b) - f->margin),
                         std::numeric_limits<double>::infinity(), f->z_min, f->z_max, f->rect});
      continue;
    }
    const Eigen::Vector2d w = f->a - o2;
    const double s = Cross(w, e) / den;
    const double along = Cross(w, c) / den * length;  // crossing point's distance from a
    const double sin_angle = std::abs(den) / length;
    // Sliding the crossing by `margin` along the wall moves it by margin / sin along the ray.
    const double slack = f->margin / sin_angle;
    if (along < -f->margin || along > length + f->margin || s < -slack) continue;
    column_.push_back({std::max(0.0, s - slack), s + slack, f->z_min, f->z_max, f->rect});
  }
  std::sort(column_.begin(), column_.end());
}

void RayCaster::Cast(const Eigen::Vector3d& origin, double yaw, const RayGrid& grid,
                     double max_range, std::vector<Hit>* hits) {
  const double cy = std::cos(yaw);
  const double sy = std::sin(yaw);
  hits->resize(grid.directions.size());
  CullForFrame(origin, yaw, grid, max_range);
  const Eigen::Vector2d o2 = origin.head<2>();
  for (int col = 0; col < grid.width; ++col) {
    const Eigen::Vector2d& cs = grid.column_directions[col];
    ColumnCandidates(o2, Eigen::Vector2d(cy * cs.x() - sy * cs.y(), sy * cs.x() + cy * cs.y()));
    for (int row = 0; row < grid.height; ++row) {
      const size_t index = static_cast<size_t>(col) * grid.height + row;
      const Eigen::Vector3d dir = RotateYaw(cy, sy, grid.directions[index]);
      Hit best;
      for (int i : frame_others_) Consider(rects_[i], i, origin, dir, max_range, &best);
      // Turning about z keeps the horizontal length; the bounds below use it only with slack
      // far above the rounding.
      const double horizontal = grid.horizontal[index];
      for (const Candidate& c : column_) {
        // A candidate whose nearest possible hit is beyond the best so far cannot win, nor can
        // any after it: they are sorted by that bound.
        if (best.rect >= 0 && c.s_low > best.range * horizontal) break;
        // Between s_low and s_high the ray rises from s_low * dir.z / horizontal to
        // s_high * dir.z / horizontal above the sensor; when that misses the wall's height
        // extent, so does the exact test. Compared times `horizontal`, without a division.
        if (c.s_high < std::numeric_limits<double>::infinity()) {
          const double rise_a = c.s_low * dir.z();
          const double rise_b = c.s_high * dir.z();
          if (std::max(rise_a, rise_b) < (c.z_min - origin.z()) * horizontal ||
              std::min(rise_a, rise_b) > (c.z_max - origin.z()) * horizontal) {
            continue;
          }
        }
        Consider(rects_[c.rect], c.rect, origin, dir, max_range, &best);
      }
      (*hits)[index] = best;
    }
  }
}

}  // namespace relplane::sim
