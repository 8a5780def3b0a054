#include "relplane/mapper/map_corners.hpp"

#include <cmath>
#include <limits>

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;

// Walls closer than this to parallel do not make a corner: where their lines cross moves far
// with a small error in either orientation.
const double kMinCornerSine = std::sin(30.0 * M_PI / 180.0);

// Only walls at least this many radii long are shortened. A wall's last sample lies short of
// the corner, so a corner past the end is what sampling leaves; a corner inside the wall means
// its points reach past the other wall's line, which only noise explains, and on a short piece
// (a door jamb's 10-20 cm, fitted a few degrees off) a line crossing it is as likely another
// surface's as the corner. A short piece lying beside a crossing wall also has both its ends
// within reach of that wall's line: only the nearer end may move there.
constexpr double kMinShortenedRadii = 2.0;
// ... and by at most this fraction of their length, from each end: a line through a wall's
// middle is not its corner (a door jamb crossing a thin partition's line at the door).
constexpr double kMaxShortenedFraction = 0.25;

Vector2d End(const MappedPlane& m, int e) { return m.vertices[e].head<2>(); }

bool IsWall(const MappedPlane& m) {
  return m.vertices.size() == 4 && m.normal.head<2>().norm() > 0.9;
}

// The unit direction lo -> hi (along the line, either way, for a wall drawn as a point).
Vector2d DirectionOf(const MappedPlane& m) {
  const Vector2d span = End(m, 1) - End(m, 0);
  if (span.norm() > 1e-9) return span.normalized();
  const Vector2d n = m.normal.head<2>().normalized();
  return {-n.y(), n.x()};
}

// Where `wall`'s end `e` meets `other`'s line, as the signed distance along `wall`'s direction
// from that end; false when the walls are near parallel, the line is farther than `radius` or
// `other` does not reach the point (to within `radius`: its own end is sampled short too).
bool MeetingOffset(const MappedPlane& wall, int e, const MappedPlane& other, double radius,
                   double* along) {
  const Vector2d t = DirectionOf(wall);
  const double norm = other.normal.head<2>().norm();
  const Vector2d n = other.normal.head<2>() / norm;
  const double sine = n.dot(t);
  if (std::abs(sine) < kMinCornerSine) return false;
  const Vector2d p = End(wall, e);
  // other's line: n . x + d = 0 for the unit 2D normal (d belongs to the 3D normal).
  *along = -(n.dot(p) + other.d / norm) / sine;
  if (std::abs(*along) > radius) return false;
  const Vector2d u = DirectionOf(other);
  const double s = u.dot(p + *along * t);
  const double s0 = u.dot(End(other, 0)), s1 = u.dot(End(other, 1));
  return s >= std::min(s0, s1) - radius && s <= std::max(s0, s1) + radius;
}

}  // namespace

int SnapEndsToCorners(std::vector<MappedPlane>* planes, double radius) {
  if (!(radius > 0.0)) return 0;
  struct Move {
    size_t wall;
    int end;
    Vector2d step;
  };
  std::vector<Move> moves;
  for (size_t i = 0; i < planes->size(); ++i) {
    const MappedPlane& wall = (*planes)[i];
    if (!IsWall(wall)) continue;
    const double length = (End(wall, 1) - End(wall, 0)).norm();
    for (int e = 0; e < 2; ++e) {
      double best = std::numeric_limits<double>::infinity();
      for (size_t j = 0; j < planes->size(); ++j) {
        double along = 0.0;
        if (j == i || !IsWall((*planes)[j]) ||
            !MeetingOffset(wall, e, (*planes)[j], radius, &along)) {
          continue;
        }
        const bool shortens = e == 0 ? along > 0.0 : along < 0.0;
        if (shortens && (length < kMinShortenedRadii * radius ||
                         std::abs(along) > kMaxShortenedFraction * length)) {
          continue;
        }
        if (std::abs(along) < std::abs(best)) best = along;
      }
      if (std::isfinite(best)) moves.push_back({i, e, best * DirectionOf(wall)});
    }
  }
  for (const Move& move : moves) {
    MappedPlane& wall = (*planes)[move.wall];
    // Mapper::Map's order: lo bottom, hi bottom, hi top, lo top.
    const int bottom = move.end == 0 ? 0 : 1, top = move.end == 0 ? 3 : 2;
    wall.vertices[bottom].head<2>() += move.step;
    wall.vertices[top].head<2>() += move.step;
    wall.centroid.head<2>() = 0.5 * (End(wall, 0) + End(wall, 1));
  }
  return static_cast<int>(moves.size());
}

}  // namespace relplane::mapper

