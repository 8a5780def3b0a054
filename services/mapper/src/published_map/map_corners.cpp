#include "published_map/map_corners.hpp"

#include <cmath>
#include <limits>

#include "published_map/box_grid.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;

// Walls closer than PublishedMapOptions::min_corner_angle to parallel do not make a corner: where
// their lines cross moves far with a small error in either orientation.
//
// Only walls at least min_shortened_radii radii long are shortened, unless the crossing wall ends where
// they meet too (an L corner). A wall's last sample lies short of the corner, so a corner past
// the end is what sampling leaves; a corner inside the wall means its points reach past the
// other wall's line, which only noise explains, and on a short piece (a door jamb's 10-20 cm,
// fitted a few degrees off) a line crossing it is as likely another surface's as the corner. A
// crossing wall that ends there as well meets it in a corner: a sample of the segmenter's wall
// end estimate lands past a corner as often as short of it (a wall drawn from one sighting, 8 cm
// of it left in view, 1.5 cm past a room's corner). A short piece lying beside a crossing wall
// also has both its ends within reach of that wall's line: only the nearer end may move there.
// And by at most max_shortened_fraction of their length, from each end: a line through a wall's
// middle is not its corner (a door jamb crossing a thin partition's line at the door).

constexpr double kGridCell = 2.0;  // m: the spatial index's cell (speed only, not the result)

// The unit direction end[0] -> end[1] (along the line, either way, for a wall seen as a point).
Vector2d DirectionOf(const WallSegment& w) {
  const Vector2d span = w.end[1] - w.end[0];
  if (span.norm() > 1e-9) return span.normalized();
  return {-w.normal.y(), w.normal.x()};
}

// Where `wall`'s end `e` meets `other`'s line, as the signed distance along `wall`'s direction
// from that end; false when the walls are near parallel, the line is farther than `radius` or
// `other` does not reach the point (to within `radius`: its own end is sampled short too).
bool MeetingOffset(const WallSegment& wall, int e, const WallSegment& other, double radius,
                   double min_sine,
                   double* along) {
  const Vector2d t = DirectionOf(wall);
  const double sine = other.normal.dot(t);
  if (std::abs(sine) < min_sine) return false;
  const Vector2d& p = wall.end[e];
  *along = -(other.normal.dot(p) + other.d) / sine;
  if (std::abs(*along) > radius) return false;
  const Vector2d u = DirectionOf(other);
  const double s = u.dot(p + *along * t);
  const double s0 = u.dot(other.end[0]), s1 = u.dot(other.end[1]);
  return s >= std::min(s0, s1) - radius && s <= std::max(s0, s1) + radius;
}

// Does `wall` end within `radius` of `point`?
bool EndsNear(const WallSegment& wall, const Vector2d& point, double radius) {
  return (wall.end[0] - point).norm() <= radius || (wall.end[1] - point).norm() <= radius;
}

}  // namespace

int SnapSegmentEnds(std::vector<WallSegment>* walls, double radius,
                    const PublishedMapOptions& options) {
  const double min_sine = std::sin(options.min_corner_angle);
  if (!(radius > 0.0)) return 0;
  struct Move {
    size_t wall;
    int end;
    Vector2d step;
  };
  // A crossing wall reaches within `radius` of a meeting point within `radius` of the end.
  BoxGrid grid(kGridCell);
  for (size_t i = 0; i < walls->size(); ++i) {
    Eigen::AlignedBox2d box((*walls)[i].end[0]);
    box.extend((*walls)[i].end[1]);
    const Vector2d reach = Vector2d::Constant(radius);
    grid.Insert(i, Eigen::AlignedBox2d(box.min() - reach, box.max() + reach));
  }
  std::vector<Move> moves;
  for (size_t i = 0; i < walls->size(); ++i) {
    const WallSegment& wall = (*walls)[i];
    const double length = (wall.end[1] - wall.end[0]).norm();
    for (int e = 0; e < 2; ++e) {
      double best = std::numeric_limits<double>::infinity();
      const Vector2d reach = Vector2d::Constant(radius);
      for (size_t j : grid.Query(Eigen::AlignedBox2d(wall.end[e] - reach, wall.end[e] + reach))) {
        double along = 0.0;
        if (j == i || !MeetingOffset(wall, e, (*walls)[j], radius, min_sine, &along)) continue;
        const bool shortens = e == 0 ? along > 0.0 : along < 0.0;
        if (shortens && (std::abs(along) > options.max_shortened_fraction * length ||
                         (length < options.min_shortened_radii * radius &&
                          !EndsNear((*walls)[j], wall.end[e] + along * DirectionOf(wall),
                                    radius)))) {
          continue;
        }
        if (std::abs(along) < std::abs(best)) best = along;
      }
      if (std::isfinite(best)) moves.push_back({i, e, best * DirectionOf(wall)});
    }
  }
  for (const Move& move : moves) (*walls)[move.wall].end[move.end] += move.step;
  return static_cast<int>(moves.size());
}

int SnapEndsToCorners(std::vector<MappedPlane>* planes, double radius,
                      const PublishedMapOptions& options) {
  std::vector<WallSegment> walls;
  std::vector<size_t> index;  // planes[index[k]] is walls[k]
  for (size_t i = 0; i < planes->size(); ++i) {
    const MappedPlane& m = (*planes)[i];
    const double norm = m.normal.head<2>().norm();
    if (m.vertices.size() != 4 || norm < 0.9) continue;
    WallSegment w;
    w.normal = m.normal.head<2>() / norm;
    w.d = m.d / norm;  // d belongs to the 3D unit normal
    w.end[0] = m.vertices[0].head<2>();
    w.end[1] = m.vertices[1].head<2>();
    walls.push_back(w);
    index.push_back(i);
  }
  const int moved = SnapSegmentEnds(&walls, radius, options);
  for (size_t k = 0; k < walls.size(); ++k) {
    MappedPlane& m = (*planes)[index[k]];
    // Mapper::Map's order: lo bottom, hi bottom, hi top, lo top.
    m.vertices[0].head<2>() = m.vertices[3].head<2>() = walls[k].end[0];
    m.vertices[1].head<2>() = m.vertices[2].head<2>() = walls[k].end[1];
    m.centroid.head<2>() = 0.5 * (walls[k].end[0] + walls[k].end[1]);
  }
  return moved;
}

}  // namespace relplane::mapper
