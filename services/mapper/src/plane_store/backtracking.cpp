#include "plane_store/backtracking.hpp"

#include <algorithm>
#include <cmath>

#include "comparison/comparison.hpp"
#include "global_map/global_map.hpp"
#include "global_map/relative_map.hpp"

namespace relplane::mapper {

int64_t MatchGlobal(const Observation& obs, const geometry::Pose2& pose, const PlaneStore& store,
                    const Grouping& grouping, const WorldMap& world, const Trajectory& trajectory,
                    const std::set<int64_t>& taken, const BacktrackOptions& options) {
  if (!options.enabled) return -1;
  const double alpha = geometry::WrapAngle(pose.yaw + obs.Alpha());
  const Eigen::Vector2d e0 = pose * obs.edge[0], e1 = pose * obs.edge[1];
  double best = -1.0;
  bool best_placed = false;  // the best has a mapped end
  int64_t best_id = -1;
  for (const auto& [id, placed] : world.global) {
    // Walls with a mapped line at least: an orientation alone has no place to compare with.
    if (taken.count(id) || placed.known == Known::kAngle) continue;
    const double dalpha = std::abs(geometry::WrapAngle(placed.alpha - alpha));
    if (dalpha > options.max_angle) continue;
    // A wall known by its line only has no mapped end to hold the overlap test to: the sighting
    // must lie along it, to within a loop's heading error and its own fit's blur (a short
    // piece's). A piece 1 m long across a door recess's corner, fitted 8 degrees off, went to
    // the line of the recess's back wall (then known from a sliver 0.14 m away), and that wall
    // was mapped along the hallway, 13 cm off (hallway_loop_doors, σ = 1 cm, seed 11).
    if (placed.known == Known::kLine && dalpha > options.line_max_angle + PieceBlur(obs)) continue;
    // And only to close a loop, once the group that placed it is frozen (§II.F: its sightings
    // dropped). Sooner, the new sightings join the old ones in its comparisons: a recess's back
    // wall, seen as a sliver from the first leg, took a sighting from the corner 30 iterations
    // later, its static end was then found 5 cm short, and the pose along the next leg followed
    // it (hallway_out_and_back, σ = 1 cm, seed 119: ATE 0.016 → 0.029 m). As a new rltplane,
    // the end was found within 4 mm.
    if (placed.known == Known::kLine) {
      const auto by = world.placed_by.find(id);
      if (by == world.placed_by.end() || by->second < 0 ||
          by->second >= static_cast<int64_t>(grouping.groups.size()) ||
          !grouping.groups[static_cast<size_t>(by->second)].Frozen()) {
        continue;
      }
    }
    const Eigen::Vector2d n = NormalOf(placed.alpha), t = DirectionOf(placed.alpha);
    const double dist = std::abs(n.dot(0.5 * (e0 + e1) - placed.point));
    if (dist > options.max_distance) continue;
    // Overlap along the wall with the mapped extent, widened by a margin.
    const RltPlane* plane = store.planes.count(id) ? &store.planes.at(id) : nullptr;
    if (plane == nullptr) continue;
    {
      Eigen::Vector2d lo, hi;
      WallEnds(trajectory, *plane, placed, &lo, &hi);
      // A wall known by its line only is drawn as last seen, from the pose then: often a sliver
      // beside a door the sensor walked through. Its first sighting, from the pose then, shows
      // how far it reached. Without it the far part of a room's first wall, seen again at the
      // end of a loop through the office, matched nothing: it became a new wall placed from the
      // loop's drifted pose (4.9 cm off), and the loop never closed (office_other_sensor,
      // σ = 1 cm, seeds 110 and 132).
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
      // run on past the wall. From the start of office_other_sensor (σ = 1 cm, seed 115) it
      // crossed a door to the next corner (the segmenter joins the pieces either side through
      // the lintel), and widened by the open margin it took a sighting of the next room's wall
      // on that line at the end of the loop.
      bool known[2] = {true, true};
      if (placed.known == Known::kPoint) {
        known[1 - placed.ref] = placed.has_other || plane->FullLengthKnown();
      }
      const double m0 = t.dot(lo) - (known[0] ? options.margin : options.open_margin);
      const double m1 = t.dot(hi) + (known[1] ? options.margin : options.open_margin);
      const double o0 = std::min(t.dot(e0), t.dot(e1)), o1 = std::max(t.dot(e0), t.dot(e1));
      const double shorter = std::max(std::min(m1 - m0, o1 - o0), 1e-3);
      if (std::min(m1, o1) - std::max(m0, o0) < options.min_overlap * shorter) continue;
    }
    const double score = (1.0 - dalpha / options.max_angle) + (1.0 - dist / options.max_distance);
    // A wall with a mapped end wins over one known by its line only, whatever their scores: one
    // surface is often both, a recess's back wall first seen as a sliver (its line only) and
    // mapped again later from a static end. On the way back two sightings of it went to the
    // sliver; the back wall was then mapped a second time, and the first drawn 2 m long, past
    // the recess (hallway_loop_doors, σ = 1 cm, seed 37).
    const bool placed_end = placed.known == Known::kPoint;
    if (best_id < 0 || placed_end > best_placed || (placed_end == best_placed && score > best)) {
      best = score, best_placed = placed_end, best_id = id;
    }
  }
  return best_id;
}

}  // namespace relplane::mapper
