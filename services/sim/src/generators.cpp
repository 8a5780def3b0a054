#include "relplane/sim/generators.hpp"

#include <cmath>
#include <random>

#include "relplane/sim/world.hpp"

namespace relplane::sim {

namespace {

using Eigen::Vector2d;

// Walls around the axis-aligned box lo..hi, counter-clockwise seen from above.
void AddBox(const Vector2d& lo, const Vector2d& hi, double height, std::vector<Rect>* out) {
  const Vector2d c[4] = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
  for (int i = 0; i < 4; ++i) out->push_back(Rect::Wall(c[i], c[(i + 1) % 4], 0.0, height));
}

// A wall from a to b with a door of `p.door_width` in its middle: two wall pieces, a lintel
// above the opening and, when frame_depth > 0, a jamb across the wall at each side of it.
void AddWallWithDoor(const Vector2d& a, const Vector2d& b, const OfficeParams& p, double height,
                     std::vector<Rect>* out) {
  const double length = (b - a).norm();
  const Vector2d dir = (b - a) / length;
  const double half = 0.5 * std::min(p.door_width, length);
  const Vector2d d0 = a + (0.5 * length - half) * dir;
  const Vector2d d1 = a + (0.5 * length + half) * dir;
  const double door_height = std::min(p.door_height, height);
  if ((d0 - a).norm() > 0.0) out->push_back(Rect::Wall(a, d0, 0.0, height));
  if ((b - d1).norm() > 0.0) out->push_back(Rect::Wall(d1, b, 0.0, height));
  if (height > door_height) {
    out->push_back(Rect::Wall(d0, d1, door_height, height - door_height));
  }
  if (p.frame_depth > 0.0) {
    // Jambs are the door frame's reveal: they occlude what lies beyond the door's edges.
    const Vector2d across(-dir.y() * 0.5 * p.frame_depth, dir.x() * 0.5 * p.frame_depth);
    out->push_back(Rect::Wall(d0 - across, d0 + across, 0.0, door_height));
    out->push_back(Rect::Wall(d1 + across, d1 - across, 0.0, door_height));
  }
}

// The wall a -> b (part of a counter-clockwise outer boundary, so the outside is on its right)
// with door recesses as HallwayLoopParams describes. The pieces follow the boundary in order:
// wall, jamb out, back wall, jamb in, wall, ...
void AddOuterWallWithRecesses(const Vector2d& a, const Vector2d& b, const HallwayLoopParams& p,
                              double height, std::vector<Rect>* out) {
  const double length = (b - a).norm();
  const Vector2d t = (b - a) / length;
  const Vector2d back = p.recess_depth * Vector2d(t.y(), -t.x());  // right of a -> b
  Vector2d from = a;
  if (p.recess_spacing > 0.0) {
    for (int k = 1;; ++k) {
      const double s0 = k * p.recess_spacing;
      const double s1 = s0 + p.recess_width;
      if (s1 > length - kRecessCornerClearance) break;
      if (s0 < kRecessCornerClearance) continue;
      const Vector2d d0 = a + s0 * t;
      const Vector2d d1 = a + s1 * t;
      out->push_back(Rect::Wall(from, d0, 0.0, height));
      out->push_back(Rect::Wall(d0, d0 + back, 0.0, height));
      out->push_back(Rect::Wall(d0 + back, d1 + back, 0.0, height));
      out->push_back(Rect::Wall(d1 + back, d1, 0.0, height));
      from = d1;
    }
  }
  out->push_back(Rect::Wall(from, b, 0.0, height));
}

}  // namespace

void AddStraightHallway(const StraightHallwayParams& p, double height, std::vector<Rect>* out) {
  const double h = 0.5 * p.width;
  const double x0 = p.start;
  const double x1 = p.start + p.length;
  out->push_back(Rect::Wall({x0, -h}, {x1, -h}, 0.0, height));
  out->push_back(Rect::Wall({x1, h}, {x0, h}, 0.0, height));
  if (p.closed_ends) {
    out->push_back(Rect::Wall({x1, -h}, {x1, h}, 0.0, height));
    out->push_back(Rect::Wall({x0, h}, {x0, -h}, 0.0, height));
  }
}

void AddHallwayLoop(const HallwayLoopParams& p, double height, std::vector<Rect>* out) {
  const double h = 0.5 * p.width;
  const Vector2d lo(-h, -h);
  const Vector2d hi = lo + p.size;
  const Vector2d c[4] = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
  for (int i = 0; i < 4; ++i) AddOuterWallWithRecesses(c[i], c[(i + 1) % 4], p, height, out);
  AddBox(lo + Vector2d(p.width, p.width), hi - Vector2d(p.width, p.width), height, out);
}

void AddOffice(const OfficeParams& p, double height, std::vector<Rect>* out) {
  const int nx = p.rooms.x();
  const int ny = p.rooms.y();
  const double w = p.room_size.x();
  const double h = p.room_size.y();
  const Vector2d lo(-0.5 * w, -0.5 * h);
  AddBox(lo, lo + Vector2d(nx * w, ny * h), height, out);
  // Walls between rooms, one piece per room side, each with a door in its middle.
  for (int i = 1; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      const Vector2d a = lo + Vector2d(i * w, j * h);
      AddWallWithDoor(a, a + Vector2d(0.0, h), p, height, out);
    }
  }
  for (int j = 1; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const Vector2d a = lo + Vector2d(i * w, j * h);
      AddWallWithDoor(a, a + Vector2d(w, 0.0), p, height, out);
    }
  }
}

void AddRandomClutter(int num_walls, int num_tilted, double extent, uint64_t seed,
                      std::vector<Rect>* out) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> pos(-0.5 * extent, 0.5 * extent);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  constexpr double kPi = 3.14159265358979323846;
  for (int i = 0; i < num_walls; ++i) {
    const Vector2d a(pos(rng), pos(rng));
    const double angle = 2.0 * kPi * unit(rng);
    const double length = 0.5 + 4.5 * unit(rng);
    const Vector2d b = a + length * Vector2d(std::cos(angle), std::sin(angle));
    const double base = unit(rng) < 0.7 ? 0.0 : 1.5 * unit(rng);
    const double height = 0.5 + 2.0 * unit(rng);
    out->push_back(Rect::Wall(a, b, base, height));
  }
  for (int i = 0; i < num_tilted; ++i) {
    Rect r;
    r.origin = Eigen::Vector3d(pos(rng), pos(rng), 2.0 * unit(rng));
    const Eigen::Vector3d axis =
        Eigen::Vector3d(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5).normalized();
    Eigen::Vector3d u = Eigen::Vector3d(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
    u = (0.5 + 2.0 * unit(rng)) * u.normalized();
    Eigen::Vector3d across = u.cross(axis);
    if (across.norm() < 1e-3 * u.norm()) across = u.cross(Eigen::Vector3d::UnitZ());
    if (across.norm() < 1e-3 * u.norm()) across = u.cross(Eigen::Vector3d::UnitX());
    const Eigen::Vector3d v = (0.5 + 2.0 * unit(rng)) * across.normalized();
    r.u = u;
    r.v = v;
    out->push_back(r);
  }
}

}  // namespace relplane::sim
