#include "relplane/mapper/backtracking.hpp"

#include <algorithm>
#include <cmath>

#include "relplane/mapper/global_map.hpp"
#include "relplane/mapper/relative_map.hpp"

namespace relplane::mapper {

int64_t MatchGlobal(const Observation& obs, const geometry::Pose2& pose, const MapperState& state,
                    const std::set<int64_t>& taken, const BacktrackOptions& options) {
  if (!options.enabled) return -1;
  const double alpha = geometry::WrapAngle(pose.yaw + obs.Alpha());
  const Eigen::Vector2d e0 = pose * obs.edge[0], e1 = pose * obs.edge[1];
  double best = -1.0;
  int64_t best_id = -1;
  for (const auto& [id, placed] : state.global) {
    // Only walls with a mapped edge: a bare line's extent is only as good as the pose was.
    if (taken.count(id) || placed.known != Known::kPoint) continue;
    const double dalpha = std::abs(geometry::WrapAngle(placed.alpha - alpha));
    if (dalpha > options.max_angle) continue;
    const Eigen::Vector2d n = NormalOf(placed.alpha), t = DirectionOf(placed.alpha);
    const double dist = std::abs(n.dot(0.5 * (e0 + e1) - placed.point));
    if (dist > options.max_distance) continue;
    // Overlap along the wall with the mapped extent, widened by a margin.
    const RltPlane* plane = state.planes.count(id) ? &state.planes.at(id) : nullptr;
    if (plane == nullptr) continue;
    {
      Eigen::Vector2d lo, hi;
      WallEnds(state, *plane, placed, &lo, &hi);
      // Sufficient overlap, as in §II.A: a collinear neighbour (the same wall on the other side
      // of a partition) must not match.
      // An end never seen static is only where the view or a nearer plane cut the wall when it
      // was mapped: the wall may go on behind it (a door recess's back wall, seen past the near
      // jamb on the way out and past the far jamb on the way back).
      bool known[2];
      known[placed.ref] = true;
      known[1 - placed.ref] = placed.has_other || plane->FullLengthKnown();
      const double m0 = t.dot(lo) - (known[0] ? options.margin : options.open_margin);
      const double m1 = t.dot(hi) + (known[1] ? options.margin : options.open_margin);
      const double o0 = std::min(t.dot(e0), t.dot(e1)), o1 = std::max(t.dot(e0), t.dot(e1));
      const double shorter = std::max(std::min(m1 - m0, o1 - o0), 1e-3);
      if (std::min(m1, o1) - std::max(m0, o0) < options.min_overlap * shorter) continue;
    }
    const double score = (1.0 - dalpha / options.max_angle) + (1.0 - dist / options.max_distance);
    if (score > best) best = score, best_id = id;
  }
  return best_id;
}

}  // namespace relplane::mapper
