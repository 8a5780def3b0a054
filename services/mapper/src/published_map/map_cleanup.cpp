#include "published_map/map_cleanup.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "comparison/comparison.hpp"
#include "published_map/box_grid.hpp"
#include "published_map/map_corners.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;

constexpr double kGridCell = 2.0;  // m: the spatial index's cell (speed only, not the result)

Vector2d End(const MappedPlane& m, int e) { return m.vertices[e].head<2>(); }

// The wall's direction (lo -> hi).
Vector2d DirectionOf(const MappedPlane& m) {
  const Vector2d n = m.normal.head<2>();
  return {-n.y(), n.x()};
}

// The segmenter's fit of a short piece is only known to a few centimetres over its length
// (PieceBlur: a 0.2 m piece beside a door jamb takes some of the jamb's points, a median 2.4
// degrees off at 1 cm range noise, one in ten over 5 degrees; pieces over 1.2 m: 0.05 degrees).
bool OnLine(const MappedPlane& line, const MappedPlane& other, const PublishedMapOptions& options,
            const FitOptions& fit) {
  const double length = (End(other, 1) - End(other, 0)).norm();
  const double tolerance = std::max(options.merge_angle, PieceBlurOfLength(length, fit));
  if (line.normal.dot(other.normal) < std::cos(tolerance)) return false;
  const Vector2d n = line.normal.head<2>();
  for (int e = 0; e < 2; ++e) {
    if (std::abs(n.dot(End(other, e)) + line.d) >= options.merge_distance) return false;
  }
  return true;
}

// Does another wall reach `line`'s line between coordinates s0 < s1 along it?
bool GapCrossed(const std::vector<MappedPlane>& planes, const std::vector<bool>& drop, size_t li,
                size_t fi, double s0, double s1, const PublishedMapOptions& options) {
  const MappedPlane& line = planes[li];
  const Vector2d n = line.normal.head<2>(), t = DirectionOf(line);
  for (size_t k = 0; k < planes.size(); ++k) {
    if (k == li || k == fi || drop[k]) continue;
    const Vector2d p = End(planes[k], 0), q = End(planes[k], 1);
    const double dp = n.dot(p) + line.d, dq = n.dot(q) + line.d;
    // The point of segment k nearest the line: where it crosses, else its nearer end.
    Vector2d x = std::abs(dp) < std::abs(dq) ? p : q;
    if (dp * dq < 0.0) x = p + (q - p) * (dp / (dp - dq));
    if (std::abs(n.dot(x) + line.d) >= options.merge_distance) continue;
    const double s = t.dot(x);
    if (s > s0 - options.merge_distance && s < s1 + options.merge_distance) return true;
  }
  return false;
}

// Stretches `wall` along its line to cover [s0, s1]; an end that moves is no longer known.
void Extend(MappedPlane* wall, double s0, double s1, int64_t observations) {
  const Vector2d t = DirectionOf(*wall);
  const double lo = t.dot(End(*wall, 0)), hi = t.dot(End(*wall, 1));
  const double z0 = wall->vertices[0].z(), z1 = wall->vertices[2].z();
  const Vector2d a = End(*wall, 0) + (std::min(lo, s0) - lo) * t;
  const Vector2d b = End(*wall, 1) + (std::max(hi, s1) - hi) * t;
  if (s0 < lo) wall->end_known[0] = false;
  if (s1 > hi) wall->end_known[1] = false;
  wall->both_ends_known = wall->end_known[0] && wall->end_known[1];
  wall->vertices = {{a.x(), a.y(), z0}, {b.x(), b.y(), z0}, {b.x(), b.y(), z1}, {a.x(), a.y(), z1}};
  const Vector2d mid = 0.5 * (a + b);
  wall->centroid = Eigen::Vector3d(mid.x(), mid.y(), 0.5 * (z0 + z1));
  wall->observations += observations;
}

}  // namespace

void MergeDuplicateWalls(std::vector<MappedPlane>* planes_in, const PublishedMapOptions& options,
                         const FitOptions& fit) {
  std::vector<MappedPlane>& planes = *planes_in;
  std::vector<bool> drop(planes.size(), false);
  // A wall lying inside another on the same line is the same wall seen as a second rltplane
  // (§II.A end: a placed rltplane merged with a previous one); the wall is the one it lies in,
  // however many sightings each has (a wall's second rltplane, made from a sighting the
  // segmenter fitted 8 degrees off while turning in place, had one sighting more than the first
  // and lay inside it: both stayed on the map). Where each lies inside the other, the
  // better-observed one is kept.
  const auto inside = [&](const MappedPlane& a, const MappedPlane& b) {
    if (!OnLine(b, a, options, fit)) return false;
    const Vector2d t = DirectionOf(b);
    const double s0 = std::min(t.dot(End(b, 0)), t.dot(End(b, 1))) - options.merge_distance;
    const double s1 = std::max(t.dot(End(b, 0)), t.dot(End(b, 1))) + options.merge_distance;
    bool in = true;
    for (int e = 0; e < 2; ++e) in = in && t.dot(End(a, e)) >= s0 && t.dot(End(a, e)) <= s1;
    return in;
  };
  // b holds a only if a's ends lie within options.merge_distance of b's line and of b's extent
  // along it, so within b's box widened by twice that (a diagonal wall's box corners).
  const auto box_of = [](const MappedPlane& m, double margin) {
    Eigen::AlignedBox2d box(End(m, 0));
    box.extend(End(m, 1));
    return Eigen::AlignedBox2d(box.min() - Vector2d::Constant(margin),
                               box.max() + Vector2d::Constant(margin));
  };
  BoxGrid grid(kGridCell);
  for (size_t j = 0; j < planes.size(); ++j) {
    grid.Insert(j, box_of(planes[j], 2.0 * options.merge_distance));
  }
  std::vector<std::vector<size_t>> near(planes.size());  // for the first round below
  for (size_t i = 0; i < planes.size(); ++i) {
    const MappedPlane& a = planes[i];
    near[i] = grid.Query(box_of(a, 0.0));
    for (size_t j : near[i]) {
      if (drop[i]) break;
      const MappedPlane& b = planes[j];
      if (i == j || drop[j] || !inside(a, b)) continue;
      const bool a_better =
          a.observations > b.observations || (a.observations == b.observations && i < j);
      if (a_better && inside(b, a)) continue;
      drop[i] = true;
    }
  }
  // Two walls on the same line, facing the same way, that share most of the shorter one are one
  // surface seen as two rltplanes, the second made where registration and backtracking missed
  // the first (§II.A end): the better-observed one is stretched over the other and keeps the
  // other's end where that reaches further (otherwise a long side wall can be on the map twice,
  // millimetres apart). Less than half shared is left alone: two pieces either side of a door
  // frame may reach a little past it.
  // Walls stretched in one round are looked at again in the next, for walls they now share most
  // of; the grid holds each under every box it has had (a superset, as Query's is).
  std::vector<size_t> todo(planes.size());
  std::iota(todo.begin(), todo.end(), size_t{0});
  for (bool first = true; !todo.empty(); first = false) {
    std::vector<size_t> stretched;
    for (size_t i : todo) {
      for (size_t j : first ? near[i] : grid.Query(box_of(planes[i], 0.0))) {
        if (drop[i]) break;
        if (j == i || drop[j] || !OnLine(planes[i], planes[j], options, fit) ||
            !OnLine(planes[j], planes[i], options, fit)) {
          continue;
        }
        const bool i_better = planes[i].observations > planes[j].observations ||
                              (planes[i].observations == planes[j].observations && i < j);
        const size_t k = i_better ? i : j;
        MappedPlane& keep = planes[k];
        const MappedPlane& gone = planes[i_better ? j : i];
        const Vector2d t = DirectionOf(keep);
        const double lo = t.dot(End(keep, 0)), hi = t.dot(End(keep, 1));
        const double g0 = t.dot(End(gone, 0)), g1 = t.dot(End(gone, 1));
        const double shorter = std::min(hi - lo, g1 - g0);
        const double shared = std::min(hi, g1) - std::max(lo, g0);
        // Where they overlap in part, the two ends inside the shared stretch: one of each wall's.
        // Unless both were seen as wall ends, the two are one surface: a wall whose end there the
        // view cut saw the surface go on past the other's end, so that end, however static it
        // looked (§II.C), is none. Two ends both seen as wall ends that reach past each other
        // contradict each other: both walls stay.
        const bool both_ends = g0 < lo ? keep.end_known[0] && gone.end_known[1]
                                       : keep.end_known[1] && gone.end_known[0];
        if (shared <= std::max(options.merge_distance, 0.5 * shorter) &&
            !(!both_ends && shared > options.cut_overlap)) {
          continue;
        }
        Extend(&keep, g0, g1, gone.observations);
        if (g0 < lo) keep.end_known[0] = gone.end_known[0];
        if (g1 > hi) keep.end_known[1] = gone.end_known[1];
        keep.both_ends_known = keep.end_known[0] && keep.end_known[1];
        drop[i_better ? j : i] = true;
        grid.Insert(k, box_of(keep, 2.0 * options.merge_distance));
        stretched.push_back(k);
      }
    }
    std::sort(stretched.begin(), stretched.end());
    stretched.erase(std::unique(stretched.begin(), stretched.end()), stretched.end());
    todo = std::move(stretched);
  }
  // A piece known only by its line continues the nearest wall on its line that may go on
  // towards it (the facing end unknown) when nothing stands in the gap.
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t i = 0; i < planes.size(); ++i) {
      const MappedPlane& piece = planes[i];
      if (drop[i] || piece.end_known[0] || piece.end_known[1]) continue;
      size_t best = planes.size();
      double best_gap = std::numeric_limits<double>::infinity();
      for (size_t j = 0; j < planes.size(); ++j) {
        if (j == i || drop[j] || !OnLine(planes[j], piece, options, fit)) continue;
        const MappedPlane& wall = planes[j];
        const Vector2d t = DirectionOf(wall);
        const double lo = t.dot(End(wall, 0)), hi = t.dot(End(wall, 1));
        const double p0 = std::min(t.dot(End(piece, 0)), t.dot(End(piece, 1)));
        const double p1 = std::max(t.dot(End(piece, 0)), t.dot(End(piece, 1)));
        double gap = 0.0, g0 = 0.0, g1 = 0.0;
        if (p0 > hi) {
          if (wall.end_known[1]) continue;
          gap = p0 - hi, g0 = hi, g1 = p0;
        } else if (p1 < lo) {
          if (wall.end_known[0]) continue;
          gap = lo - p1, g0 = p1, g1 = lo;
        }
        if (gap >= best_gap || (gap > 0.0 && GapCrossed(planes, drop, j, i, g0, g1, options)))
          continue;
        best = j, best_gap = gap;
      }
      if (best == planes.size()) continue;
      const Vector2d t = DirectionOf(planes[best]);
      Extend(&planes[best], std::min(t.dot(End(piece, 0)), t.dot(End(piece, 1))),
             std::max(t.dot(End(piece, 0)), t.dot(End(piece, 1))), piece.observations);
      drop[i] = true;
      changed = true;
    }
  }
  std::vector<MappedPlane> kept;
  for (size_t i = 0; i < planes.size(); ++i) {
    if (!drop[i]) kept.push_back(std::move(planes[i]));
  }
  planes = std::move(kept);
}

void CleanUpWalls(std::vector<MappedPlane>* planes, const PublishedMapOptions& options,
                  const FitOptions& fit) {
  MergeDuplicateWalls(planes, options, fit);
  SnapEndsToCorners(planes, options.corner_radius, options);
  MergeDuplicateWalls(planes, options, fit);
}

}  // namespace relplane::mapper
