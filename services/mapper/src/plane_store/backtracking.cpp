#include "plane_store/backtracking.hpp"

#include <algorithm>
#include <cmath>

#include "comparison/comparison.hpp"
#include "global_map/global_map.hpp"
#include "global_map/relative_map.hpp"

namespace relplane::mapper {

namespace {

// The tests of §II.A for `obs` (seen from `pose`) against mapped wall `id`: its score, or a
// negative number where it fails them; `dist_out` is its distance from the mapped line.
double FitToMapped(const Observation& obs, const geometry::Pose2& pose, int64_t id,
                   const Placement& placed, const PlaneStore& store, const Grouping& grouping,
                   const WorldMap& world, const Trajectory& trajectory,
                   const BacktrackOptions& options, const FitOptions& fit, double* dist_out) {
  const double alpha = geometry::WrapAngle(pose.yaw + obs.Alpha());
  const Eigen::Vector2d e0 = pose * obs.edge[0], e1 = pose * obs.edge[1];
  // Walls with a mapped line at least: an orientation alone has no place to compare with.
  if (placed.known == Known::kAngle) return -1.0;
  const double dalpha = std::abs(geometry::WrapAngle(placed.alpha - alpha));
  if (dalpha > options.max_angle) return -1.0;
  // A wall known by its line only has no mapped end to hold the overlap test to (§II.A): the
  // sighting must lie along it, to within a loop's heading error and its own fit's blur (a short
  // piece's). Otherwise a short piece across a door recess's corner, fitted several degrees off,
  // can take the line of the recess's back wall (known from a sliver beside it), and that wall
  // is then mapped along the hallway from the piece.
  if (placed.known == Known::kLine && dalpha > options.line_max_angle + PieceBlur(obs, fit))
    return -1.0;
  // And only to close a loop, once the group that placed it is frozen (§II.F: its sightings
  // dropped). Sooner, the new sightings join the old ones in its comparisons (§II.C): a
  // recess's back wall seen as a sliver from one leg and again from the corner a little later
  // has its static end found short, and the pose along the next leg follows that end. As a new
  // rltplane, its comparisons find the end from the new sightings alone.
  if (placed.known == Known::kLine) {
    const auto by = world.placed_by.find(id);
    if (by == world.placed_by.end() || by->second < 0 ||
        by->second >= static_cast<int64_t>(grouping.groups.size()) ||
        !grouping.groups[static_cast<size_t>(by->second)].Frozen()) {
      return -1.0;
    }
  }
  const Eigen::Vector2d n = NormalOf(placed.alpha), t = DirectionOf(placed.alpha);
  const double dist = std::abs(n.dot(0.5 * (e0 + e1) - placed.point));
  if (dist > options.max_distance) return -1.0;
  // Overlap along the wall with the mapped extent, widened by a margin.
  const RltPlane* plane = store.planes.count(id) ? &store.planes.at(id) : nullptr;
  if (plane == nullptr) return -1.0;
  {
    Eigen::Vector2d lo, hi;
    WallEnds(trajectory, *plane, placed, &lo, &hi);
    // A wall known by its line only is drawn as last seen, from the pose then: often a sliver
    // beside a door the sensor walked through. Its first sighting, from the pose then, shows
    // how far it reached. Without it the far part of a room's first wall, seen again at the
    // end of a loop, matches nothing: it becomes a new wall placed from the loop's drifted
    // pose, and the loop never closes (§II.A, closing the loop).
    if (placed.known == Known::kLine && plane->first_seen.valid) {
      for (const Eigen::Vector2d& e : plane->first_seen.edge) {
        const double s = t.dot(e - lo);
        if (s < 0.0) lo += s * t;
        if (s > t.dot(hi - lo)) hi = lo + s * t;
      }
    }
    // Sufficient overlap, as in §II.A: a collinear neighbour (the same wall on the other side
    // of a partition) must not match.
    // An end never seen static is only where the view or a nearer plane cut the wall when it
    // was mapped: the wall may go on behind it (a door recess's back wall, seen past the near
    // jamb on the way out and past the far jamb on the way back). A bare line's extent is
    // what its sightings reached, widened by the margin only: the first sighting may already
    // run on past the wall, across a door to the next corner (the segmenter joins the pieces
    // either side through the lintel), and widened by the open margin as well it would take a
    // sighting of the next room's wall on that line.
    bool known[2] = {true, true};
    if (placed.known == Known::kPoint) {
      known[1 - placed.ref] = placed.has_other || plane->FullLengthKnown();
    }
    const double m0 = t.dot(lo) - (known[0] ? options.margin : options.open_margin);
    const double m1 = t.dot(hi) + (known[1] ? options.margin : options.open_margin);
    const double o0 = std::min(t.dot(e0), t.dot(e1)), o1 = std::max(t.dot(e0), t.dot(e1));
    const double shorter = std::max(std::min(m1 - m0, o1 - o0), 1e-3);
    if (std::min(m1, o1) - std::max(m0, o0) < options.min_overlap * shorter) return -1.0;
  }
  *dist_out = dist;
  return (1.0 - dalpha / options.max_angle) + (1.0 - dist / options.max_distance);
}

}  // namespace

int64_t MatchGlobal(const Observation& obs, const std::vector<const Observation*>& others,
                    const geometry::Pose2& pose, const PlaneStore& store, const Grouping& grouping,
                    const WorldMap& world, const Trajectory& trajectory,
                    const std::set<int64_t>& taken, const BacktrackOptions& options,
                    const FitOptions& fit) {
  if (!options.enabled) return -1;
  double best = -1.0;
  bool best_placed = false;  // the best has a mapped end
  int64_t best_id = -1;
  for (const auto& [id, placed] : world.global) {
    if (taken.count(id)) continue;
    double dist = 0.0;
    const double score =
        FitToMapped(obs, pose, id, placed, store, grouping, world, trajectory, options, fit, &dist);
    if (score < 0.0) continue;
    // One surface per mapped wall in a frame (§II.A): where another of this frame's planes lies
    // on the wall's line, nearer it by more than a line's noise, that one is the wall and this
    // one a parallel surface beside it, such as a doorway's jamb a quarter metre in from a
    // corridor's wall, within the distance bound a loop's drift needs. Whether the other plane
    // went to this wall or to another rltplane of it does not matter.
    bool nearer = false;
    for (const Observation* other : others) {
      double other_dist = 0.0;
      nearer = FitToMapped(*other, pose, id, placed, store, grouping, world, trajectory, options,
                           fit, &other_dist) >= 0.0 &&
               other_dist + options.same_surface < dist;
      if (nearer) break;
    }
    if (nearer) continue;
    // A wall with a mapped end wins over one known by its line only, whatever their scores: one
    // surface is often both, a recess's back wall first seen as a sliver (its line only) and
    // mapped again later from a static end. Were the sliver to take its sightings on the way
    // back, the back wall would be mapped a second time and the first drawn on past the recess.
    const bool placed_end = placed.known == Known::kPoint;
    if (best_id < 0 || placed_end > best_placed || (placed_end == best_placed && score > best)) {
      best = score, best_placed = placed_end, best_id = id;
    }
  }
  return best_id;
}

}  // namespace relplane::mapper
