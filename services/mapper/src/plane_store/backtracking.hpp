#pragma once
// §II.A end: backtracking and closing the loop. A plane that matches no recent rltplane is
// transformed with the current position and compared to the global map before it becomes a new
// rltplane; on a match its observation joins the mapped rltplane.

#include <set>
#include <vector>

#include "global_map/world_map.hpp"
#include "grouping/group.hpp"
#include "motion/trajectory.hpp"
#include "plane_store/plane_store.hpp"
#include "relplane/common/geometry.hpp"
#include "relplane/mapper/options.hpp"

namespace relplane::mapper {

// The mapped rltplane `obs` (seen from `pose`) matches, or -1. Rltplanes in `taken` are skipped,
// and so is a wall that one of `others` (the frame's other planes) lies on nearer than `obs`.
int64_t MatchGlobal(const Observation& obs, const std::vector<const Observation*>& others,
                    const geometry::Pose2& pose, const PlaneStore& store, const Grouping& grouping,
                    const WorldMap& world, const Trajectory& trajectory,
                    const std::set<int64_t>& taken, const BacktrackOptions& options,
                    const FitOptions& fit);

}  // namespace relplane::mapper
